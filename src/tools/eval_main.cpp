// hex_slam_eval: a trajectory's accuracy against reference data.
//   relations: the relations metric of Kümmerle et al. 2009 (the Freiburg SLAM benchmark)
//   ate:       ATE after a least-squares SE(2) alignment, and RPE, against a ground truth
// Both end with one RESULT line.
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

#include "hex_slam/common/input_limits.h"
#include "hex_slam/io/trajectory_io.h"
#include "hex_slam/logs/evaluation/relations.h"
#include "hex_slam/logs/evaluation/trajectory_error.h"
#include "command_line.h"
#include "tool_main.h"

namespace hex_slam {
namespace {

struct Args {
  std::string mode;
  std::string trajectory;
  std::string reference;  // relations or ground truth
  double offset = 0.0;
  double max_gap = logs::LookupOptions().max_gap;
  double rpe_delta = logs::TrajectoryErrorOptions().rpe_delta;
  Pose2 sensor_pose;  // identity: the trajectory's own frame
};

constexpr char kPoseLookup[] =
    "Poses are taken at the same stamp (within 1 ms), else interpolated between the two around it "
    "if they are at most --max-gap apart; other times are skipped.";

// The options both modes share.
void DeclareCommon(CLI::App* mode, Args* args) {
  mode->add_option("--trajectory", args->trajectory, "the trajectory to score (TUM)")
      ->required()
      ->check(cli::NonEmpty());
  cli::AddNumber(mode, "--max-gap", &args->max_gap,
                 "the widest gap (s) between two poses to interpolate across (default 0.1)", 0.0);
  cli::AddPose(mode, "--sensor-pose", &args->sensor_pose,
               "evaluate the frame mounted at x,y,yaw on the trajectory's (e.g. the laser, when "
               "the reference is of the laser and the trajectory of the base)",
               CheckSensorPose);
  mode->footer(kPoseLookup);
}

void Declare(CLI::App* app, Args* args) {
  app->description("A trajectory's accuracy against reference data; ends with one RESULT line.");
  app->require_subcommand(1);
  CLI::App* relations = app->add_subcommand(
      "relations",
      "mean ± std of the translational (m) and rotational (deg) errors and of their squares over "
      "the relations (Kümmerle et al. 2009)");
  DeclareCommon(relations, args);
  relations->add_option("--relations", args->reference, "the relations file")
      ->required()
      ->check(cli::NonEmpty());
  cli::AddNumber(relations, "--offset", &args->offset,
                 "added to the trajectory's stamps (s) to reach the relations' clock");
  CLI::App* ate = app->add_subcommand(
      "ate",
      "RMSE of the positions after the SE(2) alignment that fits them best, and RPE over "
      "--rpe-delta seconds");
  DeclareCommon(ate, args);
  ate->add_option("--ground-truth", args->reference, "the ground truth (TUM)")
      ->required()
      ->check(cli::NonEmpty());
  cli::AddNumber(ate, "--rpe-delta", &args->rpe_delta, "the RPE's interval (s, default 1)");
  for (CLI::App* mode : {relations, ate}) {
    mode->callback([args, mode] { args->mode = mode->get_name(); });
  }
}

// CLI11 would only say that a mode is required: name the word it did not take for one.
std::string UnknownMode(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return "";
  const std::string word = argv[1];
  if (word == "relations" || word == "ate") return "";
  return "unknown mode '" + word + "' (relations or ate)";
}

// Empty, or what is wrong with the values.
std::string CheckArgs(const Args& args) {
  if (!(args.rpe_delta > 0.0)) return "--rpe-delta must be > 0";
  if (!(std::abs(args.offset) < kMaxRosTime)) return "--offset must lie within ±2^32 s (ROS time)";
  return "";
}

// The inputs are bounded (trajectory_io.h, relations.h), so every figure is finite; should one
// not be, the tool says so and fails rather than print inf or nan as a result.
bool AllFinite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) {
      std::fprintf(stderr, "error: a result is not a finite number; no RESULT line\n");
      return false;
    }
  }
  return true;
}

void PrintStatistic(const char* what, const logs::SampleStatistics& s, const char* unit) {
  std::printf("  %-22s %10.5f ± %-10.5f %s  (median %.5f, max %.5f)\n", what, s.mean, s.stddev,
              unit, s.median, s.max);
}

