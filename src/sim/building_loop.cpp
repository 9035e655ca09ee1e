#include "hex_slam/sim/building_loop.h"

#include <cmath>
#include <random>

namespace hex_slam {
namespace sim {
namespace {

// The floor, the corridor's outer and inner walls (m).
constexpr double kFloorX = 60.0, kFloorY = 32.0;
constexpr double kOuterMin = 5.0, kOuterMaxX = 55.0, kOuterMaxY = 27.0;
constexpr double kCorridorWidth = 2.4;
constexpr double kDoorWidth = 1.0;
constexpr std::uint64_t kLayoutSeed = 13;
// The odometry's random stream is derived from the seed but differs from the lidar's.
constexpr std::uint64_t kOdometrySeedOffset = 0x9e3779b97f4a7c15ULL;

// A wall from a to b along an axis, with door gaps of kDoorWidth starting at the given distances
// from a.
void WallWithDoors(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                   const std::vector<double>& doors, SegmentWorld* w) {
  const double length = (b - a).norm();
  const Eigen::Vector2d u = (b - a) / length;
  double start = 0.0;
  for (const double d : doors) {
    w->AddSegment(a + start * u, a + d * u);
    start = d + kDoorWidth;
  }
  w->AddSegment(a + start * u, b);
}

// Door positions along a wall of `length`: gaps 2.5 to 6 m apart, irregularly (a fixed seed), so
// no stretch of corridor repeats another.
std::vector<double> Doors(double length, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> gap(2.5, 6.0);
  std::vector<double> doors;
  for (double d = gap(*rng) * 0.5; d + kDoorWidth < length - 1.0; d += kDoorWidth + gap(*rng)) {
    doors.push_back(d);
  }
  return doors;
}

SegmentWorld Floor() {
  SegmentWorld w;
  std::mt19937_64 rng(kLayoutSeed);
  w.AddRectangle({0.0, 0.0}, {kFloorX, kFloorY});
  const double lo = kOuterMin, hx = kOuterMaxX, hy = kOuterMaxY;
  const double il = lo + kCorridorWidth, ihx = hx - kCorridorWidth, ihy = hy - kCorridorWidth;
  // The corridor's walls, outer and inner, with doors into the rooms on both sides.
  const Eigen::Vector2d outer[] = {{lo, lo}, {hx, lo}, {hx, hy}, {lo, hy}};
  const Eigen::Vector2d inner[] = {{il, il}, {ihx, il}, {ihx, ihy}, {il, ihy}};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d& a = outer[k];
    const Eigen::Vector2d& b = outer[(k + 1) % 4];
    WallWithDoors(a, b, Doors((b - a).norm(), &rng), &w);
    const Eigen::Vector2d& c = inner[k];
    const Eigen::Vector2d& d = inner[(k + 1) % 4];
    WallWithDoors(c, d, Doors((d - c).norm(), &rng), &w);
  }
  // Room partitions: outer rooms between the floor's wall and the corridor, inner ones in the
  // block, at spacings that do not repeat.
  for (const double x : {7.5, 11.0, 15.0, 21.0, 24.5, 30.5, 38.0, 42.0, 46.5, 51.0}) {
    w.AddSegment({x, 0.0}, {x, lo});
    w.AddSegment({x + 1.3, hy}, {x + 1.3, kFloorY});
  }
  for (const double y : {9.0, 12.0, 20.5, 24.0}) {
    w.AddSegment({0.0, y}, {lo, y});
    w.AddSegment({hx, y - 1.7}, {kFloorX, y - 1.7});
  }
  for (const double x : {11.0, 14.0, 19.5, 25.5, 33.0, 38.5, 44.0, 48.0}) {
    w.AddSegment({x, il}, {x, 12.0});
    w.AddSegment({x + 0.8, 20.0}, {x + 0.8, ihy});
  }
  w.AddSegment({il, 16.0}, {ihx, 16.0});
  // Cabinets and pillars in the corridor, against its walls.
  w.AddRectangle({lo, 9.0}, {lo + 0.45, 10.2});
  w.AddRectangle({il - 0.4, 19.0}, {il, 19.6});
  w.AddRectangle({22.0, ihy}, {23.1, ihy + 0.4});
  w.AddRectangle({31.5, hy - 0.35}, {32.2, hy});
  w.AddRectangle({36.5, lo}, {37.3, lo + 0.5});
  w.AddRectangle({16.0, il - 0.3}, {16.6, il});
  w.AddRectangle({ihx, 17.0}, {ihx + 0.4, 18.5});
  w.AddRectangle({hx - 0.5, 10.5}, {hx, 11.0});
  w.AddRectangle({11.0, hy - 0.45}, {12.6, hy});
  w.AddRectangle({28.0, il - 0.3}, {28.3, il});
  w.AddRectangle({45.0, lo}, {45.3, lo + 0.3});
  // Furniture in the rooms, seen through the doors.
  w.AddRectangle({2.0, 2.0}, {3.2, 2.8});
  w.AddRectangle({17.5, 1.0}, {18.5, 3.5});
  w.AddRectangle({40.0, 28.5}, {41.5, 29.5});
  w.AddRectangle({57.0, 22.0}, {58.5, 23.5});
  w.AddRectangle({9.0, 10.0}, {10.5, 11.0});
  w.AddRectangle({29.0, 18.0}, {30.0, 19.5});
  w.AddRectangle({46.0, 9.0}, {47.0, 10.0});
  w.AddRectangle({2.0, 25.0}, {3.0, 26.5});
  w.AddRectangle({34.0, 1.0}, {35.5, 2.0});
  return w;
}

}  // namespace

BuildingLoop MakeBuildingLoop(int laps) {
  BuildingLoop loop;
  loop.world = Floor();
  const double c = kOuterMin + 0.5 * kCorridorWidth;  // the corridor's centre line
  const double cx = kOuterMaxX - 0.5 * kCorridorWidth, cy = kOuterMaxY - 0.5 * kCorridorWidth;
  std::vector<Eigen::Vector2d> waypoints = {{c, 0.5 * (c + cy)}};
  for (int lap = 0; lap < laps; ++lap) {
    for (const Eigen::Vector2d& corner :
         {Eigen::Vector2d(c, cy), Eigen::Vector2d(cx, cy), Eigen::Vector2d(cx, c),
          Eigen::Vector2d(c, c)}) {
      waypoints.push_back(corner);
    }
  }
  waypoints.push_back(waypoints.front());
  PathMotion motion;
  motion.linear_speed = 0.6;
  motion.angular_speed = 0.6;
  motion.rate = 1.0 / loop.scan_period;
  loop.truth = SampleWaypointPath(waypoints, M_PI / 2, motion);
  loop.lidar.beams = 361;
  loop.lidar.field_of_view = M_PI;  // 361 beams 0.5° apart, both ends included
  loop.lidar.range_max = 30.0;
  loop.lidar.range_noise_stddev = 0.01;
  return loop;
}

RecordedDrive RecordBuildingLoop(const BuildingLoop& loop, std::uint64_t seed,
                                 const OdometryNoise& odometry_noise) {
  RecordedDrive drive;
  drive.truth = loop.truth;
  std::mt19937_64 rng(seed);
  DriftingOdometry odometry(odometry_noise, seed + kOdometrySeedOffset, drive.truth.front());
  for (std::size_t i = 0; i < drive.truth.size(); ++i) {
    drive.scans.push_back(
        SimulateScan(loop.world, drive.truth[i], loop.lidar, loop.scan_period * i, &rng));
    drive.odometry.push_back(odometry.Update(drive.truth[i]));
  }
  return drive;
}

}  // namespace sim
}  // namespace hex_slam
