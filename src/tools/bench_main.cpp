// hex_slam_bench: the paper's simulated experiment (Duszak 2022, Table 1) for both lattices, offline
// and deterministic. Each row is a scenario (map, finest cell area, angle between the walls and
// the map axes, beams); each seed records one drive (lidar noise, optional odometry drift) that
// the hex and the square SLAM both process, at equal cell area. Prints the table in the paper's
// form with the paper's figures beside ours and the hex/square ratios, writes docs/benchmark.md,
// the maps with their trajectories (PNG), per-run data for the plots (CSV, TUM), runs
// scripts/plot_bench.py over them, and ends with one RESULT line.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "hex_slam/io/atomic_file.h"
#include "hex_slam/io/image_io.h"
#include "hex_slam/io/map_image.h"
#include "hex_slam/io/trajectory_io.h"
#include "hex_slam/sim/scenario.h"
#include "hex_slam/sim/scenario_run.h"
#include "hex_slam/mapping/slam.h"
#include "command_line.h"
#include "tool_main.h"

#ifndef HEX_SLAM_SOURCE_DIR
#define HEX_SLAM_SOURCE_DIR "."
#endif

namespace hex_slam {
namespace {

// What runs on every drive. The first two are the comparison the paper makes: hex_slam as
// shipped against hector_mapping's method. The last two are the ablation: the same method on
// both lattices, hector's (UseHectorsMethod: no sub-cell offsets) and hex_slam's (the defaults,
// with them), so the lattice's share of a difference can be told from the method's.
struct Variant {
  const char* name;
  const char* lattice;
  bool hectors_method;
};
constexpr Variant kVariants[] = {
    {"hex", "hex", false},                       // hex_slam's defaults
    {"square", "square", true},                  // hector_mapping's method
    {"hex_plain", "hex", true},                  // the paper's method
    {"square_subcell", "square", false},         // hex_slam's method on squares
};
constexpr int kVariantCount = sizeof(kVariants) / sizeof(kVariants[0]);
enum VariantIndex { kHex = 0, kSquare = 1, kHexPlain = 2, kSquareSubcell = 3 };
// Map figures are drawn for these variants.
constexpr int kFigureVariants[] = {kHex, kSquare};
constexpr int kDefaultSeeds = 3;
// The most seeds, scans or beams asked for: more is a typo, not a plan.
constexpr int kMaxCount = 1000000;
constexpr int kMinBeams = 3;  // the simulated lidar's least
// --quick: one short row, for the smoke test.
constexpr const char* kQuickRow = "maze/0.01/0/360";
constexpr int kQuickScans = 400;
// The goal for square over hex position RMSE on a row (the RESULT line counts the rows).
constexpr double kRatioGoal = 1.5;
// Map figures are drawn for these rows (first seed), when they run. Never for the robotcraft
// maze: a map of it is a copy of a bitmap we may use for testing but not publish.
const std::set<std::string> kFigureRows = {"maze/0.01/0/1000", "maze/0.01/45/1000",
                                           "rooms/0.01/0/1000"};
// Map figures: pixels per metre, and the overlay colours (truth green, estimate red).
constexpr double kFigurePixelsPerMetre = 100.0;
const io::Rgb kTruthColour = {40, 170, 60};
const io::Rgb kEstimateColour = {220, 40, 40};

struct Args {
  std::string rows = "paper";
  int seeds = kDefaultSeeds;
  bool quick = false;
  int max_scans = 0;  // 0: the whole drive
  bool odometry = false;
  bool plots = true;
  sim::ScenarioConditions conditions;  // --max-range-ghosts, --ghost-margin
  std::map<std::string, std::string> overrides;  // --set key=value, on every variant
  std::string out = "docs";
  std::string work = "out/bench";
  std::string worlds = std::string(HEX_SLAM_SOURCE_DIR) + "/worlds";
  std::string data = sim::DataDirectory(HEX_SLAM_SOURCE_DIR);
};

// The command line; the checks that need the rows' and parameters' names come after parsing
// (CheckArgs).
void Declare(CLI::App* app, Args* args) {
  app->description(
      "The paper's simulated experiment (Duszak 2022, Table 1) for both lattices, offline and "
      "deterministic: each seed records one drive that hex_slam (hex) and hector_mapping's method "
      "(square) both process at equal cell area. Prints the table beside the paper's figures and "
      "writes benchmark.md, the maps, per-run data and the plots.");
  app->footer(
      "Ends with: RESULT rows=... seeds=... mean_square_over_hex=... worst_row=... "
      "worst_square_over_hex=... rows_ratio_ge_1.5=... hex_below_paper=.../... "
      "mean_time_ratio=... mean_plain_ratio=... mean_subcell_ratio=... "
      "hex_position_rmse_first=... square_position_rmse_first=... elapsed_s=... (ratios: "
      "geometric means over the rows)");
  const auto text = [app](const std::string& name, std::string* value, const std::string& what) {
    return app->add_option(name, *value, what)->check(cli::NonEmpty());
  };
  text("--rows", &args->rows,
       "paper (default): the paper's six Table 1 rows on our maze and rooms worlds, and its five "
       "maze rows on the paper's own maze (robotcraft) when the data folder has it; all: every "
       "map x {0.01,0.04} m2 x {0,45,60} deg x {1000,360} beams; or a comma list of rows "
       "map/area/angle/beams, e.g. maze/0.04/45/360");
  app->add_option("--seeds", args->seeds,
                  "drives per row (default " + std::to_string(kDefaultSeeds) +
                      "): lidar noise and odometry drift differ per seed")
      ->check(CLI::Range(1, kMaxCount));
  app->add_flag("--quick", args->quick,
                std::string("one short row (") + kQuickRow + ", " + std::to_string(kQuickScans) +
                    " scans, 1 seed), for smoke tests");
  text("--out", &args->out, "where benchmark.md and figures/bench_*.png go (default docs)");
  text("--work", &args->work, "per-run data: results.csv, trajectories (default out/bench)");
  app->add_flag("--odometry", args->odometry,
                "give SLAM the drifting odometry as a prior (default: none, as the paper)");
  app->add_option("--max-scans", args->max_scans, "the drives' first scans only (default: all)")
      ->check(CLI::Range(1, kMaxCount));
  app->add_flag_callback("--no-plots", [args] { args->plots = false; },
                         "no scripts/plot_bench.py run");
  text("--worlds", &args->worlds, "the worlds folder (default: the source tree's)");
  text("--data", &args->data,
       "the data folder, for the robotcraft maze (default: HEX_SLAM_DATA_DIR, or beside the "
       "checkout)");
  app->add_flag("--max-range-ghosts", args->conditions.max_range_ghosts,
                "a faulty lidar: beams without a return read as hits at its maximum range less "
                "--ghost-margin, a ring that moves with it");
  cli::AddNumber(app, "--ghost-margin", &args->conditions.max_range_ghost_margin,
                 "m, below the maximum range (default 0)", 0.0);
  cli::AddSettings(app, "--set", &args->overrides,
                   "a SLAM parameter (the node's name) for every variant; hector's method then "
                   "resets its own (UseHectorsMethod)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);  // every --set, not the last
}

// --quick overrides what it covers, wherever it stands on the command line.
void ApplyQuick(Args* args) {
  if (!args->quick) return;
  args->rows = kQuickRow;
  args->seeds = 1;
  if (args->max_scans == 0) args->max_scans = kQuickScans;
}

// A row of the table: a scenario, and the paper's figures when the paper has that row.
struct Row {
  sim::ScenarioSpec spec;
  std::optional<sim::PaperRow> paper;
};

// The paper's rows are on "maze" (its robotcraft maze) and "rooms"; ours carry its figures both
// on our maze and on the robotcraft bitmap.
std::optional<sim::PaperRow> PaperFiguresFor(const sim::ScenarioSpec& spec) {
  for (const sim::PaperRow& p : sim::PaperTable1()) {
    const bool same_map = p.spec.map == spec.map || (p.spec.map == "maze" && spec.map == "robotcraft");
    if (same_map && p.spec.cell_area == spec.cell_area &&
        p.spec.start_angle_deg == spec.start_angle_deg && p.spec.beams == spec.beams) {
      return p;
    }
  }
  return std::nullopt;
}

bool ParsePositive(const std::string& text, int* out) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (*end != '\0' || v <= 0 || v > kMaxCount) return false;
  *out = static_cast<int>(v);
  return true;
}

bool ParseRowName(const std::string& name, sim::ScenarioSpec* spec) {
  std::istringstream in(name);
  std::string map, area, angle, beams;
  if (!std::getline(in, map, '/') || !std::getline(in, area, '/') ||
      !std::getline(in, angle, '/') || !std::getline(in, beams) || map.empty()) {
    return false;
  }
  char* end = nullptr;
  spec->map = map;
  spec->cell_area = std::strtod(area.c_str(), &end);
  if (*end != '\0' || !(spec->cell_area > 0.0)) return false;
  spec->start_angle_deg = std::strtod(angle.c_str(), &end);
  if (*end != '\0' || !std::isfinite(spec->start_angle_deg)) return false;
  return ParsePositive(beams, &spec->beams) && spec->beams >= kMinBeams;
}

// Rows on the robotcraft map need the data folder: they are dropped (with a note) without it.
std::string SelectRows(const std::string& list, bool have_robotcraft, std::vector<Row>* rows) {
  std::vector<sim::ScenarioSpec> specs;
  std::istringstream in(list);
  std::string token;
  while (std::getline(in, token, ',')) {
    if (token == "paper") {
      for (const sim::PaperRow& p : sim::PaperTable1()) specs.push_back(p.spec);
      for (const sim::PaperRow& p : sim::PaperTable1()) {
        if (p.spec.map != "maze") continue;
        sim::ScenarioSpec s = p.spec;
        s.map = "robotcraft";
        specs.push_back(s);
      }
    } else if (token == "all") {
      for (const char* map : {"maze", "rooms", "robotcraft"}) {
        for (double area : {0.01, 0.04}) {
          for (double angle : {0.0, 45.0, 60.0}) {
            for (int beams : {1000, 360}) specs.push_back({map, area, angle, beams});
          }
        }
      }
    } else {
      sim::ScenarioSpec s;
      if (!ParseRowName(token, &s)) {
        return "--rows: bad row '" + token + "' (want map/area/angle/beams)";
      }
      specs.push_back(s);
    }
  }
  int dropped = 0;
  for (const sim::ScenarioSpec& s : specs) {
    if (s.map == "robotcraft" && !have_robotcraft) {
      ++dropped;
      continue;
    }
    rows->push_back({s, PaperFiguresFor(s)});
  }
  if (dropped > 0) {
    std::printf("note: %d robotcraft rows skipped: the paper's maze bitmap is not in the data "
                "folder (set HEX_SLAM_DATA_DIR or --data)\n",
                dropped);
  }
  return rows->empty() ? "no rows to run" : "";
}

// Per lattice, over every seed of a row.
struct LatticeResult {
  std::vector<double> position_rmse, angle_rmse;  // per seed
  double position_max = 0.0;
  double angle_max = 0.0;
  std::vector<double> scan_ms;  // every scan of every seed
  int scans = 0, matched = 0;

