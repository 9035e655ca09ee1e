#include "hex_slam/io/hex_map_file.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"
#include "temp_dir.h"

namespace hex_slam {
namespace io {
namespace {

const Eigen::AlignedBox2d kExtent(Eigen::Vector2d(-1.0, -1.0), Eigen::Vector2d(1.0, 1.0));

template <class Lattice>
MapPyramid<Lattice> MakeMaps(double spacing = 0.1, int levels = 2) {
  return MapPyramid<Lattice>(spacing, levels, OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                             GridGrowthPolicy(), kExtent);
}

// A wall seen from two places, so cells hold several different log-odds values.
template <class Lattice>
MapPyramid<Lattice> MappedRoom() {
  MapPyramid<Lattice> maps = MakeMaps<Lattice>();
  std::vector<Eigen::Vector2d> wall;
  for (double y = -0.9; y <= 0.9; y += 0.03) wall.emplace_back(0.8, y);
  maps.InsertScan({0.0, 0.0}, wall);
  maps.InsertScan({-0.3, 0.2}, wall);
  return maps;
}

// A small loop-closure graph: two submaps, three nodes, local and loop constraints.
HexMapGraph SmallGraph() {
  HexMapGraph g;
  g.submaps.push_back({Pose2(0.0, 0.0, 0.0), Pose2(0.0, 0.0, 0.0), {0, 1}});
  g.submaps.push_back({Pose2(1.0, 0.5, 0.0), Pose2(1.01, 0.49, 0.002), {1, 2}});
  for (int i = 0; i < 3; ++i) {
    HexMapNode n;
    n.stamp = 10.0 + 0.2 * i;
    n.local_pose = Pose2(0.5 * i, 0.25 * i, 0.1 * i);
    n.global_pose = Pose2(0.5 * i + 0.01, 0.25 * i - 0.02, 0.1 * i + 0.003);
    n.sensor_origin = Eigen::Vector2f(0.1f, -0.05f);
    for (int k = 0; k < 5 + i; ++k) n.points.emplace_back(1.0f + 0.1f * k, -0.3f * k);
    g.nodes.push_back(n);
  }
  using mapping::ConstraintTag;
  g.constraints = {{0, 0, Pose2(0.0, 0.0, 0.0), ConstraintTag::kLocal, 0.0},
                   {0, 1, Pose2(0.5, 0.25, 0.1), ConstraintTag::kLocal, 0.0},
                   {1, 1, Pose2(-0.5, -0.25, 0.1), ConstraintTag::kLocal, 0.0},
                   {1, 2, Pose2(0.0, 0.0, 0.2), ConstraintTag::kLocal, 0.0},
                   {0, 2, Pose2(1.0, 0.5, 0.2), ConstraintTag::kLoop, 0.75}};
  return g;
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// The file's checksum, recomputed so tests can forge files that pass it and must fail later checks.
void Reseal(std::string* bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  const std::size_t body = bytes->size() - 8;
  for (std::size_t i = 0; i < body; ++i) {
    hash ^= static_cast<std::uint8_t>((*bytes)[i]);
    hash *= 1099511628211ull;
  }
  for (int i = 0; i < 8; ++i) (*bytes)[body + i] = static_cast<char>((hash >> (8 * i)) & 0xff);
}

void PutU32(std::string* bytes, std::size_t offset, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) (*bytes)[offset + i] = static_cast<char>((v >> (8 * i)) & 0xff);
}

// Offsets into the layout documented in hex_map_file.h.
constexpr std::size_t kVersionOffset = 8;
constexpr std::size_t kLevelCountOffset = 8 + 4 + 4 + 8 + 16;
constexpr std::size_t kFirstLevelOffset = kLevelCountOffset + 4;
constexpr std::size_t kFirstValueOffset = kFirstLevelOffset + 16;

template <class T>
class HexMapFileTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(HexMapFileTest, Lattices);

TYPED_TEST(HexMapFileTest, SaveLoadRestoreGivesTheSameCells) {
  testing_util::TempDir dir;
  const MapPyramid<TypeParam> maps = MappedRoom<TypeParam>();
  const std::string path = dir.File("room.hexmap");
  ASSERT_EQ(WriteHexMapFile(path, CaptureHexMap(maps)), "");
  HexMapData data;
  ASSERT_EQ(ReadHexMapFile(path, &data), "");
  EXPECT_EQ(data.lattice, TypeParam::kName);
  EXPECT_EQ(data.spacing, 0.1);
  EXPECT_EQ(data.model.free_delta, maps.level(0).model().free_delta);
  ASSERT_EQ(data.levels.size(), 2u);

  MapPyramid<TypeParam> back = MakeMaps<TypeParam>();
  ASSERT_EQ(RestoreHexMap(data, &back), "");
  for (int k = 0; k < maps.size(); ++k) {
    const GridMap<TypeParam>& a = maps.level(k);
    const GridMap<TypeParam>& b = back.level(k);
    EXPECT_EQ(b.rect().min, a.rect().min);
    EXPECT_EQ(b.rect().width, a.rect().width);
    EXPECT_EQ(b.rect().height, a.rect().height);
    EXPECT_EQ(b.log_odds_grid().values(), a.log_odds_grid().values());  // bit-exact
    // The hit records come back: the same cells, counts and means (the weighted terms are
    // recomputed from the probability, so the means agree to float rounding).
    ASSERT_FALSE(data.levels[k].hits.empty());
    int hit = 0;
    for (std::size_t i = 0; i < a.rect().size(); ++i) {
      const GridIndex index = a.rect().IndexAt(i);
      ASSERT_EQ(b.ProbabilityAt(index), a.ProbabilityAt(index)) << "cell " << i;
      const CellHits& ha = a.HitsAt(i);
      const CellHits& hb = b.HitsAt(i);
      EXPECT_EQ(hb.count, ha.count) << "cell " << i;
      EXPECT_EQ(hb.weight, ha.weight) << "cell " << i;
      EXPECT_NEAR(hb.Mean().x(), ha.Mean().x(), 1e-7) << "cell " << i;
      EXPECT_NEAR(hb.Mean().y(), ha.Mean().y(), 1e-7) << "cell " << i;
      hit += ha.count > 0.0f;
    }
    EXPECT_EQ(hit, static_cast<int>(data.levels[k].hits.size()));
  }
  // The map is really there: free before the wall, occupied on it.
  const GridMap<TypeParam>& fine = back.level(0);
  EXPECT_LT(fine.LogOdds(fine.lattice().CellOf({0.4, 0.0})), 0.0f);
  EXPECT_GT(fine.LogOdds(fine.lattice().CellOf({0.8, 0.0})), 0.0f);
  // Only the file is left: the atomic write removed its temporary.
  EXPECT_EQ(dir.Files(), std::vector<std::string>{"room.hexmap"});
}

TYPED_TEST(HexMapFileTest, RestoreRefusesAMapOfAnotherShape) {
  const HexMapData data = CaptureHexMap(MappedRoom<TypeParam>());
  MapPyramid<TypeParam> three_levels = MakeMaps<TypeParam>(0.1, 3);
  EXPECT_NE(RestoreHexMap(data, &three_levels).find("levels"), std::string::npos);
  MapPyramid<TypeParam> finer = MakeMaps<TypeParam>(0.05, 2);
  EXPECT_NE(RestoreHexMap(data, &finer).find("spacing"), std::string::npos);
  HexMapData other = data;
  other.lattice = std::string(TypeParam::kName) == "hex" ? "square" : "hex";
  MapPyramid<TypeParam> maps = MakeMaps<TypeParam>();
  EXPECT_NE(RestoreHexMap(other, &maps).find("not a"), std::string::npos);
  // A refused restore leaves the maps as they were (here: empty).
  EXPECT_TRUE(maps.level(0).KnownExtent().isEmpty());
}

class HexMapFileErrorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.File("m.hexmap");
    HexMapData data = CaptureHexMap(MappedRoom<HexLattice>());
    data.graph = SmallGraph();
    ASSERT_EQ(WriteHexMapFile(path_, data), "");
    good_ = ReadBytes(path_);
  }
  // Writes `bytes` and returns the reader's verdict; `data` must not change on error.
  std::string Load(const std::string& bytes) {
    WriteBytes(path_, bytes);
    HexMapData data;
    data.spacing = -7.0;  // a marker: an error must leave it alone
    const std::string error = ReadHexMapFile(path_, &data);
    if (!error.empty()) {
      EXPECT_EQ(data.spacing, -7.0) << "the reader changed its output on error: " << error;
    }
    return error;
  }

