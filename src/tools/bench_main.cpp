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
#include "hex_slam/slam.h"

#ifndef HEX_SLAM_SOURCE_DIR
#define HEX_SLAM_SOURCE_DIR "."
#endif

namespace hex_slam {
namespace {

constexpr const char* kLattices[] = {"hex", "square"};
constexpr int kDefaultSeeds = 3;
// --quick: one short row, for the smoke test.
constexpr const char* kQuickRow = "maze/0.01/0/360";
constexpr int kQuickScans = 400;
// Map figures are drawn for these rows (first seed), when they run.
const std::set<std::string> kFigureRows = {"maze/0.01/0/1000", "maze/0.01/45/1000",
                                           "rooms/0.01/0/1000", "robotcraft/0.01/0/1000"};
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
  std::string out = "docs";
  std::string work = "out/bench";
  std::string worlds = std::string(HEX_SLAM_SOURCE_DIR) + "/worlds";
  std::string data = sim::DataDirectory(HEX_SLAM_SOURCE_DIR);
};

void Usage(const char* argv0) {
  std::fprintf(
      stderr,
      "usage: %s [--rows LIST] [--seeds N] [--quick] [--out DIR] [--work DIR] [--odometry]\n"
      "          [--max-scans N] [--no-plots] [--worlds DIR] [--data DIR]\n"
      "  --rows   paper (default): the paper's six Table 1 rows on our maze and rooms worlds,\n"
      "           and its five maze rows on the paper's own maze (robotcraft) when the data\n"
      "           folder has it; all: every map x {0.01,0.04} m2 x {0,45,60} deg x {1000,360}\n"
      "           beams; or a comma list of rows map/area/angle/beams, e.g. maze/0.04/45/360\n"
      "  --seeds  drives per row (default %d): lidar noise and odometry drift differ per seed\n"
      "  --quick  one short row (%s, %d scans, 1 seed), for smoke tests\n"
      "  --out    where benchmark.md and figures/bench_*.png go (default docs)\n"
      "  --work   per-run data: results.csv, trajectories (default out/bench)\n"
      "  --odometry  give SLAM the drifting odometry as a prior (default: none, as the paper)\n",
      argv0, kDefaultSeeds, kQuickRow, kQuickScans);
}

bool ParsePositive(const char* text, int* out) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (*end != '\0' || v <= 0 || v > 1000000) return false;
  *out = static_cast<int>(v);
  return true;
}

bool Parse(int argc, char** argv, Args* args) {
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (key == "--quick") {
      args->quick = true;
      continue;
    }
    if (key == "--odometry") {
      args->odometry = true;
      continue;
    }
    if (key == "--no-plots") {
      args->plots = false;
      continue;
    }
    if (i + 1 >= argc) return false;
    const char* value = argv[++i];
    if (key == "--rows") {
      args->rows = value;
    } else if (key == "--seeds") {
      if (!ParsePositive(value, &args->seeds)) return false;
    } else if (key == "--max-scans") {
      if (!ParsePositive(value, &args->max_scans)) return false;
    } else if (key == "--out") {
      args->out = value;
    } else if (key == "--work") {
      args->work = value;
    } else if (key == "--worlds") {
      args->worlds = value;
    } else if (key == "--data") {
      args->data = value;
    } else {
      return false;
    }
  }
  if (args->quick) {
    args->rows = kQuickRow;
    args->seeds = 1;
    if (args->max_scans == 0) args->max_scans = kQuickScans;
  }
  return true;
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
  return ParsePositive(beams.c_str(), &spec->beams) && spec->beams >= 3;
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
      if (!ParseRowName(token, &s)) return "bad row '" + token + "' (want map/area/angle/beams)";
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
  LatticeResult lattice[2];  // hex, square
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
  std::string error = sim::MakeScenario(row.spec, files, sim::ScenarioConditions(), &scenario);
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
    std::vector<Pose2> estimates[2];
    for (int k = 0; k < 2; ++k) {
      Slam slam(sim::ScenarioSlamOptions(row.spec, kLattices[k]));
      const sim::SlamRun run = sim::RunSlam(drive, args.odometry, &slam);
      const sim::TrajectoryError e = sim::CompareTrajectories(run.poses, drive.truth);
      LatticeResult& r = result->lattice[k];
      r.position_rmse.push_back(e.position_rmse);
      r.angle_rmse.push_back(e.angle_rmse);
      r.position_max = std::max(r.position_max, e.position_max);
      r.angle_max = std::max(r.angle_max, e.angle_max);
      for (double s : run.scan_seconds) r.scan_ms.push_back(1e3 * s);
      r.scans += static_cast<int>(run.poses.size());
      r.matched += run.matched;
      estimates[k] = run.poses;
      if (seed == 1) {
        error = io::WriteTumTrajectory(args.work + "/" + id + "_" + kLattices[k] + ".tum",
                                       Stamped(run.poses, scenario.scan_period));
        if (error.empty() && kFigureRows.count(row.spec.Name())) {
          const std::string png =
              args.out + "/figures/bench_map_" + id + "_" + kLattices[k] + ".png";
          error = slam.hex_maps() ? WriteMapFigure(slam.hex_maps()->level(0), drive.truth,
                                                   run.poses, png)
                                  : WriteMapFigure(slam.square_maps()->level(0), drive.truth,
                                                   run.poses, png);
        }
        if (!error.empty()) return error;
      }
    }
    if (seed == 1) {
      error = io::WriteTumTrajectory(args.work + "/" + id + "_truth.tum",
                                     Stamped(drive.truth, scenario.scan_period));
      if (!error.empty()) return error;
    }
  }
  return "";
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