  double MeanPositionRmse() const { return Mean(position_rmse); }
  double MeanAngleRmse() const { return Mean(angle_rmse); }
  static double Mean(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / v.size();
  }
};

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t i = std::min(values.size() - 1, static_cast<std::size_t>(q * values.size()));
  return values[i];
}

struct RowResult {
  Row row;
  LatticeResult runs[kVariantCount];  // by VariantIndex
  int scans_per_drive = 0;
  double drive_seconds = 0.0;  // simulated duration
  double drive_length = 0.0;   // m
};

std::string FileId(const sim::ScenarioSpec& spec) {
  std::string id = spec.Name();
  std::replace(id.begin(), id.end(), '/', '_');
  return id;
}

std::vector<io::StampedPose> Stamped(const std::vector<Pose2>& poses, double period) {
  std::vector<io::StampedPose> out;
  for (std::size_t i = 0; i < poses.size(); ++i) out.push_back({period * i, poses[i]});
  return out;
}

template <class Lattice>
std::string WriteMapFigure(const GridMap<Lattice>& grid, const std::vector<Pose2>& truth,
                           const std::vector<Pose2>& estimate, const std::string& path) {
  io::MapImageOptions options;
  options.pixels_per_metre = kFigurePixelsPerMetre;
  io::ImageFrame frame;
  io::Image image = io::RenderMap(grid, options, &frame);
  std::vector<Eigen::Vector2d> t, e;
  for (const Pose2& p : truth) t.push_back(p.translation());
  for (const Pose2& p : estimate) e.push_back(p.translation());
  io::DrawPolyline(frame, t, kTruthColour, 3, &image);
  io::DrawPolyline(frame, e, kEstimateColour, 1, &image);
  return io::WritePng(path, image);
}

std::string RunRow(const Row& row, const Args& args, RowResult* result) {
  sim::Scenario scenario;
  const sim::ScenarioFiles files{args.worlds, args.data};
  std::string error = sim::MakeScenario(row.spec, files, args.conditions, &scenario);
  if (!error.empty()) return error;
  if (args.max_scans > 0 && static_cast<int>(scenario.truth.size()) > args.max_scans) {
    scenario.truth.resize(args.max_scans);
  }
  result->row = row;
  result->scans_per_drive = static_cast<int>(scenario.truth.size());
  result->drive_seconds = scenario.scan_period * scenario.truth.size();
  for (std::size_t i = 1; i < scenario.truth.size(); ++i) {
    result->drive_length +=
        (scenario.truth[i].translation() - scenario.truth[i - 1].translation()).norm();
  }
  const std::string id = FileId(row.spec);
  std::ofstream per_scan;  // the first seed's per-scan errors, for the plots
  for (int seed = 1; seed <= args.seeds; ++seed) {
    const sim::RecordedDrive drive =
        sim::RecordDrive(scenario, static_cast<std::uint64_t>(seed), sim::OdometryNoise::Typical());
    for (int k = 0; k < kVariantCount; ++k) {
      const Variant& v = kVariants[k];
      SlamOptions options = sim::ScenarioSlamOptions(row.spec, v.lattice);
      SlamParameterTable(&options).Apply(args.overrides);  // each checked by CheckArgs
      if (v.hectors_method) UseHectorsMethod(&options.matcher);
      Slam slam(options);
      const sim::SlamRun run = sim::RunSlam(drive, args.odometry, &slam);
      const sim::TrajectoryError e = sim::CompareTrajectories(run.poses, drive.truth);
      LatticeResult& r = result->runs[k];
      r.position_rmse.push_back(e.position_rmse);
      r.angle_rmse.push_back(e.angle_rmse);
      r.position_max = std::max(r.position_max, e.position_max);
      r.angle_max = std::max(r.angle_max, e.angle_max);
      for (double t : run.scan_seconds) r.scan_ms.push_back(1e3 * t);
      r.scans += static_cast<int>(run.poses.size());
      r.matched += run.matched;
      if (seed != 1) continue;
      error = io::WriteTumTrajectory(args.work + "/" + id + "_" + v.name + ".tum",
                                     Stamped(run.poses, scenario.scan_period));
      const bool figure = kFigureRows.count(row.spec.Name()) &&
                          std::find(std::begin(kFigureVariants), std::end(kFigureVariants), k) !=
                              std::end(kFigureVariants);
      if (error.empty() && figure) {
        const std::string png = args.out + "/figures/bench_map_" + id + "_" + v.name + ".png";
        error = slam.hex_maps()
                    ? WriteMapFigure(slam.hex_maps()->level(0), drive.truth, run.poses, png)
                    : WriteMapFigure(slam.square_maps()->level(0), drive.truth, run.poses, png);
      }
      if (!error.empty()) return error;
    }
    if (seed == 1) {
      error = io::WriteTumTrajectory(args.work + "/" + id + "_truth.tum",
                                     Stamped(drive.truth, scenario.scan_period));
      if (!error.empty()) return error;
    }
  }
  return "";
}

// Column values of one row, shared by the terminal tables, the markdown and the CSV.
struct RowFigures {
  std::string name, test;
  double pos[kVariantCount], ang[kVariantCount], max[kVariantCount];
  double median_ms[kVariantCount], p99_ms[kVariantCount];
  double paper_pos[2] = {0, 0}, paper_ang[2] = {0, 0};  // hex, hector
  bool has_paper = false;
  // Position RMSE ratios, square over hex: > 1 means hex is better.
  double square_over_hex = 0.0;    // hector's method over hex_slam (the paper's comparison)
  double plain_ratio = 0.0;        // same method (no sub-cell) on both lattices
  double subcell_ratio = 0.0;      // same method (sub-cell) on both lattices
  double time_ratio = 0.0;         // hex_slam over hector's method, median per-scan time
  double plain_time_ratio = 0.0;   // hex over square, both without sub-cell
  double subcell_time_ratio = 0.0; // hex over square, both with sub-cell
};

double Ratio(double a, double b) { return b > 0.0 ? a / b : 0.0; }

RowFigures Figures(const RowResult& r) {
  RowFigures f;
  f.name = r.row.spec.Name();
  f.test = r.row.paper ? std::to_string(r.row.paper->test) : "-";
  for (int k = 0; k < kVariantCount; ++k) {
    const LatticeResult& l = r.runs[k];
    f.pos[k] = l.MeanPositionRmse();
    f.ang[k] = l.MeanAngleRmse();
    f.max[k] = l.position_max;
    f.median_ms[k] = Percentile(l.scan_ms, 0.5);
    f.p99_ms[k] = Percentile(l.scan_ms, 0.99);
  }
  if (r.row.paper) {
    f.has_paper = true;
    f.paper_pos[0] = r.row.paper->hex_position;
    f.paper_pos[1] = r.row.paper->square_position;
    f.paper_ang[0] = r.row.paper->hex_angle;
    f.paper_ang[1] = r.row.paper->square_angle;
  }
  f.square_over_hex = Ratio(f.pos[kSquare], f.pos[kHex]);
  f.plain_ratio = Ratio(f.pos[kSquare], f.pos[kHexPlain]);
  f.subcell_ratio = Ratio(f.pos[kSquareSubcell], f.pos[kHex]);
  f.time_ratio = Ratio(f.median_ms[kHex], f.median_ms[kSquare]);
  f.plain_time_ratio = Ratio(f.median_ms[kHexPlain], f.median_ms[kSquare]);
  f.subcell_time_ratio = Ratio(f.median_ms[kHex], f.median_ms[kSquareSubcell]);
  return f;
}

std::string Fmt(double v, int precision = 4) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(precision) << v;
  return s.str();
}

