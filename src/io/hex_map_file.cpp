#include "hex_slam/io/hex_map_file.h"

#include <cstring>
#include <fstream>
#include <ostream>
#include <vector>

#include "hex_slam/io/atomic_file.h"

namespace hex_slam {
namespace io {

namespace {

// 64-bit FNV-1a.
constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;

std::uint64_t FnvStep(std::uint64_t hash, char byte) {
  return (hash ^ static_cast<std::uint8_t>(byte)) * kFnvPrime;
}

}  // namespace

std::uint64_t HexMapChecksum(const std::string& bytes, std::size_t count) {
  std::uint64_t hash = kFnvOffset;
  for (std::size_t i = 0; i < count && i < bytes.size(); ++i) hash = FnvStep(hash, bytes[i]);
  return hash;
}

namespace {

constexpr char kMagic[8] = {'H', 'E', 'X', 'S', 'L', 'A', 'M', '\n'};
constexpr std::uint32_t kHexLatticeCode = 0;
constexpr std::uint32_t kSquareLatticeCode = 1;
// Spacings beyond these are not maps anyone builds; a value outside them is corruption.
constexpr double kMinSpacing = 1e-4;  // m
constexpr double kMaxSpacing = 1e3;   // m
constexpr std::size_t kHitRecordBytes = 16;  // u32 cell + 3 × f32


// Little-endian encoding whatever the host's byte order, streamed through a small buffer and
// hashed on the way (the checksum the file ends with): a large building's map with its submaps
// runs to hundreds of MB, which were held a second time in memory, as the file's bytes, while
// it was saved.
class Writer {
 public:
  explicit Writer(std::ostream* out) : out_(out), buffer_(kBufferBytes) {}
  void U32(std::uint32_t v) { Bytes(v, 4); }
  void I32(std::int32_t v) { Bytes(static_cast<std::uint32_t>(v), 4); }
  void U64(std::uint64_t v) { Bytes(v, 8); }
  void F32(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    U32(bits);
  }
  void F64(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    U64(bits);
  }
  void Raw(const char* data, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) Put(data[i]);
  }
  // Ends the file with the checksum of every byte before it.
  void Finish() {
    U64(hash_);
    Flush();
  }

 private:
  static constexpr std::size_t kBufferBytes = 1 << 16;
  void Bytes(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) Put(static_cast<char>((v >> (8 * i)) & 0xff));
  }
  void Put(char c) {
    hash_ = FnvStep(hash_, c);
    buffer_[size_++] = c;
    if (size_ == kBufferBytes) Flush();
  }
  void Flush() {
    out_->write(buffer_.data(), static_cast<std::streamsize>(size_));
    size_ = 0;
  }

  std::ostream* out_;
  std::vector<char> buffer_;
  std::size_t size_ = 0;
  std::uint64_t hash_ = kFnvOffset;
};

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  std::size_t remaining() const { return bytes_.size() - pos_; }
  std::size_t position() const { return pos_; }
  bool U32(std::uint32_t* v) {
    std::uint64_t x;
    if (!Bytes(4, &x)) return false;
    *v = static_cast<std::uint32_t>(x);
    return true;
  }
  bool I32(std::int32_t* v) {
    std::uint32_t x;
    if (!U32(&x)) return false;
    *v = static_cast<std::int32_t>(x);
    return true;
  }
  bool U64(std::uint64_t* v) { return Bytes(8, v); }
  bool F32(float* v) {
    std::uint32_t bits;
    if (!U32(&bits)) return false;
    std::memcpy(v, &bits, sizeof bits);
    return true;
  }
  bool F64(double* v) {
    std::uint64_t bits;
    if (!U64(&bits)) return false;
    std::memcpy(v, &bits, sizeof bits);
    return true;
  }
  bool Raw(std::size_t n, std::string* out) {
    if (remaining() < n) return false;
    out->assign(bytes_, pos_, n);
    pos_ += n;
    return true;
  }

 private:
  bool Bytes(int n, std::uint64_t* v) {
    if (remaining() < static_cast<std::size_t>(n)) return false;
    *v = 0;
    for (int i = 0; i < n; ++i) {
      *v |= static_cast<std::uint64_t>(static_cast<std::uint8_t>(bytes_[pos_ + i])) << (8 * i);
    }
    pos_ += n;
    return true;
  }
  const std::string& bytes_;
  std::size_t pos_ = 0;
};