double Ratio(double a, double b) { return b > 0.0 ? a / b : 0.0; }

// Column values of one row, shared by the terminal table, the markdown and the CSV.
struct RowFigures {
  std::string name, test;
  double pos[2], ang[2], max[2], median_ms[2], p99_ms[2];
  double paper_pos[2] = {0, 0}, paper_ang[2] = {0, 0};
  bool has_paper = false;
  double square_over_hex = 0.0;  // position RMSE ratio: > 1 means hex is better
  double time_ratio = 0.0;       // hex / square median per-scan time
};

RowFigures Figures(const RowResult& r) {
  RowFigures f;
  f.name = r.row.spec.Name();
  f.test = r.row.paper ? std::to_string(r.row.paper->test) : "-";
  for (int k = 0; k < 2; ++k) {
    const LatticeResult& l = r.lattice[k];
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
  f.square_over_hex = Ratio(f.pos[1], f.pos[0]);
  f.time_ratio = Ratio(f.median_ms[0], f.median_ms[1]);
  return f;
}

void PrintTable(const std::vector<RowFigures>& rows) {
  std::printf("\n%-4s %-24s | %-8s %-8s %-6s | %-8s %-8s | %-9s %-9s | %-8s %-8s | %-8s %-8s | "
              "%-13s %-13s %-5s\n",
              "test", "map/area m2/angle/beams", "pos hex", "pos sq", "sq/hex", "paper hx",
              "paper hc", "ang hex", "ang sq", "paper hx", "paper hc", "max hex", "max sq",
              "ms hex med/99", "ms sq med/99", "t h/s");
  for (const RowFigures& f : rows) {
    std::printf("%-4s %-24s | %-8s %-8s %-6s | %-8s %-8s | %-9s %-9s | %-8s %-8s | %-8s %-8s | "
                "%-13s %-13s %-5s\n",
                f.test.c_str(), f.name.c_str(), Fmt(f.pos[0]).c_str(), Fmt(f.pos[1]).c_str(),
                Fmt(f.square_over_hex, 2).c_str(),
                f.has_paper ? Fmt(f.paper_pos[0]).c_str() : "-",
                f.has_paper ? Fmt(f.paper_pos[1]).c_str() : "-", Sci(f.ang[0]).c_str(),
                Sci(f.ang[1]).c_str(), f.has_paper ? Sci(f.paper_ang[0]).c_str() : "-",
                f.has_paper ? Sci(f.paper_ang[1]).c_str() : "-", Fmt(f.max[0]).c_str(),
                Fmt(f.max[1]).c_str(),
                (Fmt(f.median_ms[0], 3) + "/" + Fmt(f.p99_ms[0], 3)).c_str(),
                (Fmt(f.median_ms[1], 3) + "/" + Fmt(f.p99_ms[1], 3)).c_str(),
                Fmt(f.time_ratio, 2).c_str());
  }
  std::printf("(pos, max: position RMSE and largest error, m; ang: heading RMSE, rad; paper hx / "
              "hc: the paper's hexagonal SLAM / hector_slam; ms: per-scan time, median/p99)\n");
}

std::string WriteCsv(const std::string& path, const std::vector<RowFigures>& rows) {
  return io::WriteFileAtomically(path, [&](std::ostream& out) {
    out << "row,test,hex_position_rmse,square_position_rmse,square_over_hex,paper_hex_position,"
           "paper_square_position,hex_angle_rmse,square_angle_rmse,paper_hex_angle,"
           "paper_square_angle,hex_position_max,square_position_max,hex_median_ms,hex_p99_ms,"
           "square_median_ms,square_p99_ms,time_ratio\n";
    out << std::setprecision(6);
    for (const RowFigures& f : rows) {
      out << f.name << ',' << f.test << ',' << f.pos[0] << ',' << f.pos[1] << ','
          << f.square_over_hex << ',' << f.paper_pos[0] << ',' << f.paper_pos[1] << ','
          << f.ang[0] << ',' << f.ang[1] << ',' << f.paper_ang[0] << ',' << f.paper_ang[1] << ','
          << f.max[0] << ',' << f.max[1] << ',' << f.median_ms[0] << ',' << f.p99_ms[0] << ','
          << f.median_ms[1] << ',' << f.p99_ms[1] << ',' << f.time_ratio << '\n';
    }
  });
}

std::string WriteMarkdown(const std::string& path, const std::vector<RowFigures>& rows,
                          const std::vector<RowResult>& results, const Args& args,
                          const std::string& command, double elapsed_s) {
  return io::WriteFileAtomically(path, [&](std::ostream& out) {
    const sim::ScenarioConditions c;
    out << "# hex vs square: the paper's simulated experiment\n\n"
        << "Generated by `" << command << "` (" << Fmt(elapsed_s, 0) << " s). Do not edit: rerun "
        << "the command.\n\n"
        << "Both lattices process the same recorded scans, at equal cell area (hex centre "
        << "spacing d = s·sqrt(2/sqrt(3))), with the default SLAM options"
        << (args.odometry ? " and the drifting odometry as a prior" : " and no odometry")
        << ". Figures are means over " << args.seeds << " seed(s) per row; the largest error is "
        << "the worst over all seeds. Conditions: " << Fmt(c.scan_rate, 0) << " Hz scans over "
        << "360°, " << Fmt(c.linear_speed, 2) << " m/s, " << Fmt(c.angular_speed, 2)
        << " rad/s turning in place, " << Fmt(100 * c.range_noise, 0) << " cm Gaussian range "
        << "noise, ranges " << Fmt(c.range_min, 2) << "–" << Fmt(c.range_max, 0) << " m.\n\n";
    out << "| test | map / cell area m² / angle ° / beams | position RMSE hex (m) | square (m) | "
           "square/hex | paper hex | paper hector | angle RMSE hex (rad) | square (rad) | "
           "paper hex | paper hector | max error hex / square (m) | ms/scan hex median / p99 | "
           "square median / p99 | time hex/square |\n"
        << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const RowFigures& f : rows) {
      out << "| " << f.test << " | " << f.name << " | " << Fmt(f.pos[0]) << " | "
          << Fmt(f.pos[1]) << " | " << Fmt(f.square_over_hex, 2) << " | "
          << (f.has_paper ? Fmt(f.paper_pos[0]) : "–") << " | "
          << (f.has_paper ? Fmt(f.paper_pos[1]) : "–") << " | " << Sci(f.ang[0]) << " | "
          << Sci(f.ang[1]) << " | " << (f.has_paper ? Sci(f.paper_ang[0]) : "–") << " | "
          << (f.has_paper ? Sci(f.paper_ang[1]) : "–") << " | " << Fmt(f.max[0]) << " / "
          << Fmt(f.max[1]) << " | " << Fmt(f.median_ms[0], 3) << " / " << Fmt(f.p99_ms[0], 3)
          << " | " << Fmt(f.median_ms[1], 3) << " / " << Fmt(f.p99_ms[1], 3) << " | "
          << Fmt(f.time_ratio, 2) << " |\n";
    }
    out << "\nDrives: ";
    for (std::size_t i = 0; i < results.size(); ++i) {
      const RowResult& r = results[i];
      if (i > 0 && r.row.spec.map == results[i - 1].row.spec.map) continue;
      out << r.row.spec.map << " " << r.scans_per_drive << " scans, " << Fmt(r.drive_length, 1)
          << " m, " << Fmt(r.drive_seconds, 0) << " s; ";
    }
    out << "\n";
  });
}

