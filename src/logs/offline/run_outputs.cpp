#include "hex_slam/logs/offline/run_outputs.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "hex_slam/io/hex_map_file.h"
#include "hex_slam/io/image_io.h"
#include "hex_slam/io/map_image.h"
#include "hex_slam/io/map_server_io.h"
#include "hex_slam/io/occupancy_raster.h"

namespace hex_slam {
namespace logs {
namespace {

constexpr io::Rgb kEstimateColour = {220, 40, 40};
constexpr io::Rgb kOdometryColour = {40, 90, 220};
constexpr io::Rgb kStartColour = {40, 170, 60};
constexpr double kCellPixels = 8.0;  // the cell picture's scale when it fits
constexpr int kPathThickness = 3;
constexpr int kStartRadius = 6;

double LargestSide(const Eigen::AlignedBox2d& box) {
  return box.isEmpty() ? 1.0 : std::max(box.sizes().x(), box.sizes().y());
}

template <class Lattice>
void AddMaps(const std::string& dir, const GridMap<Lattice>& finest,
             const std::vector<io::StampedPose>& trajectory, const std::vector<Pose2>& odometry,
             const RunOutputOptions& options, io::AtomicFileSet* files,
             std::vector<std::string>* written) {
  const io::OccupancyRaster raster =
      io::Rasterize(finest.log_odds_grid(), io::MapResolution(finest.lattice()));
  io::AddMapServerMap(raster, dir + "/map", files);
  written->push_back(dir + "/map.pgm");
  written->push_back(dir + "/map.yaml");

  io::MapImageOptions cells;
  const double side = LargestSide(finest.KnownExtent()) + 2.0 * cells.margin;
  cells.pixels_per_metre =
      std::min(kCellPixels / finest.lattice().spacing(), options.max_cell_image_side / side);
  io::ImageFrame frame;
  const std::string cell_name = dir + "/" + Lattice::kName + "_map.png";
  io::AddPng(cell_name, io::RenderMap(finest, cells, &frame), files);
  written->push_back(cell_name);

  io::MapImageOptions plain;
  plain.cell_outlines = false;
  plain.pixels_per_metre = options.max_trajectory_image_side / side;
  io::Image picture = io::RenderMap(finest, plain, &frame);
  if (!odometry.empty() && !trajectory.empty()) {
    // The odometry moved rigidly so it starts where the estimate starts.
    const Pose2 to_map = trajectory.front().pose * odometry.front().inverse();
    std::vector<Eigen::Vector2d> path;
    for (const Pose2& p : odometry) path.push_back((to_map * p).translation());
    io::DrawPolyline(frame, path, kOdometryColour, kPathThickness, &picture);
  }
  std::vector<Eigen::Vector2d> path;
  for (const io::StampedPose& p : trajectory) path.push_back(p.pose.translation());
  io::DrawPolyline(frame, path, kEstimateColour, kPathThickness, &picture);
  if (!path.empty()) io::DrawDisc(frame, path.front(), kStartRadius, kStartColour, &picture);
  io::AddPng(dir + "/trajectory.png", picture, files);
  written->push_back(dir + "/trajectory.png");
}

}  // namespace

std::string WriteRunOutputs(const std::string& dir, const Slam& slam,
                            const std::vector<io::StampedPose>& trajectory,
                            const std::vector<Pose2>& odometry, const RunOutputOptions& options,
                            std::vector<std::string>* written) {
  std::error_code dir_error;
  std::filesystem::create_directories(dir, dir_error);
  if (dir_error) return "cannot create " + dir + ": " + dir_error.message();
  // One set: the outputs of one run appear together, or none of them does.
  io::AtomicFileSet files;
  std::vector<std::string> names;
  io::AddTumTrajectory(dir + "/trajectory.tum", trajectory, &files);
  names.push_back(dir + "/trajectory.tum");
  io::AddHexMapFile(dir + "/map.hexmap", io::CaptureSlamMap(slam), &files);
  names.push_back(dir + "/map.hexmap");
  if (slam.hex_maps()) {
    AddMaps(dir, slam.hex_maps()->level(0), trajectory, odometry, options, &files, &names);
  } else {
    AddMaps(dir, slam.square_maps()->level(0), trajectory, odometry, options, &files, &names);
  }
  const std::string error = files.Commit();
  if (error.empty()) written->insert(written->end(), names.begin(), names.end());
  return error;
}

}  // namespace logs
}  // namespace hex_slam