std::string CheckModel(const OccupancyModel& m) {
  const bool finite = std::isfinite(m.free_delta) && std::isfinite(m.occupied_delta) &&
                      std::isfinite(m.min_log_odds) && std::isfinite(m.max_log_odds);
  if (!finite || !(m.free_delta < 0.0f) || !(m.occupied_delta > 0.0f) ||
      !(m.min_log_odds < 0.0f) || !(m.max_log_odds > 0.0f)) {
    return "bad occupancy model (need free_delta < 0 < occupied_delta, min < 0 < max, finite)";
  }
  return "";
}

std::string CheckRect(const GridRect& r) {
  if (r.width < 1 || r.height < 1) return "a level has an empty rectangle";
  if (static_cast<std::int64_t>(r.width) * r.height > kHexMapMaxCellsPerLevel) {
    return "a level has more than " + std::to_string(kHexMapMaxCellsPerLevel) + " cells";
  }
  if (std::abs(r.min.col) > kHexMapMaxAbsIndex || std::abs(r.min.row) > kHexMapMaxAbsIndex ||
      r.width > kHexMapMaxAbsIndex || r.height > kHexMapMaxAbsIndex) {
    return "a level's rectangle lies outside the supported index range";
  }
  return "";
}

// A hit mean lies inside its cell, within one spacing of the centre however the cell is shaped.
std::string CheckHits(const HexMapLevel& level, double spacing) {
  for (std::size_t i = 0; i < level.hits.size(); ++i) {
    const HexMapHit& h = level.hits[i];
    if (h.cell >= level.rect.size() || (i > 0 && h.cell <= level.hits[i - 1].cell)) {
      return "hit cells out of range or not in ascending order";
    }
    if (!(h.count > 0.0f && h.count <= GridMap<HexLattice>::kHitMemory)) {
      return "a hit count is NaN or outside (0, " +
             std::to_string(static_cast<int>(GridMap<HexLattice>::kHitMemory)) + "]";
    }
    if (!(std::abs(h.mean_x) <= spacing && std::abs(h.mean_y) <= spacing)) {
      return "a hit mean is NaN or outside its cell";
    }
  }
  return "";
}

bool FinitePose(const Pose2& p) {
  return std::abs(p.x) <= kHexMapMaxCoordinate && std::abs(p.y) <= kHexMapMaxCoordinate &&
         std::abs(p.theta) <= M_PI + 1e-9;  // NaN fails every comparison
}

std::string CheckGraph(const HexMapGraph& g) {
  const auto too_many = [](std::size_t n) { return static_cast<std::int64_t>(n) > kHexMapMaxGraphItems; };
  if (too_many(g.submaps.size()) || too_many(g.nodes.size()) || too_many(g.constraints.size())) {
    return "graph: more than " + std::to_string(kHexMapMaxGraphItems) + " submaps, nodes or constraints";
  }
  const std::size_t node_count = g.nodes.size();
  for (std::size_t i = 0; i < g.submaps.size(); ++i) {
    const HexMapSubmap& s = g.submaps[i];
    if (!FinitePose(s.local_pose) || !FinitePose(s.global_pose)) {
      return "graph: submap " + std::to_string(i) + " has a non-finite or far-off pose";
    }
    for (std::size_t k = 0; k < s.nodes.size(); ++k) {
      if (s.nodes[k] >= node_count || (k > 0 && s.nodes[k] <= s.nodes[k - 1])) {
        return "graph: submap " + std::to_string(i) + "'s nodes are unknown or not ascending";
      }
    }
  }
  for (std::size_t i = 0; i < node_count; ++i) {
    const HexMapNode& n = g.nodes[i];
    if (!std::isfinite(n.stamp) || !FinitePose(n.local_pose) || !FinitePose(n.global_pose)) {
      return "graph: node " + std::to_string(i) + " has a non-finite stamp or pose";
    }
    if (static_cast<std::int64_t>(n.points.size()) > kHexMapMaxNodePoints) {
      return "graph: node " + std::to_string(i) + " has too many points";
    }
    if (!(n.sensor_origin.cwiseAbs().maxCoeff() <= kHexMapMaxCoordinate)) {
      return "graph: node " + std::to_string(i) + " has a non-finite sensor origin";
    }
    for (const Eigen::Vector2f& p : n.points) {
      if (!(p.cwiseAbs().maxCoeff() <= kHexMapMaxCoordinate)) {
        return "graph: node " + std::to_string(i) + " has a non-finite point";
      }
    }
  }
  for (std::size_t i = 0; i < g.constraints.size(); ++i) {
    const mapping::Constraint& c = g.constraints[i];
    const bool tag_ok =
        c.tag == mapping::ConstraintTag::kLocal || c.tag == mapping::ConstraintTag::kLoop;
    if (c.submap < 0 || static_cast<std::size_t>(c.submap) >= g.submaps.size() || c.node < 0 ||
        static_cast<std::size_t>(c.node) >= node_count || !tag_ok || !FinitePose(c.relative) ||
        !(c.score >= 0.0 && c.score <= 1.0)) {
      return "graph: constraint " + std::to_string(i) +
             " joins unknown ids or has a bad tag, pose or score";
    }
  }
  return "";
}

