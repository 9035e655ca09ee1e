// What hex_slam_offline leaves in its output folder, all files written together atomically:
//   trajectory.tum       one "t x y z qx qy qz qw" line per scan, the log's stamps
//   map.pgm + map.yaml   the finest level rasterised at equal cell area (map_server format)
//   map.hexmap           every level's cells exactly, for --map (localization on a saved map)
//   hex_map.png          the finest level's cells drawn as cells (square_map.png on squares)
//   trajectory.png       the map with the estimated path (red) and, when given, the raw
//                        odometry started at the same pose (blue)
#ifndef HEX_SLAM_LOGS_OFFLINE_RUN_OUTPUTS_H_
#define HEX_SLAM_LOGS_OFFLINE_RUN_OUTPUTS_H_

#include <string>
#include <vector>

#include "hex_slam/io/trajectory_io.h"
#include "hex_slam/mapping/slam.h"

namespace hex_slam {
namespace logs {

struct RunOutputOptions {
  int max_cell_image_side = 4000;        // px: the cell picture shrinks to fit
  int max_trajectory_image_side = 1600;  // px
};

// Creates `dir` (and parents), then writes every file as one set (atomic_file.h): all of them,
// or on an error none. Returns an empty string or the error; `written` lists the files made.
std::string WriteRunOutputs(const std::string& dir, const Slam& slam,
                            const std::vector<io::StampedPose>& trajectory,
                            const std::vector<Pose2>& odometry, const RunOutputOptions& options,
                            std::vector<std::string>* written);

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_OFFLINE_RUN_OUTPUTS_H_