  testing_util::TempDir dir_;
  std::string path_;
  std::string good_;
};

TEST_F(HexMapFileErrorTest, MissingFileAndWrongMagic) {
  HexMapData data;
  EXPECT_NE(ReadHexMapFile(dir_.File("none.hexmap"), &data).find("cannot open"),
            std::string::npos);
  std::string bytes = good_;
  bytes[0] = 'P';  // e.g. a PGM given by mistake
  EXPECT_NE(Load(bytes).find("bad magic"), std::string::npos);
  EXPECT_NE(Load("").find("truncated"), std::string::npos);
}

TEST_F(HexMapFileErrorTest, UnsupportedVersion) {
  std::string bytes = good_;
  PutU32(&bytes, kVersionOffset, kHexMapFormatVersion + 1);
  EXPECT_NE(Load(bytes).find("version 4 is not supported"), std::string::npos);
  PutU32(&bytes, kVersionOffset, 0);
  EXPECT_NE(Load(bytes).find("version 0 is not supported"), std::string::npos);
}

// A version 1 file (no hit records) from this build's version 2 bytes: the hit blocks cut out.
std::string AsVersionOne(const std::string& v2, const HexMapData& data) {
  std::string v1 = v2.substr(0, kFirstLevelOffset);
  PutU32(&v1, kVersionOffset, 1);
  std::size_t at = kFirstLevelOffset;
  for (const HexMapLevel& level : data.levels) {
    const std::size_t cells = 16 + 4 * level.rect.size();
    v1 += v2.substr(at, cells);
    at += cells + 4 + 16 * level.hits.size();
  }
  v1 += std::string(8, '\0');  // the checksum, resealed below
  Reseal(&v1);
  return v1;
}

TEST_F(HexMapFileErrorTest, VersionOneFilesAreStillRead) {
  const HexMapData saved = CaptureHexMap(MappedRoom<HexLattice>());
  WriteBytes(path_, AsVersionOne(good_, saved));
  HexMapData data;
  ASSERT_EQ(ReadHexMapFile(path_, &data), "");
  ASSERT_EQ(data.levels.size(), saved.levels.size());
  for (std::size_t k = 0; k < saved.levels.size(); ++k) {
    EXPECT_EQ(data.levels[k].log_odds, saved.levels[k].log_odds);
    EXPECT_TRUE(data.levels[k].hits.empty());
  }
}

// A version 2 file: this build's bytes of the map without a graph, its (empty) graph cut out.
TEST_F(HexMapFileErrorTest, VersionTwoFilesAreStillRead) {
  const HexMapData saved = CaptureHexMap(MappedRoom<HexLattice>());
  ASSERT_EQ(WriteHexMapFile(path_, saved), "");
  std::string v2 = ReadBytes(path_);
  constexpr std::size_t kEmptyGraphBytes = 3 * 4;  // three zero counts
  v2.erase(v2.size() - 8 - kEmptyGraphBytes, kEmptyGraphBytes);
  PutU32(&v2, kVersionOffset, 2);
  Reseal(&v2);
  WriteBytes(path_, v2);
  HexMapData data;
  ASSERT_EQ(ReadHexMapFile(path_, &data), "");
  EXPECT_TRUE(data.graph.empty());
  ASSERT_EQ(data.levels.size(), saved.levels.size());
  for (std::size_t k = 0; k < saved.levels.size(); ++k) {
    EXPECT_EQ(data.levels[k].log_odds, saved.levels[k].log_odds);
    EXPECT_EQ(data.levels[k].hits.size(), saved.levels[k].hits.size());
  }
}

TEST_F(HexMapFileErrorTest, TheGraphComesBackAsItWasWritten) {
  HexMapData data;
  ASSERT_EQ(ReadHexMapFile(path_, &data), "");
  const HexMapGraph g = SmallGraph();
  ASSERT_EQ(data.graph.submaps.size(), g.submaps.size());
  ASSERT_EQ(data.graph.nodes.size(), g.nodes.size());
  ASSERT_EQ(data.graph.constraints.size(), g.constraints.size());
  for (std::size_t i = 0; i < g.submaps.size(); ++i) {
    EXPECT_EQ(data.graph.submaps[i].local_pose.x, g.submaps[i].local_pose.x);
    EXPECT_EQ(data.graph.submaps[i].global_pose.theta, g.submaps[i].global_pose.theta);
    EXPECT_EQ(data.graph.submaps[i].nodes, g.submaps[i].nodes);
  }
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    const HexMapNode& a = data.graph.nodes[i];
    const HexMapNode& b = g.nodes[i];
    EXPECT_EQ(a.stamp, b.stamp);
    EXPECT_EQ(a.local_pose.y, b.local_pose.y);
    EXPECT_EQ(a.global_pose.x, b.global_pose.x);
    EXPECT_EQ(a.sensor_origin, b.sensor_origin);
    EXPECT_EQ(a.points, b.points);
  }
  for (std::size_t i = 0; i < g.constraints.size(); ++i) {
    const mapping::Constraint& a = data.graph.constraints[i];
    const mapping::Constraint& b = g.constraints[i];
    EXPECT_EQ(a.submap, b.submap);
    EXPECT_EQ(a.node, b.node);
    EXPECT_EQ(a.tag, b.tag);
    EXPECT_EQ(a.relative.theta, b.relative.theta);
    EXPECT_FLOAT_EQ(a.score, b.score);
  }
}