std::string Sci(double v) {
  std::ostringstream s;
  s << std::scientific << std::setprecision(1) << v;
  return s.str();
}

std::string Timing(const RowFigures& f, int k) {
  return Fmt(f.median_ms[k], 3) + "/" + Fmt(f.p99_ms[k], 3);
}

// The two tables as rows of cells; the terminal and the markdown lay them out.
using Table = std::vector<std::vector<std::string>>;

Table MainTable(const std::vector<RowFigures>& rows) {
  Table t = {{"test", "map/area m²/angle °/beams", "pos hex", "pos square", "square/hex",
              "paper hex", "paper hector", "angle hex", "angle square", "paper hex",
              "paper hector", "max hex", "max square", "ms hex med/p99", "ms square med/p99",
              "time hex/square"}};
  for (const RowFigures& f : rows) {
    const auto paper = [&](double v, bool sci) {
      return f.has_paper ? (sci ? Sci(v) : Fmt(v)) : std::string("–");
    };
    t.push_back({f.test, f.name, Fmt(f.pos[kHex]), Fmt(f.pos[kSquare]),
                 Fmt(f.square_over_hex, 2), paper(f.paper_pos[0], false),
                 paper(f.paper_pos[1], false), Sci(f.ang[kHex]), Sci(f.ang[kSquare]),
                 paper(f.paper_ang[0], true), paper(f.paper_ang[1], true), Fmt(f.max[kHex]),
                 Fmt(f.max[kSquare]), Timing(f, kHex), Timing(f, kSquare),
                 Fmt(f.time_ratio, 2)});
  }
  return t;
}

