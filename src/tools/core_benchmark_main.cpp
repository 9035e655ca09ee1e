// Per-scan cost of the SLAM core on a simulated drive: hex_slam as shipped against hector's method.
//
// Scans are simulated first, so only Slam::ProcessScan is timed. The variants run interleaved
// (every repeat runs each once, in turn) so a change in the machine's load hits them alike.
// Prints median, p99 and mean per scan, the median of the scans that only match and of those that
// also update the map, scans per second and map memory for each variant and beam count, then the
// ratios to hector's method, the position RMSE against the truth (the same for every repeat), and
// ends with one RESULT line.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "hex_slam/common/input_limits.h"
#include "hex_slam/sim/room_drive.h"
#include "hex_slam/mapping/slam.h"
#include "command_line.h"
#include "tool_main.h"

namespace hex_slam {
namespace {

// What is compared. The first is hex_slam's defaults, the second hector_mapping's method (the
// baseline every ratio is taken against: UseHectorsMethod); the last two (--ablation) are the
// same two methods on the other lattice.
struct Variant {
  const char* name;
  const char* lattice;
  bool hectors_method;
};
constexpr Variant kShipped = {"hex_slam", "hex", false};
constexpr Variant kHector = {"hector", "square", true};
constexpr Variant kAblation[] = {{"hex_plain", "hex", true}, {"sq_subcell", "square", false}};
constexpr double kFinestHexSpacing = 0.05;  // m; the square side gives the same cell area
constexpr long kMinBeams = 3;  // the simulated lidar's least
constexpr int kDefaultRepeats = 3;

struct Timing {
  double median_ms = 0.0;
  double p99_ms = 0.0;
  double mean_ms = 0.0;
  double match_median_ms = 0.0;   // scans that did not update the map
  double update_median_ms = 0.0;  // scans that did
  double scans_per_s = 0.0;
  double memory_mb = 0.0;
  double position_rmse_m = 0.0;
  int scans = 0;
};

struct Samples {
  std::vector<double> all_ms, match_ms, update_ms;
  double total_s = 0.0;
  double memory_mb = 0.0;
  double position_rmse_m = 0.0;
  // Gauss–Newton iterations, linearisations (passes over the points) and points, summed per
  // level over matched scans, finest first.
  std::vector<double> iterations, linearizations, points;
  int matched = 0;
};

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t i = std::min(values.size() - 1, static_cast<std::size_t>(q * values.size()));
  return values[i];
}

struct Drive {
  std::vector<LaserScan> scans;
  std::vector<Pose2> truth;
};

Drive SimulateDrive(int beams, unsigned seed) {
  const sim::RoomDrive room = sim::MakeRoomDrive(beams);
  std::mt19937_64 rng(seed);
  Drive drive;
  drive.truth = room.truth;
  for (std::size_t i = 0; i < room.truth.size(); ++i) {
    drive.scans.push_back(
        sim::SimulateScan(room.world, room.truth[i], room.lidar, room.scan_period * i, &rng));
  }
  return drive;
}

SlamOptions OptionsFor(const Variant& v) {
  SlamOptions options;
  options.lattice = v.lattice;
  options.map_resolution = std::string(v.lattice) == "hex"
                               ? kFinestHexSpacing
                               : kFinestHexSpacing * std::sqrt(0.5 * std::sqrt(3.0));
  if (v.hectors_method) UseHectorsMethod(&options.matcher);
  return options;
}

void RunOnce(const Variant& v, const Drive& drive, Samples* samples) {
  Slam slam(OptionsFor(v));
  slam.Reset(drive.truth.front());
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < drive.scans.size(); ++i) {
    const auto start = std::chrono::steady_clock::now();
    const ScanReport report = slam.ProcessScan(drive.scans[i]);
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    sum_sq += (report.pose.translation() - drive.truth[i].translation()).squaredNorm();
    samples->all_ms.push_back(1e3 * s);
    (report.map_updated ? samples->update_ms : samples->match_ms).push_back(1e3 * s);
    samples->total_s += s;
    if (report.outcome != ScanOutcome::kMatched) continue;
    const std::vector<LevelReport>& levels = report.match.levels;
    samples->iterations.resize(levels.size(), 0.0);
    samples->linearizations.resize(levels.size(), 0.0);
    samples->points.resize(levels.size(), 0.0);
    for (std::size_t k = 0; k < levels.size(); ++k) {
      samples->iterations[k] += levels[k].iterations;
      samples->linearizations[k] += levels[k].linearizations;
      samples->points[k] += levels[k].points;
    }
    ++samples->matched;
  }
  // Every repeat gives the same poses; the last one's error is kept.
  samples->position_rmse_m = std::sqrt(sum_sq / drive.scans.size());
  samples->memory_mb = slam.MemoryBytes() / 1048576.0;
}