TEST(HexMapGraphTest, ForgedGraphsAreRefused) {
  testing_util::TempDir dir;
  const auto refused = [&dir](const HexMapGraph& g) {
    HexMapData data = CaptureHexMap(MappedRoom<HexLattice>());
    data.graph = g;
    // The writer checks what the reader checks, so a forged graph is caught on both sides.
    return WriteHexMapFile(dir.File("g.hexmap"), data);
  };
  HexMapGraph g = SmallGraph();
  EXPECT_EQ(refused(g), "");
  g.submaps[1].nodes = {2, 1};
  EXPECT_NE(refused(g).find("not ascending"), std::string::npos);
  g = SmallGraph();
  g.submaps[0].nodes.push_back(7);
  EXPECT_NE(refused(g).find("unknown"), std::string::npos);
  g = SmallGraph();
  g.nodes[1].global_pose.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(refused(g).find("non-finite"), std::string::npos);
  g = SmallGraph();
  g.nodes[2].points[0].y() = std::numeric_limits<float>::infinity();
  EXPECT_NE(refused(g).find("non-finite point"), std::string::npos);
  g = SmallGraph();
  g.constraints[4].submap = 9;
  EXPECT_NE(refused(g).find("unknown ids"), std::string::npos);
  g = SmallGraph();
  g.constraints[4].score = 2.0;
  EXPECT_NE(refused(g).find("score"), std::string::npos);
}