Table AblationTable(const std::vector<RowFigures>& rows) {
  Table t = {{"map/area m²/angle °/beams", "hex plain", "square plain", "square/hex",
              "hex sub-cell", "square sub-cell", "square/hex", "ms hex/square plain",
              "ms hex/square sub-cell"}};
  for (const RowFigures& f : rows) {
    t.push_back({f.name, Fmt(f.pos[kHexPlain]), Fmt(f.pos[kSquare]), Fmt(f.plain_ratio, 2),
                 Fmt(f.pos[kHex]), Fmt(f.pos[kSquareSubcell]), Fmt(f.subcell_ratio, 2),
                 Fmt(f.median_ms[kHexPlain], 3) + "/" + Fmt(f.median_ms[kSquare], 3),
                 Fmt(f.median_ms[kHex], 3) + "/" + Fmt(f.median_ms[kSquareSubcell], 3)});
  }
  return t;
}

// Display width in characters (the headers hold ² and °, two bytes each in UTF-8).
std::size_t Width(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
}

void PrintTable(const Table& t) {
  std::vector<std::size_t> widths(t.front().size(), 0);
  for (const auto& row : t) {
    for (std::size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], Width(row[c]));
  }
  for (const auto& row : t) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      line += row[c] + std::string(widths[c] - Width(row[c]) + 2, ' ');
    }
    std::printf("%s\n", line.c_str());
  }
}

