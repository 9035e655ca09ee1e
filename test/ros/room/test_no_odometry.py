#!/usr/bin/python3
"""rostest checker: hex_slam_node without odometry (odom_frame = base_frame, as hector_mapping
is mostly run) publishes map->base_link itself and tracks the robot from scans alone."""
import os
import sys
import unittest

import rospy
import rostest
import tf2_ros

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # test/ros
import ros_test_util as util  # noqa: E402

# The bound of test_room_mapping.py. Without odometry each match starts from the previous scan's
# motion, off by a whole step (4 cm or 0.075 rad at 20 Hz) when the robot starts or stops
# turning, well inside the 0.2 m basin of the coarsest level: the result is as precise.
MAX_POSITION_ERROR = 0.05  # m
MAX_HEADING_ERROR = 0.02   # rad
DISTANCE = 9.0  # m: two legs and three turns of the loop


class NoOdometryTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_no_odometry")
        cls.rec = util.Recorder()
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        util.wait_for(lambda: cls.rec.travelled >= DISTANCE, 40.0)

    def test_pose_follows_the_truth_from_scans_alone(self):
        self.assertGreaterEqual(self.rec.travelled, DISTANCE)
        errors = self.rec.matched_errors()
        self.assertGreater(len(errors), 200)
        worst = max(e[1] for e in errors)
        worst_heading = max(e[2] for e in errors)
        print("no odometry: %d scans, worst %.4f m, %.4f rad" % (len(errors), worst,
                                                                 worst_heading))
        self.assertLess(worst, MAX_POSITION_ERROR)
        self.assertLess(worst_heading, MAX_HEADING_ERROR)

    def test_tf_is_map_to_base_link_directly(self):
        stamp, pose = self.rec.latest_pose()
        t = self.tf_buffer.lookup_transform("map", "base_link", stamp, rospy.Duration(2.0))
        self.assertEqual(t.child_frame_id, "base_link")
        tf_pose = (t.transform.translation.x, t.transform.translation.y,
                   util.yaw_of(t.transform.rotation))
        distance, heading = util.pose_error(tf_pose, pose)
        self.assertLess(distance, 1e-3)
        self.assertLess(heading, 1e-3)
        self.assertFalse(self.tf_buffer._frameExists("odom"), "an odom frame appeared")

    def test_no_odometry_was_looked_up(self):
        d = util.wait_for(lambda: self.rec.diagnostics, 5.0)
        self.assertEqual(d["no_odometry"], "0")
        self.assertEqual(d["dropped_invalid"], "0")


if __name__ == "__main__":
    rostest.rosrun("hex_slam", "no_odometry", NoOdometryTest, sys.argv)
