// The paper's simulated experiment (its Table 1), made concrete: which world, which cell area,
// which angle between the walls and the map's axes, which lidar, and the conditions the paper
// does not state (scan rate, speeds, noise), fixed here and stated.
//
// A scenario is simulated in the SLAM's map frame: the frame of the robot's start position,
// turned by the start angle, so with 45° every wall runs at 45° to the lattice's axes (what stage
// gives when the robot starts at 45° to the walls and the map is aligned with the robot).
#ifndef HEX_SLAM_SIM_SCENARIO_H_
#define HEX_SLAM_SIM_SCENARIO_H_

#include <string>
#include <vector>

#include "hex_slam/geometry/pose2.h"
#include "hex_slam/sim/image_world.h"
#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/placed_world.h"
#include "hex_slam/mapping/slam_options.h"

namespace hex_slam {
namespace sim {

struct ScenarioSpec {
  // "maze" and "rooms": our worlds (worlds/); "robotcraft": the paper's own maze bitmap, read
  // from the data folder when present (never shipped).
  std::string map = "maze";
  double cell_area = 0.01;       // m², of a cell of the finest map level
  double start_angle_deg = 0.0;  // between the walls and the map's axes
  int beams = 1000;              // over 360°

  // "maze/0.01/0/1000", the paper's order of parameters.
  std::string Name() const;
};

// What the paper leaves unsaid, chosen as a small indoor robot would have it.
struct ScenarioConditions {
  double scan_rate = 10.0;     // Hz (stage's default laser rate)
  double linear_speed = 0.3;   // m/s
  double angular_speed = 0.6;  // rad/s, turning in place at waypoints
  double range_noise = 0.01;   // m, Gaussian
  double range_min = 0.05;     // m
  double range_max = 8.0;      // m (the paper's RPLidar)
  // LidarModel::max_range_ghosts: beams without a return read range_max - the margin.
  bool max_range_ghosts = false;
  double max_range_ghost_margin = 0.0;  // m
};

// Where the worlds are: worlds_dir holds maze.yaml, rooms.yaml and the *_path.yaml files;
// data_dir is the shared data folder (robotcraft_maze/540x540-90cm.png).
struct ScenarioFiles {
  std::string worlds_dir;
  std::string data_dir;
};

struct Scenario {
  ScenarioSpec spec;
  ImageWorld image;          // the world in its own (image) frame
  Pose2 map_frame;           // the SLAM's map frame in the image frame
  std::vector<Pose2> truth;  // the robot (and its lidar) at each scan, in the map frame
  LidarModel lidar;
  double scan_period = 0.1;  // s

  // The world as seen in the map frame.
  PlacedWorld World() const { return PlacedWorld(image, map_frame.inverse()); }
};

// Loads the world and its path and samples the drive. Returns an empty string or an error
// (e.g. the robotcraft bitmap is absent: the message says where it was looked for).
std::string MakeScenario(const ScenarioSpec& spec, const ScenarioFiles& files,
                         const ScenarioConditions& conditions, Scenario* scenario);

// The SLAM options of a run: defaults (hector's where they exist) except the lattice and its
// cell size at the scenario's cell area (MATH.md §2: equal area for both lattices).
SlamOptions ScenarioSlamOptions(const ScenarioSpec& spec, const std::string& lattice);

// One row of the paper's Table 1: its scenario and its figures. The paper's "MSE ... in meters"
// is read as a root-mean-square error (its magnitudes are metres, not square metres).
struct PaperRow {
  int test = 0;
  ScenarioSpec spec;
  double hex_position = 0.0;     // m
  double square_position = 0.0;  // m (hector_slam)
  double hex_angle = 0.0;        // rad
  double square_angle = 0.0;     // rad
};
std::vector<PaperRow> PaperTable1();

// The shared data folder: $HEX_SLAM_DATA_DIR if set, else `source_dir`/../shared/data.
std::string DataDirectory(const std::string& source_dir);

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_SCENARIO_H_