TEST_F(HexMapFileErrorTest, GraphCountsBeyondTheFileAreRejectedBeforeAllocating) {
  // The graph follows the levels: find its submap count from the end, past the nodes and
  // constraints of SmallGraph.
  const HexMapGraph g = SmallGraph();
  std::size_t graph_bytes = 4 + 4 + 4 + 5 * 40;
  for (const HexMapSubmap& s : g.submaps) graph_bytes += 52 + 4 * s.nodes.size();
  for (const HexMapNode& n : g.nodes) graph_bytes += 68 + 8 * n.points.size();
  const std::size_t graph_start = good_.size() - 8 - graph_bytes;
  std::string bytes = good_;
  PutU32(&bytes, graph_start, 1u << 30);
  Reseal(&bytes);
  EXPECT_NE(Load(bytes).find("graph claims"), std::string::npos);
  bytes = good_;
  PutU32(&bytes, graph_start + 4 + 48, 0xffffffffu);  // the first submap's node count
  Reseal(&bytes);
  EXPECT_NE(Load(bytes).find("truncated"), std::string::npos);
}

TEST_F(HexMapFileErrorTest, BadHitRecordsAreRejectedEvenWithAValidChecksum) {
  const HexMapData saved = CaptureHexMap(MappedRoom<HexLattice>());
  const std::size_t first_hit = kFirstValueOffset + 4 * saved.levels[0].rect.size() + 4;
  ASSERT_GT(saved.levels[0].hits.size(), 1u);
  auto forged = [&](std::size_t field, std::uint32_t bits) {
    std::string bytes = good_;
    PutU32(&bytes, first_hit + field, bits);
    Reseal(&bytes);
    return Load(bytes);
  };
  EXPECT_NE(forged(0, 0xffffffu).find("hit cells"), std::string::npos);  // beyond the level
  EXPECT_NE(forged(16, saved.levels[0].hits[0].cell).find("ascending"), std::string::npos);
  float value = 0.0f;
  std::uint32_t bits;
  std::memcpy(&bits, &value, 4);
  EXPECT_NE(forged(12, bits).find("hit count"), std::string::npos);  // no hits
  value = 1.0f;  // 1 m from the centre of a 0.1 m cell
  std::memcpy(&bits, &value, 4);
  EXPECT_NE(forged(4, bits).find("outside its cell"), std::string::npos);
  std::string bytes = good_;
  PutU32(&bytes, first_hit - 4, 1u << 30);  // more hit records than bytes left
  EXPECT_NE(Load(bytes).find("truncated"), std::string::npos);
}