void WritePose(const Pose2& p, Writer* w) {
  w->F64(p.x);
  w->F64(p.y);
  w->F64(p.theta);
}

bool ReadPose(Reader* r, Pose2* p) { return r->F64(&p->x) && r->F64(&p->y) && r->F64(&p->theta); }

void WriteGraph(const HexMapGraph& g, Writer* w) {
  w->U32(static_cast<std::uint32_t>(g.submaps.size()));
  for (const HexMapSubmap& s : g.submaps) {
    WritePose(s.local_pose, w);
    WritePose(s.global_pose, w);
    w->U32(static_cast<std::uint32_t>(s.nodes.size()));
    for (const std::uint32_t id : s.nodes) w->U32(id);
  }
  w->U32(static_cast<std::uint32_t>(g.nodes.size()));
  for (const HexMapNode& n : g.nodes) {
    w->F64(n.stamp);
    WritePose(n.local_pose, w);
    WritePose(n.global_pose, w);
    w->F32(n.sensor_origin.x());
    w->F32(n.sensor_origin.y());
    w->U32(static_cast<std::uint32_t>(n.points.size()));
    for (const Eigen::Vector2f& p : n.points) {
      w->F32(p.x());
      w->F32(p.y());
    }
  }
  w->U32(static_cast<std::uint32_t>(g.constraints.size()));
  for (const mapping::Constraint& c : g.constraints) {
    w->U32(static_cast<std::uint32_t>(c.submap));
    w->U32(static_cast<std::uint32_t>(c.node));
    WritePose(c.relative, w);
    w->U32(c.tag == mapping::ConstraintTag::kLoop ? 1 : 0);
    w->F32(static_cast<float>(c.score));
  }
}

// Smallest record sizes: a count read from the file is checked against the bytes left.
constexpr std::size_t kSubmapRecordBytes = 6 * 8 + 4;
constexpr std::size_t kNodeRecordBytes = 7 * 8 + 2 * 4 + 4;
constexpr std::size_t kConstraintRecordBytes = 4 + 4 + 3 * 8 + 4 + 4;

// Reads a count of records of at least `record_bytes` each; false (and `error` set) when the
// file cannot hold that many.
bool ReadCount(Reader* r, std::size_t record_bytes, const std::string& what, std::uint32_t* count,
               std::string* error) {
  if (!r->U32(count)) {
    *error = "truncated (graph's " + what + " count)";
    return false;
  }
  if (r->remaining() / record_bytes < *count) {
    *error = "truncated (graph claims " + std::to_string(*count) + " " + what + ")";
    return false;
  }
  return true;
}

