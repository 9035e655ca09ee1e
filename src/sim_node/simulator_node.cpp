#include "simulator_node.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/LaserScan.h>
#include <std_msgs/Bool.h>

#include <ros/callback_queue.h>
#include <ros/package.h>

#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/path_file.h"
#include "hex_slam/sim/waypoint_path.h"
#include "pose_msgs.h"
#include "rosparam_reader.h"

namespace hex_slam {
namespace {

// Simulated time starts here, not at 0: tf treats a zero stamp as "latest".
constexpr double kSimTimeStart = 1.0;  // s
// The odometry message's covariance: what the drift model adds over one step, floored so
// consumers that invert it never see zeros.
constexpr double kMinCovariance = 1e-9;

// Every private parameter goes through the options' table (read by the node's own loader):
// unknown keys are errors, as for the core's options.
void LoadParameters(const ros::NodeHandle& private_node, ParameterTable* table) {
  const PrivateParameters params = ReadPrivateParameters(private_node);
  if (!params.error.empty()) throw std::runtime_error(params.error);
  std::vector<std::string> errors = table->Apply(params.values);
  for (const std::string& key : params.non_scalar_keys) {
    errors.push_back("parameter '" + key + "' must be a single value, not a list or dictionary");
  }
  if (!errors.empty()) {
    std::ostringstream s;
    s << "bad parameters:";
    for (const std::string& e : errors) s << "\n  " << e;
    throw std::runtime_error(s.str());
  }
}

}  // namespace

SimulatorNode::SimulatorNode(ros::NodeHandle node, ros::NodeHandle private_node)
    : node_(node) {
  ParameterTable table = sim::SimulatorParameterTable(&options_);
  LoadParameters(private_node, &table);
  const std::vector<std::string> errors = options_.Validate();
  if (!errors.empty()) {
    std::ostringstream s;
    s << "invalid parameters:";
    for (const std::string& e : errors) s << "\n  " << e;
    throw std::runtime_error(s.str());
  }
  std::string error = sim::LoadImageWorld(options_.world, sim::ImageWorldOptions(), &world_);
  if (!error.empty()) throw std::runtime_error("world: " + error);
  std::vector<Pose2> path;
  if (!options_.path.empty()) {
    sim::WaypointPath waypoints;
    error = sim::ReadWaypointPath(options_.path, &waypoints);
    if (!error.empty()) throw std::runtime_error("path: " + error);
    sim::PathMotion motion = options_.motion;
    motion.rate = options_.rate;
    path = sim::SampleWaypointPath(waypoints.waypoints, waypoints.start_heading, motion);
  }
  robot_ = std::make_unique<sim::SimulatedRobot>(world_, path, options_.start, options_.robot);
  odometry_ = std::make_unique<sim::DriftingOdometry>(
      options_.odometry, static_cast<std::uint64_t>(options_.seed) + 1, Pose2());
  rng_.seed(static_cast<std::uint64_t>(options_.seed));

  node.param("/use_sim_time", sim_time_, false);
  scan_pub_ = node.advertise<sensor_msgs::LaserScan>("scan", 10);
  odom_pub_ = node.advertise<nav_msgs::Odometry>("odom", 10);
  truth_pub_ = node.advertise<nav_msgs::Odometry>("base_pose_ground_truth", 10);
  finished_pub_ = node.advertise<std_msgs::Bool>("path_finished", 1, true);
  if (sim_time_) clock_pub_ = node.advertise<rosgraph_msgs::Clock>("/clock", 10);
  cmd_sub_ = node.subscribe("cmd_vel", 10, &SimulatorNode::OnCommand, this);
  SubscribeLockstep(options_.lockstep_topics, false);
  SubscribeLockstep(options_.lockstep_late_topics, true);
  if (!lockstep_.empty() && !sim_time_) {
    throw std::runtime_error("lockstep topics need /use_sim_time: the simulator is the clock");
  }

  std_msgs::Bool finished;
  finished.data = false;
  finished_pub_.publish(finished);
  ROS_INFO("hex_slam_sim: world %s (%d x %d px of %.3f m), %s, %d beams at %.1f Hz, %s time%s",
           options_.world.c_str(), world_.width(), world_.height(), world_.resolution(),
           path.empty() ? "no path (waiting for cmd_vel)" : ("path " + options_.path).c_str(),
           options_.lidar.beams, options_.rate, sim_time_ ? "simulated" : "wall",
           sim_time_ ? (" x" + std::to_string(options_.real_time_factor)).c_str() : "");
}

void SimulatorNode::SubscribeLockstep(const std::string& topics, bool late) {
  std::istringstream words(topics);
  std::string word;
  while (words >> word) {
    const std::size_t colon = word.find(':');
    if (colon != std::string::npos) {
      const std::string package = word.substr(0, colon);
      word = word.substr(colon + 1);
      if (ros::package::getPath(package).empty()) {
        ROS_INFO("hex_slam_sim: %s is not installed: not waiting for %s", package.c_str(),
                 word.c_str());
        continue;
      }
    }
    lockstep_.push_back(std::make_unique<Lockstep>());
    Lockstep* topic = lockstep_.back().get();
    topic->topic = word;
    topic->late = late;
    // Poses come one per scan: a queue long enough that none is lost while a step waits.
    constexpr int kPoseQueue = 100;
    topic->subscriber = node_.subscribe<geometry_msgs::PoseStamped>(
        word, kPoseQueue, [this, topic](const geometry_msgs::PoseStamped::ConstPtr& pose) {
          OnLockstepPose(pose, topic);
        });
  }
}

void SimulatorNode::OnLockstepPose(const geometry_msgs::PoseStamped::ConstPtr& pose,
                                   Lockstep* topic) {
  topic->latest = std::max(topic->latest, pose->header.stamp);
  topic->answered = true;
}

bool SimulatorNode::LockstepReady() const {
  for (const auto& topic : lockstep_) {
    if (!topic->answered && !topic->late) return false;
  }
  return true;
}

void SimulatorNode::WaitForLockstep(const ros::Time& stamp) {
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(options_.lockstep_timeout);
  // A callback's arrival ends each wait at once; the slice only bounds a missed wake-up.
  const ros::WallDuration slice(0.01);
  for (const auto& topic : lockstep_) {
    while (topic->answered && topic->latest < stamp && ros::ok()) {
      if (ros::WallTime::now() > give_up) {
        ++lockstep_timeouts_;
        ROS_WARN("hex_slam_sim: no pose on %s for the scan at %.3f s within %.1f s (wall); "
                 "going on (%ld such steps)",
                 topic->topic.c_str(), stamp.toSec(), options_.lockstep_timeout,
                 lockstep_timeouts_);
        return;
      }
      ros::getGlobalCallbackQueue()->callAvailable(slice);
    }
  }
}

void SimulatorNode::OnCommand(const geometry_msgs::Twist& twist) {
  robot_->CommandVelocity(twist.linear.x, twist.angular.z, now_.toSec());
}

void SimulatorNode::PublishStaticLaser(const ros::Time& stamp) {
  static_tf_.sendTransform(
      ToTransformStampedMsg(options_.laser_mount, stamp, options_.base_frame, options_.laser_frame));
}

void SimulatorNode::Step(const ros::Time& stamp, bool move) {
  const double dt = 1.0 / options_.rate;
  const Pose2 truth = move ? robot_->Step(stamp.toSec(), dt) : robot_->pose();
  const Pose2 odom = odometry_->Update(truth);

  tf_.sendTransform(ToTransformStampedMsg(odom, stamp, options_.odom_frame, options_.base_frame));

  nav_msgs::Odometry odom_msg;
  odom_msg.header.stamp = stamp;
  odom_msg.header.frame_id = options_.odom_frame;
  odom_msg.child_frame_id = options_.base_frame;
  odom_msg.pose.pose = ToPoseMsg(odom);
  odom_msg.twist.twist.linear.x = move ? robot_->linear_velocity() : 0.0;
  odom_msg.twist.twist.angular.z = move ? robot_->angular_velocity() : 0.0;
  const double step = odom_msg.twist.twist.linear.x * dt;
  const double var_xy = std::max(kMinCovariance, std::pow(options_.odometry.translation_stddev, 2) *
                                                     std::abs(step));
  const double var_yaw = std::max(
      kMinCovariance, std::pow(options_.odometry.rotation_stddev_per_distance, 2) * std::abs(step));
  odom_msg.pose.covariance[0] = odom_msg.pose.covariance[7] = var_xy;
  odom_msg.pose.covariance[35] = var_yaw;
  odom_pub_.publish(odom_msg);

  nav_msgs::Odometry truth_msg = odom_msg;
  truth_msg.header.frame_id = options_.ground_truth_frame;
  truth_msg.pose.pose = ToPoseMsg(truth);
  truth_msg.pose.covariance = {};
  truth_pub_.publish(truth_msg);

  const LaserScan scan =
      sim::SimulateScan(world_, truth * options_.laser_mount, options_.lidar, stamp.toSec(), &rng_);
  sensor_msgs::LaserScan scan_msg;
  scan_msg.header.stamp = stamp;
  scan_msg.header.frame_id = options_.laser_frame;
  scan_msg.angle_min = static_cast<float>(scan.angle_min);
  scan_msg.angle_max = static_cast<float>(scan.angle_max);
  scan_msg.angle_increment = static_cast<float>(scan.angle_increment);
  scan_msg.time_increment = 0.0f;  // every beam at the stamp: the robot does not move during it
  scan_msg.scan_time = static_cast<float>(dt);
  scan_msg.range_min = static_cast<float>(scan.range_min);
  scan_msg.range_max = static_cast<float>(scan.range_max);
  scan_msg.ranges = scan.ranges;
  scan_pub_.publish(scan_msg);

  if (robot_->path_finished() && !announced_finish_) {
    announced_finish_ = true;
    std_msgs::Bool finished;
    finished.data = true;
    finished_pub_.publish(finished);
    ROS_INFO("hex_slam_sim: the path is finished at t = %.1f s", stamp.toSec());
  }
}

void SimulatorNode::Run() {
  const double dt = 1.0 / options_.rate;
  const ros::WallTime start_moving = ros::WallTime::now() + ros::WallDuration(options_.start_delay);
  if (sim_time_) {
    now_ = ros::Time(kSimTimeStart);
    const ros::WallDuration pause(dt / options_.real_time_factor);
    rosgraph_msgs::Clock clock;
    clock.clock = now_;
    clock_pub_.publish(clock);
    PublishStaticLaser(now_);
    // With lockstep, the robot moves start_delay simulated seconds after every node answered.
    std::optional<ros::Time> ready_at;
    while (ros::ok()) {
      ros::WallTime wake = ros::WallTime::now() + pause;
      now_ += ros::Duration(dt);
      clock.clock = now_;
      clock_pub_.publish(clock);
      ros::spinOnce();  // commands received up to now act on this step
      bool move = ros::WallTime::now() >= start_moving;
      if (!options_.lockstep_topics.empty()) {
        if (!ready_at && LockstepReady()) ready_at = now_;
        move = ready_at && (now_ - *ready_at).toSec() >= options_.start_delay;
      }
      Step(now_, move);
      WaitForLockstep(now_);
      ros::WallTime::sleepUntil(wake);
    }
  } else {
    ros::WallRate rate(options_.rate);
    now_ = ros::Time::now();
    PublishStaticLaser(now_);
    while (ros::ok()) {
      now_ = ros::Time::now();
      ros::spinOnce();
      Step(now_, ros::WallTime::now() >= start_moving);
      rate.sleep();
    }
  }
}

}  // namespace hex_slam