std::string CommandLine(int argc, char** argv) {
  std::string s = "hex_slam_bench";
  for (int i = 1; i < argc; ++i) s += std::string(" ") + argv[i];
  return s;
}

int Main(int argc, char** argv) {
  Args args;
  if (!Parse(argc, argv, &args)) {
    Usage(argv[0]);
    return 2;
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
  const bool have_robotcraft =
      std::filesystem::exists(args.data + "/robotcraft_maze/540x540-90cm.png");
  std::vector<Row> rows;
  std::string error = SelectRows(args.rows, have_robotcraft, &rows);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    Usage(argv[0]);
    return 2;
  }
  std::printf("hex_slam_bench: %zu rows x %d seeds x {hex, square}%s\n", rows.size(), args.seeds,
              args.odometry ? ", odometry prior" : "");
  std::vector<RowResult> results;
  for (const Row& row : rows) {
    RowResult result;
    const auto t0 = std::chrono::steady_clock::now();
    error = RunRow(row, args, &result);
    if (!error.empty()) {
      std::fprintf(stderr, "error: %s: %s\n", row.spec.Name().c_str(), error.c_str());
      return 1;
    }
    const RowFigures f = Figures(result);
    std::printf("  %-24s hex %.4f m  square %.4f m  (%.1f s)\n", f.name.c_str(), f.pos[0],
                f.pos[1],
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    std::fflush(stdout);
    results.push_back(std::move(result));
  }
  std::vector<RowFigures> figures;
  for (const RowResult& r : results) figures.push_back(Figures(r));
  PrintTable(figures);

  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  error = WriteCsv(args.work + "/results.csv", figures);
  if (error.empty()) {
    error = WriteMarkdown(args.out + "/benchmark.md", figures, results, args,
                          CommandLine(argc, argv), elapsed);
  }
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  if (args.plots) {
    std::string plotted;
    for (const RowResult& r : results) {
      if (!kFigureRows.count(r.row.spec.Name())) continue;
      plotted += (plotted.empty() ? "" : ",") + FileId(r.row.spec);
    }
    const std::string script = std::string(HEX_SLAM_SOURCE_DIR) + "/scripts/plot_bench.py";
    const std::string command = "/usr/bin/python3 '" + script + "' --work '" + args.work +
                                "' --figures '" + args.out + "/figures' --rows '" + plotted + "'";
    if (std::system(command.c_str()) != 0) {
      std::fprintf(stderr, "warning: the plots failed (%s); the table is complete\n",
                   command.c_str());
    }
  }
  std::printf("\nwrote %s/benchmark.md, %s/figures/bench_*.png, %s/results.csv\n",
              args.out.c_str(), args.out.c_str(), args.work.c_str());

  // Summary: the geometric mean of square/hex over rows, the worst row, and the goal counts.
  double log_sum = 0.0, log_time = 0.0;
  const RowFigures* worst = &figures.front();
  int beats_paper = 0, with_paper = 0, ratio_goal = 0;
  for (const RowFigures& f : figures) {
    log_sum += std::log(std::max(1e-9, f.square_over_hex));
    log_time += std::log(std::max(1e-9, f.time_ratio));
    if (f.square_over_hex < worst->square_over_hex) worst = &f;
    if (f.has_paper) {
      ++with_paper;
      if (f.pos[0] < f.paper_pos[0]) ++beats_paper;
    }
    if (f.square_over_hex >= 1.5) ++ratio_goal;
  }
  const double n = static_cast<double>(figures.size());
  std::printf("RESULT rows=%zu seeds=%d mean_square_over_hex=%.3f worst_row=%s "
              "worst_square_over_hex=%.3f rows_ratio_ge_1.5=%d hex_below_paper=%d/%d "
              "mean_time_ratio=%.3f hex_position_rmse_first=%.5f square_position_rmse_first=%.5f "
              "elapsed_s=%.1f\n",
              figures.size(), args.seeds, std::exp(log_sum / n), worst->name.c_str(),
              worst->square_over_hex, ratio_goal, beats_paper, with_paper, std::exp(log_time / n),
              figures.front().pos[0], figures.front().pos[1], elapsed);
  return 0;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::Main(argc, argv); }