void WriteMarkdownTable(const Table& t, std::ostream& out) {
  for (std::size_t r = 0; r < t.size(); ++r) {
    out << "|";
    for (const std::string& cell : t[r]) out << " " << cell << " |";
    out << "\n";
    if (r == 0) {
      out << "|";
      for (std::size_t c = 0; c < t[r].size(); ++c) out << "---|";
      out << "\n";
    }
  }
}

std::string WriteCsv(const std::string& path, const std::vector<RowFigures>& rows) {
  return io::WriteFileAtomically(path, [&](std::ostream& out) {
    out << "row,test,paper_hex_position,paper_square_position,paper_hex_angle,paper_square_angle";
    for (const Variant& v : kVariants) {
      for (const char* field : {"position_rmse", "angle_rmse", "position_max", "median_ms",
                                "p99_ms"}) {
        out << ',' << v.name << '_' << field;
      }
    }
    out << ",square_over_hex,plain_ratio,subcell_ratio,time_ratio\n" << std::setprecision(6);
    for (const RowFigures& f : rows) {
      out << f.name << ',' << f.test << ',' << f.paper_pos[0] << ',' << f.paper_pos[1] << ','
          << f.paper_ang[0] << ',' << f.paper_ang[1];
      for (int k = 0; k < kVariantCount; ++k) {
        out << ',' << f.pos[k] << ',' << f.ang[k] << ',' << f.max[k] << ',' << f.median_ms[k]
            << ',' << f.p99_ms[k];
      }
      out << ',' << f.square_over_hex << ',' << f.plain_ratio << ',' << f.subcell_ratio << ','
          << f.time_ratio << '\n';
    }
  });
}