std::string ReadGraph(Reader* r, HexMapGraph* g) {
  std::string error;
  std::uint32_t count = 0;
  if (!ReadCount(r, kSubmapRecordBytes, "submaps", &count, &error)) return error;
  g->submaps.resize(count);
  for (HexMapSubmap& s : g->submaps) {
    std::uint32_t k = 0;
    if (!ReadPose(r, &s.local_pose) || !ReadPose(r, &s.global_pose) ||
        !ReadCount(r, 4, "submap nodes", &k, &error)) {
      return error.empty() ? "truncated (in a submap)" : error;
    }
    s.nodes.resize(k);
    for (std::uint32_t& id : s.nodes) r->U32(&id);
  }
  if (!ReadCount(r, kNodeRecordBytes, "nodes", &count, &error)) return error;
  g->nodes.resize(count);
  for (HexMapNode& n : g->nodes) {
    std::uint32_t p = 0;
    if (!r->F64(&n.stamp) || !ReadPose(r, &n.local_pose) || !ReadPose(r, &n.global_pose) ||
        !r->F32(&n.sensor_origin.x()) || !r->F32(&n.sensor_origin.y()) ||
        !ReadCount(r, 8, "node points", &p, &error)) {
      return error.empty() ? "truncated (in a node)" : error;
    }
    if (static_cast<std::int64_t>(p) > kHexMapMaxNodePoints) return "graph: a node has too many points";
    n.points.resize(p);
    for (Eigen::Vector2f& q : n.points) {
      r->F32(&q.x());
      r->F32(&q.y());
    }
  }
  if (!ReadCount(r, kConstraintRecordBytes, "constraints", &count, &error)) return error;
  g->constraints.resize(count);
  for (mapping::Constraint& c : g->constraints) {
    std::uint32_t submap = 0, node = 0, tag = 0;
    float score = 0.0f;
    r->U32(&submap);
    r->U32(&node);
    ReadPose(r, &c.relative);
    r->U32(&tag);
    r->F32(&score);
    // Out-of-range ids and tags are caught by CheckGraph; these casts keep them out of range.
    c.submap = submap > static_cast<std::uint32_t>(kHexMapMaxGraphItems) ? -1 : static_cast<int>(submap);
    c.node = node > static_cast<std::uint32_t>(kHexMapMaxGraphItems) ? -1 : static_cast<int>(node);
    c.tag = tag == 1 ? mapping::ConstraintTag::kLoop : mapping::ConstraintTag::kLocal;
    if (tag > 1) c.submap = -1;
    c.score = score;
  }
  return "";
}

}  // namespace

HexMapGraph CaptureGraph(const mapping::PoseGraphSolution& solution) {
  HexMapGraph g;
  for (std::size_t i = 0; i < solution.submap_poses.size(); ++i) {
    HexMapSubmap s;
    s.local_pose = i < solution.submap_local_poses.size() ? solution.submap_local_poses[i] : Pose2();
    s.global_pose = solution.submap_poses[i];
    g.submaps.push_back(s);
  }
  for (std::size_t i = 0; i < solution.node_poses.size(); ++i) {
    const mapping::TrajectoryNode& node = *solution.nodes[i];
    HexMapNode n;
    n.stamp = node.stamp;
    n.local_pose = node.local_pose;
    n.global_pose = solution.node_poses[i];
    n.sensor_origin = node.sensor_origin.cast<float>();
    for (const Eigen::Vector2d& p : node.points) n.points.push_back(p.cast<float>());
    g.nodes.push_back(std::move(n));
  }
  g.constraints = solution.constraints;
  for (const mapping::Constraint& c : g.constraints) {
    if (c.tag == mapping::ConstraintTag::kLocal && c.submap < static_cast<int>(g.submaps.size())) {
      g.submaps[c.submap].nodes.push_back(static_cast<std::uint32_t>(c.node));
    }
  }
  return g;
}

