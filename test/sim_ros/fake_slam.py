#!/usr/bin/python3
"""A stand-in SLAM for testing sim_evaluator: republishes the simulator's ground truth as
slam_out_pose in a map frame at the robot's start (as a SLAM would), exact while the robot stands
at its start and wrong by ~offset metres along x once it has moved. The evaluator must then
measure an RMSE a little below ~offset (the standing part is exact), never above it."""
import math

import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry

MOVED = 0.01  # m from the start: the robot has left it


def main():
    rospy.init_node("fake_slam")
    offset = rospy.get_param("~offset", 0.03)
    pub = rospy.Publisher("slam_out_pose", PoseStamped, queue_size=100)
    start = []

    def on_truth(msg):
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        theta = 2.0 * math.atan2(q.z, q.w)
        if not start:
            start.append((p.x, p.y, theta))
        x0, y0, t0 = start[0]
        error = offset if math.hypot(p.x - x0, p.y - y0) > MOVED else 0.0
        c, s = math.cos(t0), math.sin(t0)
        dx, dy = p.x - x0, p.y - y0
        out = PoseStamped()
        out.header.stamp = msg.header.stamp
        out.header.frame_id = "map"
        out.pose.position.x = c * dx + s * dy + error
        out.pose.position.y = -s * dx + c * dy
        out.pose.orientation.z = math.sin(0.5 * (theta - t0))
        out.pose.orientation.w = math.cos(0.5 * (theta - t0))
        pub.publish(out)

    rospy.Subscriber("base_pose_ground_truth", Odometry, on_truth, queue_size=100)
    rospy.spin()


if __name__ == "__main__":
    main()