TEST_F(HexMapFileErrorTest, EveryTruncationIsRejected) {
  for (std::size_t length = 0; length < good_.size(); ++length) {
    const std::string error = Load(good_.substr(0, length));
    EXPECT_NE(error.find("truncated"), std::string::npos) << "length " << length << ": " << error;
  }
  EXPECT_EQ(Load(good_), "");
}

TEST_F(HexMapFileErrorTest, TrailingBytesAndFlippedBitsAreRejected) {
  EXPECT_NE(Load(good_ + "x").find("trailing"), std::string::npos);
  std::string bytes = good_;
  bytes[kFirstValueOffset + 5] ^= 0x10;  // a log-odds value, under the checksum
  EXPECT_NE(Load(bytes).find("checksum"), std::string::npos);
}

TEST_F(HexMapFileErrorTest, HugeSizesAreRejectedBeforeAllocating) {
  // A level claiming 2^14 x 2^14 cells (1 GiB) in a file of a few kilobytes.
  std::string bytes = good_;
  PutU32(&bytes, kFirstLevelOffset + 8, 1u << 14);
  PutU32(&bytes, kFirstLevelOffset + 12, 1u << 14);
  EXPECT_NE(Load(bytes).find("truncated"), std::string::npos);
  // Over the cap: rejected as such, whatever the file's length.
  PutU32(&bytes, kFirstLevelOffset + 8, 1u << 20);
  EXPECT_NE(Load(bytes).find("more than"), std::string::npos);
  bytes = good_;
  PutU32(&bytes, kFirstLevelOffset + 8, 0xffffffffu);  // width -1
  EXPECT_NE(Load(bytes).find("empty rectangle"), std::string::npos);
  bytes = good_;
  PutU32(&bytes, kLevelCountOffset, 1000);
  EXPECT_NE(Load(bytes).find("level count"), std::string::npos);
  PutU32(&bytes, kLevelCountOffset, 0);
  EXPECT_NE(Load(bytes).find("level count"), std::string::npos);
}

TEST_F(HexMapFileErrorTest, ValuesBreakingInvariantsAreRejectedEvenWithAValidChecksum) {
  std::string bytes = good_;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::uint32_t bits;
  std::memcpy(&bits, &nan, 4);
  PutU32(&bytes, kFirstValueOffset, bits);
  Reseal(&bytes);
  EXPECT_NE(Load(bytes).find("NaN or outside"), std::string::npos);
  bytes = good_;
  const float beyond = 1000.0f;  // past the log-odds limit of 50
  std::memcpy(&bits, &beyond, 4);
  PutU32(&bytes, kFirstValueOffset, bits);
  Reseal(&bytes);
  EXPECT_NE(Load(bytes).find("outside the limits"), std::string::npos);
  bytes = good_;
  PutU32(&bytes, 12, 7);  // lattice code
  Reseal(&bytes);
  EXPECT_NE(Load(bytes).find("lattice code"), std::string::npos);
}

// Seeded mutations (a poor man's fuzzer): whatever the damage, the reader returns an error or a
// map that satisfies every invariant; it never crashes or accepts garbage.
TEST_F(HexMapFileErrorTest, RandomDamageNeverYieldsAnInvalidMap) {
  int accepted = 0;
  for (int seed = 0; seed < 300; ++seed) {
    std::mt19937 rng(seed);
    std::string bytes = good_;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      bytes[rng() % bytes.size()] = static_cast<char>(rng() & 0xff);
    }
    if (seed % 3 == 0) Reseal(&bytes);  // get past the checksum to the invariant checks
    if (seed % 5 == 0) bytes.resize(rng() % bytes.size());
    WriteBytes(path_, bytes);
    HexMapData data;
    if (ReadHexMapFile(path_, &data).empty()) {
      ++accepted;
      EXPECT_EQ(CheckHexMapData(data), "") << "seed " << seed;
    }
  }
  // Resealed edits to log-odds values within the limits are valid maps; most damage is not.
  EXPECT_LT(accepted, 150);
}

TEST(HexMapFileWriteTest, InvalidDataAndUnwritablePathsAreErrors) {
  testing_util::TempDir dir;
  HexMapData data = CaptureHexMap(MappedRoom<HexLattice>());
  EXPECT_NE(WriteHexMapFile("/nonexistent/dir/m.hexmap", data), "");
  data.levels[0].log_odds.pop_back();
  EXPECT_NE(WriteHexMapFile(dir.File("m.hexmap"), data).find("does not match"), std::string::npos);
  data.levels.clear();
  EXPECT_NE(WriteHexMapFile(dir.File("m.hexmap"), data).find("level count"), std::string::npos);
  EXPECT_TRUE(dir.Files().empty());
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