std::string CheckHexMapData(const HexMapData& map) {
  if (map.lattice != "hex" && map.lattice != "square") {
    return "unknown lattice '" + map.lattice + "'";
  }
  if (!(map.spacing >= kMinSpacing && map.spacing <= kMaxSpacing)) {
    return "spacing " + std::to_string(map.spacing) + " m is outside [1e-4, 1e3]";
  }
  std::string error = CheckModel(map.model);
  if (!error.empty()) return error;
  if (map.levels.empty() || static_cast<int>(map.levels.size()) > kHexMapMaxLevels) {
    return "level count " + std::to_string(map.levels.size()) + " is outside [1, " +
           std::to_string(kHexMapMaxLevels) + "]";
  }
  for (std::size_t k = 0; k < map.levels.size(); ++k) {
    const HexMapLevel& level = map.levels[k];
    error = CheckRect(level.rect);
    if (!error.empty()) return "level " + std::to_string(k) + ": " + error;
    if (level.log_odds.size() != level.rect.size()) {
      return "level " + std::to_string(k) + ": cell count does not match its rectangle";
    }
    for (const float v : level.log_odds) {
      if (!(v >= map.model.min_log_odds && v <= map.model.max_log_odds)) {
        return "level " + std::to_string(k) + ": a log-odds value is NaN or outside the limits";
      }
    }
    error = CheckHits(level, map.spacing * std::pow(2.0, static_cast<double>(k)));
    if (!error.empty()) return "level " + std::to_string(k) + ": " + error;
  }
  return CheckGraph(map.graph);
}

std::string WriteHexMapFile(const std::string& path, const HexMapData& map) {
  AtomicFileSet file;
  AddHexMapFile(path, map, &file);
  return file.Commit();
}

void AddHexMapFile(const std::string& path, const HexMapData& map, AtomicFileSet* files) {
  const std::string invalid = CheckHexMapData(map);
  if (!invalid.empty()) return files->Fail("not writing " + path + ": " + invalid);
  files->Add(path, [&map](std::ostream& out) {
    Writer w(&out);
    w.Raw(kMagic, sizeof kMagic);
    w.U32(kHexMapFormatVersion);
    w.U32(map.lattice == "hex" ? kHexLatticeCode : kSquareLatticeCode);
    w.F64(map.spacing);
    w.F32(map.model.free_delta);
    w.F32(map.model.occupied_delta);
    w.F32(map.model.min_log_odds);
    w.F32(map.model.max_log_odds);
    w.U32(static_cast<std::uint32_t>(map.levels.size()));
    for (const HexMapLevel& level : map.levels) {
      w.I32(level.rect.min.col);
      w.I32(level.rect.min.row);
      w.I32(level.rect.width);
      w.I32(level.rect.height);
      for (const float v : level.log_odds) w.F32(v);
      w.U32(static_cast<std::uint32_t>(level.hits.size()));
      for (const HexMapHit& h : level.hits) {
        w.U32(h.cell);
        w.F32(h.mean_x);
        w.F32(h.mean_y);
        w.F32(h.count);
      }
    }
    WriteGraph(map.graph, &w);
    w.Finish();
  });
}

std::string ReadHexMapFile(const std::string& path, HexMapData* map) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot open " + path;
  // The largest file the caps allow: a header, then every level at its cap, every cell hit.
  constexpr std::int64_t kMaxFileBytes =
      4096 + kHexMapMaxLevels * (16 + 4 * kHexMapMaxCellsPerLevel + 4 +
                                 static_cast<std::int64_t>(kHitRecordBytes) *
                                     kHexMapMaxCellsPerLevel);
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) return "cannot read " + path;
  if (size > kMaxFileBytes) return path + ": file too large for a hex map";
  in.seekg(0, std::ios::beg);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (!in.read(&bytes[0], size)) return "cannot read " + path;
  return ParseHexMapFile(bytes, path, map);
}