Timing Summarise(const Samples& s) {
  Timing t;
  t.scans = static_cast<int>(s.all_ms.size());
  t.median_ms = Percentile(s.all_ms, 0.5);
  t.p99_ms = Percentile(s.all_ms, 0.99);
  t.mean_ms = t.scans > 0 ? 1e3 * s.total_s / t.scans : 0.0;
  t.match_median_ms = Percentile(s.match_ms, 0.5);
  t.update_median_ms = Percentile(s.update_ms, 0.5);
  t.scans_per_s = s.total_s > 0.0 ? t.scans / s.total_s : 0.0;
  t.memory_mb = s.memory_mb;
  t.position_rmse_m = s.position_rmse_m;
  return t;
}

struct Args {
  int repeats = kDefaultRepeats;
  std::vector<int> beam_counts = {360, 1081};  // 1081: a 270 deg Hokuyo; the others 360 deg
  bool ablation = false;
  std::string only;  // empty: every variant
};

// The command line; the checks that need the variants' names come after parsing (CheckArgs).
void Declare(CLI::App* app, Args* args) {
  app->description(
      "Per-scan cost of the SLAM core on a simulated drive through the test room: hex_slam as "
      "shipped (hex_slam) against hector_mapping's method (hector), interleaved.");
  app->footer(
      "Ends with: RESULT VARIANT_median_ms_BEAMS=... VARIANT_p99_ms_BEAMS=... "
      "VARIANT_rmse_m_BEAMS=... for each variant and beam count, and "
      "hex_slam_over_hector_median_BEAMS=... unless --only");
  // CLI::PositiveNumber would report its bounds as doubles, the upper one 309 digits long.
  app->add_option("--repeats", args->repeats,
                  "drives per variant (default " + std::to_string(kDefaultRepeats) + ")")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  app->add_option_function<int>(
         "--beams", [args](int beams) { args->beam_counts = {beams}; },
         "one beam count instead of 360 and 1081 (1081: 270 deg Hokuyo, otherwise 360 deg)")
      ->check(CLI::Range(kMinBeams, kMaxScanReadings));
  app->add_flag("--ablation", args->ablation,
                "also hector's method on hexes (hex_plain: the paper's matcher) and hex_slam's on "
                "squares (sq_subcell)");
  app->add_option("--only", args->only,
                  "run just this variant: hex_slam, hector, or with --ablation hex_plain or "
                  "sq_subcell (for profiling; no ratios)")
      ->check(cli::NonEmpty());
}

std::vector<Variant> SelectVariants(const Args& args) {
  std::vector<Variant> variants = {kShipped, kHector};
  if (args.ablation) variants.insert(variants.end(), std::begin(kAblation), std::end(kAblation));
  if (!args.only.empty()) {
    variants.erase(std::remove_if(variants.begin(), variants.end(),
                                  [&args](const Variant& v) { return args.only != v.name; }),
                   variants.end());
  }
  return variants;
}