// benchmark.md keeps its prose: the bench rewrites only what lies between these two lines (the
// whole file when it has none).
constexpr const char* kBeginMarker = "<!-- hex_slam_bench: begin -->";
constexpr const char* kEndMarker = "<!-- hex_slam_bench: end -->";

std::string GeneratedSection(const std::vector<RowFigures>& rows,
                             const std::vector<RowResult>& results, const Args& args,
                             const std::string& command, double elapsed_s) {
  std::ostringstream out;
  const sim::ScenarioConditions& c = args.conditions;
  out << kBeginMarker << "\n<!-- Generated by `" << command << "` (" << Fmt(elapsed_s, 0)
      << " s); rerun it rather than editing. -->\n\n"
      << "Both lattices process the same recorded scans at equal cell area (hex centre spacing "
      << "d = s·sqrt(2/sqrt(3))) with the default SLAM options"
      << (args.odometry ? " and the drifting odometry as a prior" : " and no odometry")
      << "; **hex** is hex_slam as shipped (its defaults: sub-cell offsets on), **square** is "
      << "hector_mapping's method (UseHectorsMethod: no sub-cell offsets, every step verified, "
      << "one angle tolerance on all levels). Means over " << args.seeds
      << " seed(s) per row; the largest error is the worst over all seeds; times are per scan "
      << "over every scan of every seed. Conditions: " << Fmt(c.scan_rate, 0)
      << " Hz scans over 360°, " << Fmt(c.linear_speed, 2) << " m/s, "
      << Fmt(c.angular_speed, 2) << " rad/s turning in place, " << Fmt(100 * c.range_noise, 0)
      << " cm Gaussian range noise, ranges " << Fmt(c.range_min, 2) << "–" << Fmt(c.range_max, 0)
      << " m"
      << (c.max_range_ghosts ? "; beams without a return read as hits at " +
                                   Fmt(c.range_max - c.max_range_ghost_margin, 2) + " m (ghosts)"
                             : std::string())
      << ". Positions in m, angles in rad, times in ms.\n\n";
  WriteMarkdownTable(MainTable(rows), out);
  out << "\n**The same method on both lattices.** plain: hector's method (the paper's matcher on "
      << "hex, hector's on square); sub-cell: hex_slam's (the defaults) on both.\n\n";
  WriteMarkdownTable(AblationTable(rows), out);
  out << "\nDrives:";
  std::set<std::string> described;
  for (const RowResult& r : results) {
    if (!described.insert(r.row.spec.map).second) continue;
    out << (described.size() > 1 ? ";" : "") << " " << r.row.spec.map << " " << r.scans_per_drive
        << " scans, " << Fmt(r.drive_length, 1) << " m, " << Fmt(r.drive_seconds, 0) << " s";
  }
  out << ".\n" << kEndMarker;
  return out.str();
}

