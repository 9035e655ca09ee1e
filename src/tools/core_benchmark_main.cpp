// Per-scan cost of the SLAM core on a simulated drive, hex and square in one run.
//
// Scans are simulated first, so only Slam::ProcessScan is timed. Prints median, p99 and mean per
// scan, scans per second and map memory for each lattice and beam count, then the hex/square
// ratios, and ends with one RESULT line.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "hex_slam/sim/room_drive.h"
#include "hex_slam/slam.h"

namespace hex_slam {
namespace {

struct Timing {
  double median_ms = 0.0;
  double p99_ms = 0.0;
  double mean_ms = 0.0;
  double scans_per_s = 0.0;
  double memory_mb = 0.0;
  int scans = 0;
};

double Percentile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const std::size_t i = std::min(values.size() - 1, static_cast<std::size_t>(q * values.size()));
  return values[i];
}

std::vector<LaserScan> SimulateDrive(int beams, unsigned seed) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(beams);
  std::mt19937_64 rng(seed);
  std::vector<LaserScan> scans;
  for (std::size_t i = 0; i < drive.truth.size(); ++i) {
    scans.push_back(
        sim::SimulateScan(drive.world, drive.truth[i], drive.lidar, drive.scan_period * i, &rng));
  }
  return scans;
}

Timing Measure(const std::string& lattice, const std::vector<LaserScan>& scans, int repeats) {
  SlamOptions options;
  options.lattice = lattice;
  options.map_resolution = lattice == "hex" ? 0.05 : 0.05 * std::sqrt(0.5 * std::sqrt(3.0));
  std::vector<double> per_scan_ms;
  double total_s = 0.0;
  Timing t;
  for (int r = 0; r < repeats; ++r) {
    Slam slam(options);
    for (const LaserScan& scan : scans) {
      const auto start = std::chrono::steady_clock::now();
      slam.ProcessScan(scan);
      const double s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      per_scan_ms.push_back(1e3 * s);
      total_s += s;
    }
    t.memory_mb = slam.MemoryBytes() / 1048576.0;
  }
  t.scans = static_cast<int>(per_scan_ms.size());
  t.median_ms = Percentile(per_scan_ms, 0.5);
  t.p99_ms = Percentile(per_scan_ms, 0.99);
  t.mean_ms = 1e3 * total_s / t.scans;
  t.scans_per_s = t.scans / total_s;
  return t;
}

int Main(int argc, char** argv) {
  int repeats = 3;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeats") == 0 && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "usage: %s [--repeats N]\n", argv[0]);
      return 2;
    }
  }
  std::printf("hex_slam core benchmark: simulated drive in the test room, map_resolution 0.05 m "
              "(square at equal cell area), %d repeats\n\n", repeats);
  std::printf("%-7s %6s %7s %11s %9s %9s %9s %10s\n", "lattice", "beams", "scans", "median_ms",
              "p99_ms", "mean_ms", "scans/s", "memory_MB");
  std::string result = "RESULT";
  for (int beams : {360, 1081}) {
    const std::vector<LaserScan> scans = SimulateDrive(beams, 1);
    Timing hex, square;
    for (const std::string lattice : {"hex", "square"}) {
      const Timing t = Measure(lattice, scans, repeats);
      std::printf("%-7s %6d %7d %11.4f %9.4f %9.4f %9.0f %10.1f\n", lattice.c_str(), beams,
                  t.scans, t.median_ms, t.p99_ms, t.mean_ms, t.scans_per_s, t.memory_mb);
      (lattice == "hex" ? hex : square) = t;
    }
    std::printf("%-7s %6d %7s %11.2f %9.2f %9.2f\n", "hex/sq", beams, "", hex.median_ms / square.median_ms,
                hex.p99_ms / square.p99_ms, hex.mean_ms / square.mean_ms);
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  " hex_median_ms_%d=%.4f hex_p99_ms_%d=%.4f square_median_ms_%d=%.4f "
                  "square_p99_ms_%d=%.4f",
                  beams, hex.median_ms, beams, hex.p99_ms, beams, square.median_ms, beams,
                  square.p99_ms);
    result += buf;
  }
  std::printf("\n%s\n", result.c_str());
  return 0;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::Main(argc, argv); }
