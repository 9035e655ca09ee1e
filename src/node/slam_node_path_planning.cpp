// SlamNode's plan_path service (nav_msgs/GetPlan, as move_base's make_plan): the shortest path on
// the current hex map, on the map thread from its snapshot, so planning never delays a scan.
// The plan is also published, latched, on planned_path for rviz.
#include <cmath>

#include <nav_msgs/Path.h>

#include "hex_slam/planning/hex_planner.h"
#include "ros_input/msg_conversion.h"
#include "pose_msgs.h"
#include "slam_node.h"

namespace hex_slam {
namespace node {

bool SlamNode::OnPlanPath(nav_msgs::GetPlan::Request& request,
                          nav_msgs::GetPlan::Response& response) {
  response.plan.header.frame_id = options_.map_frame;
  response.plan.header.stamp = ros::Time::now();
  auto refuse = [this, &response](const std::string& why) {
    ROS_WARN("hex_slam: plan_path: %s", why.c_str());
    planned_path_pub_.publish(response.plan);  // an empty path clears rviz's display
    return true;                               // an empty plan is GetPlan's "no path"
  };
  for (const geometry_msgs::PoseStamped* p : {&request.start, &request.goal}) {
    const std::string frame = CleanFrameId(p->header.frame_id);
    if (!frame.empty() && frame != options_.map_frame) {
      return refuse("poses must be in the map frame '" + options_.map_frame + "', not '" + frame +
                    "'");
    }
  }
  Pose2 start = PoseFromMsg(request.start.pose);
  if (request.start.header.frame_id.empty()) {
    std::lock_guard<std::mutex> lock(mutex_);
    start = slam_.pose();  // no start given: from where the robot is
  }
  RefreshSnapshot();
  if (!snapshot_.hex) return refuse("planning needs the hex lattice (lattice: hex)");
  HexPlannerOptions planner = options_.planner;
  if (std::isfinite(request.tolerance) && request.tolerance > 0.0f) {
    planner.goal_tolerance = request.tolerance;
  }
  const Pose2 goal = PoseFromMsg(request.goal.pose);
  const HexPlan plan =
      PlanHexPath(snapshot_.hex->finest(), start.translation(), goal.translation(), planner);
  if (!plan.found) return refuse(plan.message);

  // A pose every cell spacing along the taut path, as move_base's global planners give.
  const std::vector<Eigen::Vector2d> points =
      ResamplePath(plan.waypoints, snapshot_.hex->finest().lattice().spacing());
  // Each pose faces the next point; the last takes the goal's heading, or (a goal without a
  // valid orientation) the last segment's.
  double final_heading = goal.theta;
  if (!std::isfinite(final_heading)) {
    const Eigen::Vector2d last = points.back() - points[points.size() >= 2 ? points.size() - 2 : 0];
    final_heading = std::atan2(last.y(), last.x());
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points[i];
    double heading = final_heading;
    if (i + 1 < points.size()) {
      const Eigen::Vector2d ahead = points[i + 1] - p;
      heading = std::atan2(ahead.y(), ahead.x());
    }
    geometry_msgs::PoseStamped pose;
    pose.header = response.plan.header;
    pose.pose = ToPoseMsg(Pose2(p.x(), p.y(), heading));
    response.plan.poses.push_back(pose);
  }
  planned_path_pub_.publish(response.plan);
  ROS_INFO("hex_slam: plan_path: %zu cells, %.2f m (%.2f m along the cells), %ld cells expanded",
           plan.cells.size(), plan.length, plan.cell_path_length,
           static_cast<long>(plan.expansions));
  return true;
}

void SlamNode::OnGoal(const geometry_msgs::PoseStamped::ConstPtr& goal) {
  nav_msgs::GetPlan::Request request;  // an empty start frame: from the robot's pose
  request.goal = *goal;
  nav_msgs::GetPlan::Response response;
  OnPlanPath(request, response);  // publishes planned_path either way
}

}  // namespace node
}  // namespace hex_slam