int Relations(const Args& args, const std::vector<io::StampedPose>& trajectory) {
  std::vector<logs::Relation> relations;
  const std::string error = logs::ReadRelations(args.reference, &relations);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  logs::RelationsOptions options;
  options.offset = args.offset;
  options.lookup.max_gap = args.max_gap;
  const logs::RelationsReport r = logs::EvaluateRelations(trajectory, relations, options);
  std::printf("relations: %d of %d have both poses in the trajectory (%zu poses)\n", r.evaluated,
              r.relations, trajectory.size());
  if (r.evaluated == 0) {
    std::fprintf(stderr, "error: no relation falls inside the trajectory's time span; are the "
                         "clocks the same (see --offset)?\n");
    return 1;
  }
  if (!AllFinite({r.translation.mean, r.translation.stddev, r.translation_squared.mean,
                  r.translation_squared.stddev, r.rotation.mean, r.rotation.stddev,
                  r.rotation_squared.mean, r.rotation_squared.stddev, r.translation.median,
                  r.translation.max, r.rotation.median, r.rotation.max,
                  r.translation_squared.median, r.translation_squared.max,
                  r.rotation_squared.median, r.rotation_squared.max})) {
    return 1;
  }
  PrintStatistic("translation", r.translation, "m");
  PrintStatistic("translation squared", r.translation_squared, "m²");
  PrintStatistic("rotation", r.rotation, "deg");
  PrintStatistic("rotation squared", r.rotation_squared, "deg²");
  std::printf("RESULT relations=%d evaluated=%d trans_mean_m=%.6f trans_std_m=%.6f "
              "trans_sq_mean_m2=%.6f trans_sq_std_m2=%.6f rot_mean_deg=%.5f rot_std_deg=%.5f "
              "rot_sq_mean_deg2=%.5f rot_sq_std_deg2=%.5f\n",
              r.relations, r.evaluated, r.translation.mean, r.translation.stddev,
              r.translation_squared.mean, r.translation_squared.stddev, r.rotation.mean,
              r.rotation.stddev, r.rotation_squared.mean, r.rotation_squared.stddev);
  return 0;
}

int Ate(const Args& args, const std::vector<io::StampedPose>& trajectory) {
  std::vector<io::StampedPose> truth;
  const std::string error = io::ReadTumTrajectory(args.reference, &truth);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  logs::TrajectoryErrorOptions options;
  options.lookup.max_gap = args.max_gap;
  options.rpe_delta = args.rpe_delta;
  const logs::TrajectoryErrorReport r = logs::EvaluateTrajectory(trajectory, truth, options);
  if (!AllFinite({r.alignment.x, r.alignment.y, r.alignment.theta, r.ate_translation.rmse,
                  r.ate_translation.mean, r.ate_translation.max, r.ate_rotation.rmse,
                  r.rpe_translation.rmse, r.rpe_rotation.rmse})) {
    return 1;
  }
  std::printf("ate: %d of %d poses have a ground-truth pose; alignment x=%.4f y=%.4f yaw=%.5f\n",
              r.matched, r.poses, r.alignment.x, r.alignment.y, r.alignment.theta);
  if (r.matched < 2) {
    std::fprintf(stderr, "error: fewer than two poses share a time with the ground truth\n");
    return 1;
  }
  std::printf("  ATE translation RMSE %.5f m (mean %.5f, max %.5f); rotation RMSE %.4f deg\n",
              r.ate_translation.rmse, r.ate_translation.mean, r.ate_translation.max,
              r.ate_rotation.rmse);
  std::printf("  RPE over %.2f s: translation RMSE %.5f m, rotation RMSE %.4f deg (%d pairs)\n",
              args.rpe_delta, r.rpe_translation.rmse, r.rpe_rotation.rmse, r.rpe_translation.count);
  std::printf("RESULT poses=%d matched=%d ate_rmse_m=%.6f ate_mean_m=%.6f ate_max_m=%.6f "
              "ate_rot_rmse_deg=%.5f rpe_pairs=%d rpe_trans_rmse_m=%.6f rpe_rot_rmse_deg=%.5f\n",
              r.poses, r.matched, r.ate_translation.rmse, r.ate_translation.mean,
              r.ate_translation.max, r.ate_rotation.rmse, r.rpe_translation.count,
              r.rpe_translation.rmse, r.rpe_rotation.rmse);
  return 0;
}

int Main(int argc, char** argv) {
  Args args;
  if (const std::string error = UnknownMode(argc, argv); !error.empty()) {
    return cli::UsageError("hex_slam_eval", error);
  }
  if (const std::optional<int> status = cli::ParseCommandLine(
          "hex_slam_eval", argc, argv, [&args](CLI::App* app) { Declare(app, &args); },
          [&args] { return CheckArgs(args); })) {
    return *status;
  }
  std::vector<io::StampedPose> trajectory;
  const std::string error = io::ReadTumTrajectory(args.trajectory, &trajectory);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  if (trajectory.empty()) {
    std::fprintf(stderr, "error: %s holds no poses\n", args.trajectory.c_str());
    return 1;
  }
  for (io::StampedPose& p : trajectory) p.pose = p.pose * args.sensor_pose;
  return args.mode == "relations" ? Relations(args, trajectory) : Ate(args, trajectory);
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::RunToolMain(hex_slam::Main, argc, argv); }