// Empty, or what is wrong with --only.
std::string CheckArgs(const Args& args) {
  if (args.only.empty() || !SelectVariants(args).empty()) return "";
  const bool in_ablation =
      std::any_of(std::begin(kAblation), std::end(kAblation),
                  [&args](const Variant& v) { return args.only == v.name; });
  return "--only " + args.only + ": no such variant" +
         (in_ablation ? std::string(" without --ablation") : std::string());
}

int Main(int argc, char** argv) {
  Args args;
  if (const std::optional<int> status = cli::ParseCommandLine(
          "hex_slam_core_bench", argc, argv, [&args](CLI::App* app) { Declare(app, &args); },
          [&args] { return CheckArgs(args); })) {
    return *status;
  }
  const std::vector<Variant> variants = SelectVariants(args);
  std::printf("hex_slam core benchmark: simulated drive in the test room, hex spacing %.2f m "
              "(square at equal cell area), %d repeats interleaved\n"
              "hex_slam = hex lattice with the default options (shipped); hector = square lattice "
              "with hector_mapping's method (no sub-cell offsets, every step verified)\n\n",
              kFinestHexSpacing, args.repeats);
  std::printf("%-10s %6s %7s %10s %8s %8s %9s %10s %8s %9s %9s\n", "variant", "beams", "scans",
              "median_ms", "p99_ms", "mean_ms", "match_ms", "update_ms", "scans/s", "memory_MB",
              "rmse_m");
  std::string result = "RESULT";
  for (int beams : args.beam_counts) {
    const Drive drive = SimulateDrive(beams, 1);
    std::vector<Samples> samples(variants.size());
    for (int r = 0; r < args.repeats; ++r) {
      for (std::size_t v = 0; v < variants.size(); ++v) RunOnce(variants[v], drive, &samples[v]);
    }
    std::vector<Timing> timings;
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const Timing t = Summarise(samples[v]);
      timings.push_back(t);
      std::printf("%-10s %6d %7d %10.4f %8.4f %8.4f %9.4f %10.4f %8.0f %9.1f %9.6f\n",
                  variants[v].name, beams, t.scans, t.median_ms, t.p99_ms, t.mean_ms,
                  t.match_median_ms, t.update_median_ms, t.scans_per_s, t.memory_mb,
                  t.position_rmse_m);
      char buf[200];
      const char* name = variants[v].name;
      std::snprintf(buf, sizeof(buf), " %s_median_ms_%d=%.4f %s_p99_ms_%d=%.4f %s_rmse_m_%d=%.6f",
                    name, beams, t.median_ms, name, beams, t.p99_ms, name, beams,
                    t.position_rmse_m);
      result += buf;
    }
    if (args.only.empty()) {
      const Timing& hector = timings[1];
      for (std::size_t v = 0; v < variants.size(); ++v) {
        if (v == 1) continue;
        const Timing& t = timings[v];
        std::printf("%-10s %6d %7s %10.2f %8.2f %8.2f %9.2f %10.2f   (/ hector)\n",
                    variants[v].name, beams, "", t.median_ms / hector.median_ms,
                    t.p99_ms / hector.p99_ms, t.mean_ms / hector.mean_ms,
                    t.match_median_ms / hector.match_median_ms,
                    t.update_median_ms / hector.update_median_ms);
      }
      char buf[96];
      std::snprintf(buf, sizeof(buf), " hex_slam_over_hector_median_%d=%.3f", beams,
                    timings[0].median_ms / hector.median_ms);
      result += buf;
    }
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const Samples& s = samples[v];
      std::printf("%-10s %6d  per matched scan, finest level first: iterations", variants[v].name,
                  beams);
      for (double it : s.iterations) std::printf(" %.2f", it / std::max(1, s.matched));
      std::printf(", linearisations");
      for (double n : s.linearizations) std::printf(" %.2f", n / std::max(1, s.matched));
      std::printf(", points");
      for (double n : s.points) std::printf(" %.0f", n / std::max(1, s.matched));
      std::printf("\n");
    }
    std::printf("\n");
  }
  std::printf("%s\n", result.c_str());
  return 0;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::RunToolMain(hex_slam::Main, argc, argv); }