std::string WriteMarkdown(const std::string& path, const std::string& section) {
  std::string text;
  {
    std::ifstream in(path);
    if (in) text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::size_t begin = text.find(kBeginMarker);
  const std::size_t end = begin == std::string::npos ? begin : text.find(kEndMarker, begin);
  if (end == std::string::npos) {
    text = "# hex vs square: the paper's simulated experiment\n\n" + section + "\n";
  } else {
    text.replace(begin, end + std::string(kEndMarker).size() - begin, section);
  }
  return io::WriteFileAtomically(path, [&](std::ostream& out) { out << text; });
}

std::string CommandLine(int argc, char** argv) {
  std::string s = "hex_slam_bench";
  for (int i = 1; i < argc; ++i) s += std::string(" ") + argv[i];
  return s;
}

// Empty, or what is wrong with the options taken together or with the names they give; the rows
// to run in `rows`.
std::string CheckArgs(const Args& args, std::vector<Row>* rows) {
  const sim::ScenarioConditions& c = args.conditions;
  if (c.max_range_ghost_margin >= c.range_max) {
    return "--ghost-margin: must be below the lidar's maximum range, " + Fmt(c.range_max, 1) +
           " m";
  }
  SlamOptions probe;
  const std::vector<std::string> errors = SlamParameterTable(&probe).Apply(args.overrides);
  if (!errors.empty()) return "--set: " + errors.front();
  const bool have_robotcraft =
      std::filesystem::exists(args.data + "/robotcraft_maze/540x540-90cm.png");
  return SelectRows(args.rows, have_robotcraft, rows);
}

// Runs every row, printing each as it finishes. Returns an error naming the row that failed.
std::string RunRows(const std::vector<Row>& rows, const Args& args,
                    std::vector<RowResult>* results) {
  for (const Row& row : rows) {
    RowResult result;
    const auto t0 = std::chrono::steady_clock::now();
    const std::string error = RunRow(row, args, &result);
    if (!error.empty()) return row.spec.Name() + ": " + error;
    const RowFigures f = Figures(result);
    std::printf("  %-24s hex %.4f m  square %.4f m  hex plain %.4f m  square sub-cell %.4f m  "
                "(%.1f s)\n",
                f.name.c_str(), f.pos[kHex], f.pos[kSquare], f.pos[kHexPlain],
                f.pos[kSquareSubcell],
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    std::fflush(stdout);
    results->push_back(std::move(result));
  }
  return "";
}

// scripts/plot_bench.py over the figure rows; a failure costs the plots, not the table.
void Plot(const std::vector<RowResult>& results, const Args& args) {
  std::string plotted;
  for (const RowResult& r : results) {
    if (!kFigureRows.count(r.row.spec.Name())) continue;
    plotted += (plotted.empty() ? "" : ",") + FileId(r.row.spec);
  }
  const std::string script = std::string(HEX_SLAM_SOURCE_DIR) + "/scripts/plot_bench.py";
  const std::string command = "/usr/bin/python3 '" + script + "' --work '" + args.work +
                              "' --figures '" + args.out + "/figures' --rows '" + plotted + "'";
  std::fflush(stdout);  // the script's output after ours
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "warning: the plots failed (%s); the table is complete\n",
                 command.c_str());
  }
}

