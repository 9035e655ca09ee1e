#!/usr/bin/python3
"""rostest of hex_slam_sim alone (test/sim_ros/sim_node.test): collects a few simulated seconds
of its output and checks frames, rates, the tf tree, the scan's geometry against the known maze,
and that cmd_vel takes over from the path."""
import math
import sys
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import PoseStamped, Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan

PKG = "hex_slam"
COLLECT = 4.0  # simulated seconds, at least
TRAVEL = 0.6  # m the robot drives before the checks
RATE = 10.0
LASER_X = 0.1  # the launch file's laser_x
# worlds/maze: the robot starts at (0.05, 4.95) facing +x; the outer wall's inner face is at
# y = 5.38, the first inner wall ahead has its face at x = 0.89.
START = (0.05, 4.95)
UP_WALL, AHEAD_WALL = 5.38 - 4.95, 0.89 - START[0] - LASER_X


def yaw(q):
    return 2.0 * math.atan2(q.z, q.w)


class SimNodeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("sim_node_test")
        cls.scans, cls.odoms, cls.truths, cls.clocks = [], [], [], []
        cls.seen = rospy.Publisher("~seen", PoseStamped, queue_size=100)
        rospy.Subscriber("scan", LaserScan, cls.scans.append)
        rospy.Subscriber("odom", Odometry, cls.odoms.append)
        rospy.Subscriber("base_pose_ground_truth", Odometry, cls.on_truth)
        rospy.Subscriber("/clock", Clock, cls.clocks.append)
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        # Until the robot has left its start (it waits there until this test answers, then
        # start_delay) and driven a little.
        deadline = rospy.get_rostime() + rospy.Duration(120.0)
        while not rospy.is_shutdown() and rospy.get_rostime() < deadline:
            rospy.sleep(0.05)
            if len(cls.truths) >= 2 and len(cls.scans) >= COLLECT * RATE:
                p0, p1 = cls.truths[0].pose.pose.position, cls.truths[-1].pose.pose.position
                if math.hypot(p1.x - p0.x, p1.y - p0.y) > TRAVEL:
                    break

    @classmethod
    def on_truth(cls, msg):
        cls.truths.append(msg)
        # The simulator's lockstep topic (sim_node.test): answered only once scans and odometry
        # arrive too, so the robot stands at its start until every list here begins there,
        # however late this test came up.
        if cls.scans and cls.odoms:
            cls.seen.publish(PoseStamped(header=msg.header, pose=msg.pose.pose))

    def test_scans(self):
        self.assertGreaterEqual(len(self.scans), COLLECT * RATE)
        first = self.scans[0]
        self.assertEqual(first.header.frame_id, "laser")
        self.assertEqual(len(first.ranges), 360)
        self.assertAlmostEqual(first.angle_increment, 2 * math.pi / 360, places=6)
        self.assertAlmostEqual(first.angle_min, -math.pi, places=6)
        for scan in self.scans:
            for r in scan.ranges:
                self.assertTrue(math.isinf(r) or scan.range_min <= r <= scan.range_max, r)
        # 10 Hz in simulated time, one scan per step.
        stamps = [s.header.stamp.to_sec() for s in self.scans]
        for a, b in zip(stamps, stamps[1:]):
            self.assertAlmostEqual(b - a, 1.0 / RATE, places=6)

    def test_scan_sees_the_maze_where_it_is(self):
        # The scan taken at the start pose (the robot turns or drives only afterwards). The first
        # scans may have come before the first truth: the first five that have one.
        truth_by_stamp = {t.header.stamp: t for t in self.truths}
        checked = 0
        for scan in [s for s in self.scans if s.header.stamp in truth_by_stamp][:5]:
            truth = truth_by_stamp[scan.header.stamp]
            p = truth.pose.pose.position
            if abs(p.x - START[0]) > 1e-6 or abs(yaw(truth.pose.pose.orientation)) > 1e-6:
                continue
            up = int(round((math.pi / 2 - scan.angle_min) / scan.angle_increment))
            ahead = int(round((0.0 - scan.angle_min) / scan.angle_increment))
            self.assertAlmostEqual(scan.ranges[up], UP_WALL, delta=0.05)
            self.assertAlmostEqual(scan.ranges[ahead], AHEAD_WALL, delta=0.05)
            self.assertTrue(math.isinf(scan.ranges[0]))  # straight back: the open entrance
            checked += 1
        self.assertGreater(checked, 0, "no scan at the start pose")

    def test_odometry_and_ground_truth(self):
        self.assertGreaterEqual(len(self.odoms), COLLECT * RATE)
        self.assertGreaterEqual(len(self.truths), COLLECT * RATE)
        self.assertEqual(self.odoms[0].header.frame_id, "odom")
        self.assertEqual(self.odoms[0].child_frame_id, "base_link")
        self.assertEqual(self.truths[0].header.frame_id, "world")
        first, last = self.truths[0].pose.pose.position, self.truths[-1].pose.pose.position
        self.assertAlmostEqual(first.x, START[0], places=6)
        self.assertAlmostEqual(first.y, START[1], places=6)
        travelled = math.hypot(last.x - first.x, last.y - first.y)
        self.assertGreater(travelled, TRAVEL)
        # Odometry starts at zero and drifts a little from the truth's motion.
        o0, o1 = self.odoms[0].pose.pose.position, self.odoms[-1].pose.pose.position
        self.assertAlmostEqual(math.hypot(o0.x, o0.y), 0.0, places=6)
        self.assertAlmostEqual(math.hypot(o1.x - o0.x, o1.y - o0.y), travelled, delta=0.1)
        self.assertGreater(self.odoms[-1].twist.twist.linear.x, 0.0)
        self.assertGreater(len(self.clocks), 0)

    def test_tf_tree(self):
        # The newest scan whose odometry message has arrived too: the subscribers keep
        # appending while the test runs, and a scan may come in before its step's odometry.
        odom_stamps = [o.header.stamp for o in list(self.odoms)]
        stamp = max(s.header.stamp for s in list(self.scans) if s.header.stamp in odom_stamps)
        base = self.tf_buffer.lookup_transform("odom", "base_link", stamp, rospy.Duration(2.0))
        odom = [o for o in self.odoms if o.header.stamp == stamp]
        self.assertEqual(len(odom), 1)
        self.assertAlmostEqual(base.transform.translation.x, odom[0].pose.pose.position.x, places=6)
        laser = self.tf_buffer.lookup_transform("base_link", "laser", rospy.Time(0),
                                                rospy.Duration(2.0))
        self.assertAlmostEqual(laser.transform.translation.x, LASER_X, places=9)
        self.tf_buffer.lookup_transform("odom", "laser", stamp, rospy.Duration(2.0))

    def test_zz_cmd_vel_takes_over(self):  # runs last: it stops the path
        pub = rospy.Publisher("cmd_vel", Twist, queue_size=1)
        twist = Twist()
        twist.angular.z = 1.0
        deadline = rospy.get_rostime() + rospy.Duration(10.0)
        while abs(self.truths[-1].twist.twist.angular.z - 1.0) > 1e-6:  # until it takes over
            self.assertLess(rospy.get_rostime(), deadline, "cmd_vel never took over")
            pub.publish(twist)
            rospy.sleep(0.05)
        before = self.truths[-1]
        start = rospy.get_rostime()
        while rospy.get_rostime() - start < rospy.Duration(1.0) and not rospy.is_shutdown():
            pub.publish(twist)
            rospy.sleep(0.05)
        after = self.truths[-1]
        p0, p1 = before.pose.pose.position, after.pose.pose.position
        self.assertLess(math.hypot(p1.x - p0.x, p1.y - p0.y), 0.05)  # turning in place
        self.assertAlmostEqual(after.twist.twist.angular.z, 1.0, places=6)


if __name__ == "__main__":
    rostest.rosrun(PKG, "sim_node_test", SimNodeTest, sys.argv)