std::string ParseHexMapFile(const std::string& bytes, const std::string& path, HexMapData* map) {
  const std::string where = path + ": ";
  const std::string truncated = where + "truncated";
  Reader r(bytes);
  std::string magic;
  if (!r.Raw(sizeof kMagic, &magic)) return truncated + " (no header)";
  if (magic != std::string(kMagic, sizeof kMagic)) return where + "not a hex map file (bad magic)";
  std::uint32_t version = 0, lattice = 0, level_count = 0;
  HexMapData data;
  if (!r.U32(&version)) return truncated;
  if (version < kHexMapOldestVersion || version > kHexMapFormatVersion) {
    return where + "format version " + std::to_string(version) + " is not supported (this build " +
           "reads versions " + std::to_string(kHexMapOldestVersion) + " to " +
           std::to_string(kHexMapFormatVersion) + ")";
  }
  if (!r.U32(&lattice) || !r.F64(&data.spacing) || !r.F32(&data.model.free_delta) ||
      !r.F32(&data.model.occupied_delta) || !r.F32(&data.model.min_log_odds) ||
      !r.F32(&data.model.max_log_odds) || !r.U32(&level_count)) {
    return truncated + " (in the header)";
  }
  if (lattice != kHexLatticeCode && lattice != kSquareLatticeCode) {
    return where + "unknown lattice code " + std::to_string(lattice);
  }
  data.lattice = lattice == kHexLatticeCode ? "hex" : "square";
  if (level_count < 1 || level_count > static_cast<std::uint32_t>(kHexMapMaxLevels)) {
    return where + "level count " + std::to_string(level_count) + " is outside [1, " +
           std::to_string(kHexMapMaxLevels) + "]";
  }
  for (std::uint32_t k = 0; k < level_count; ++k) {
    HexMapLevel level;
    if (!r.I32(&level.rect.min.col) || !r.I32(&level.rect.min.row) ||
        !r.I32(&level.rect.width) || !r.I32(&level.rect.height)) {
      return truncated + " (in level " + std::to_string(k) + "'s header)";
    }
    const std::string bad_rect = CheckRect(level.rect);
    if (!bad_rect.empty()) return where + "level " + std::to_string(k) + ": " + bad_rect;
    // Check the bytes exist before allocating for them.
    if (r.remaining() / 4 < level.rect.size()) {
      return truncated + " (level " + std::to_string(k) + " needs " +
             std::to_string(4 * level.rect.size()) + " bytes, " + std::to_string(r.remaining()) +
             " left)";
    }
    level.log_odds.resize(level.rect.size());
    for (float& v : level.log_odds) r.F32(&v);
    if (version >= 2) {
      std::uint32_t hit_count = 0;
      if (!r.U32(&hit_count)) return truncated + " (level " + std::to_string(k) + "'s hit count)";
      if (r.remaining() / kHitRecordBytes < hit_count) {
        return truncated + " (level " + std::to_string(k) + " claims " +
               std::to_string(hit_count) + " hit cells)";
      }
      level.hits.resize(hit_count);
      for (HexMapHit& h : level.hits) {
        r.U32(&h.cell);
        r.F32(&h.mean_x);
        r.F32(&h.mean_y);
        r.F32(&h.count);
      }
    }
    data.levels.push_back(std::move(level));
  }
  if (version >= 3) {
    const std::string graph_error = ReadGraph(&r, &data.graph);
    if (!graph_error.empty()) return where + graph_error;
  }
  const std::size_t hashed = r.position();
  std::uint64_t stored_hash = 0;
  if (!r.U64(&stored_hash)) return truncated + " (no checksum)";
  if (r.remaining() != 0) {
    return where + std::to_string(r.remaining()) + " unexpected trailing bytes";
  }
  if (stored_hash != HexMapChecksum(bytes, hashed)) return where + "checksum mismatch (corrupt)";
  const std::string invalid = CheckHexMapData(data);
  if (!invalid.empty()) return where + invalid;
  *map = std::move(data);
  return "";
}

HexMapData CaptureSlamMap(const Slam& slam) {
  HexMapData data =
      slam.hex_maps() ? CaptureHexMap(*slam.hex_maps()) : CaptureHexMap(*slam.square_maps());
  if (slam.loop_closure_active()) data.graph = CaptureGraph(*slam.solutions()->Get());
  return data;
}

std::string RestoreSlamMap(const HexMapData& data, Slam* slam) {
  const std::string error = slam->hex_maps() ? RestoreHexMap(data, slam->mutable_hex_maps())
                                             : RestoreHexMap(data, slam->mutable_square_maps());
  if (error.empty()) slam->UseLoadedMap();
  return error;
}

std::string LoadSlamMap(const std::string& path, Slam* slam) {
  HexMapData data;
  const std::string unreadable = ReadHexMapFile(path, &data);  // names the file itself
  if (!unreadable.empty()) return unreadable;
  const std::string error = RestoreSlamMap(data, slam);
  return error.empty() ? error : path + ": " + error;
}

}  // namespace io
}  // namespace hex_slam