// The RESULT line: geometric means of the ratios over rows, the worst row, and the goal counts.
void PrintResult(const std::vector<RowFigures>& figures, const Args& args, double elapsed) {
  double log_ratio = 0.0, log_time = 0.0, log_plain = 0.0, log_subcell = 0.0;
  const RowFigures* worst = &figures.front();
  int beats_paper = 0, with_paper = 0, ratio_goal = 0;
  const auto log_of = [](double v) { return std::log(std::max(1e-9, v)); };
  for (const RowFigures& f : figures) {
    log_ratio += log_of(f.square_over_hex);
    log_time += log_of(f.time_ratio);
    log_plain += log_of(f.plain_ratio);
    log_subcell += log_of(f.subcell_ratio);
    if (f.square_over_hex < worst->square_over_hex) worst = &f;
    if (f.has_paper) {
      ++with_paper;
      if (f.pos[kHex] < f.paper_pos[0]) ++beats_paper;
    }
    if (f.square_over_hex >= kRatioGoal) ++ratio_goal;
  }
  const double n = static_cast<double>(figures.size());
  std::printf("RESULT rows=%zu seeds=%d mean_square_over_hex=%.3f worst_row=%s "
              "worst_square_over_hex=%.3f rows_ratio_ge_1.5=%d hex_below_paper=%d/%d "
              "mean_time_ratio=%.3f mean_plain_ratio=%.3f mean_subcell_ratio=%.3f "
              "hex_position_rmse_first=%.5f square_position_rmse_first=%.5f elapsed_s=%.1f\n",
              figures.size(), args.seeds, std::exp(log_ratio / n), worst->name.c_str(),
              worst->square_over_hex, ratio_goal, beats_paper, with_paper, std::exp(log_time / n),
              std::exp(log_plain / n), std::exp(log_subcell / n), figures.front().pos[kHex],
              figures.front().pos[kSquare], elapsed);
}

int Main(int argc, char** argv) {
  Args args;
  std::vector<Row> rows;
  if (const std::optional<int> status = cli::ParseCommandLine(
          "hex_slam_bench", argc, argv, [&args](CLI::App* app) { Declare(app, &args); },
          [&args, &rows] {
            ApplyQuick(&args);
            return CheckArgs(args, &rows);
          })) {
    return *status;
  }
  const auto started = std::chrono::steady_clock::now();
  for (const std::string& dir : {args.out + "/figures", args.work}) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
      std::fprintf(stderr, "error: cannot create %s: %s\n", dir.c_str(), ec.message().c_str());
      return 1;
    }
  }
  std::printf("hex_slam_bench: %zu rows x %d seeds x {hex, square (hector), hex plain, square "
              "sub-cell}%s\n",
              rows.size(), args.seeds, args.odometry ? ", odometry prior" : "");
  std::vector<RowResult> results;
  std::string error = RunRows(rows, args, &results);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  std::vector<RowFigures> figures;
  for (const RowResult& r : results) figures.push_back(Figures(r));
  std::printf("\nhex_slam (hex, sub-cell offsets) against hector_mapping's method (square), "
              "with the paper's Table 1 (position and angle RMSE in m and rad, ms per scan):\n");
  PrintTable(MainTable(figures));
  std::printf("\nThe same method on both lattices (position RMSE, m; median ms per scan):\n");
  PrintTable(AblationTable(figures));

  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  error = WriteCsv(args.work + "/results.csv", figures);
  if (error.empty()) {
    error = WriteMarkdown(args.out + "/benchmark.md",
                          GeneratedSection(figures, results, args, CommandLine(argc, argv), elapsed));
  }
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  if (args.plots) Plot(results, args);
  std::printf("\nwrote %s/benchmark.md, %s/figures/bench_*.png, %s/results.csv\n",
              args.out.c_str(), args.out.c_str(), args.work.c_str());
  PrintResult(figures, args, elapsed);
  return 0;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::RunToolMain(hex_slam::Main, argc, argv); }
