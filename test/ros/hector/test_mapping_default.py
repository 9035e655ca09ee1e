#!/usr/bin/python3
"""rostest checker of hector/mapping_default.test: hector_mapping's own launch settings on a real
bag, played in lockstep (bag_replay.LockstepPlayer)."""
import math
import os
import sys
import threading
import unittest

import rospy
import rostest
import tf2_ros
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Pose, PoseStamped, TransformStamped
from hex_slam.srv import ResetMapping
from nav_msgs.msg import MapMetaData, OccupancyGrid
from nav_msgs.srv import GetMap

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # test/ros
import bag_replay  # noqa: E402
import ros_test_util as util  # noqa: E402

BAG = "ccny_demo/laser_scan_matcher_demo.bag"
BEFORE_RESTART = 300   # scans played before restart_mapping_with_new_pose
RESTART_POSE = (2.0, -1.0, 0.5)  # x, y, yaw
# A hand-held walk at 10 Hz moves a few cm a scan: the first pose after the restart is the
# given one, moved by at most one scan's motion.
MAX_RESTART_OFFSET = 0.15  # m
MIN_POSED_FRACTION = 0.99
# With tf_timeout 2 s a wait on the missing nav frame would take 2 s a scan; a scan's work is
# ~1 ms, so even a crowded machine stays far below this.
MAX_SCAN_WORK_MS = 1000.0
START_TIMEOUT = 30.0  # wall s for the node to come up


class MappingDefaultTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.latest = {}
        self.poses = []

    def keep(self, key):
        def store(msg):
            with self.lock:
                self.latest[key] = msg
        return store

    def on_pose(self, msg):
        with self.lock:
            self.poses.append((msg.header.stamp, util.planar(msg.pose)))

    def values(self):
        with self.lock:
            diagnostics = self.latest.get("diagnostics")
        for status in getattr(diagnostics, "status", []):
            if status.name.endswith("scan matching"):
                return {kv.key: kv.value for kv in status.values}
        return {}

    def test_hector_users_setup_on_a_real_bag(self):
        bag = os.path.join(bag_replay.data_dir(), BAG)
        if not os.path.exists(bag):
            self.skipTest("%s not found (set HEX_SLAM_DATA_DIR)" % bag)
        rospy.init_node("test_mapping_default")
        rospy.Subscriber("map_metadata", MapMetaData, self.keep("metadata"))
        rospy.Subscriber("map", OccupancyGrid, self.keep("map"))
        rospy.Subscriber("diagnostics", DiagnosticArray, self.keep("diagnostics"))
        rospy.Subscriber("slam_out_pose", PoseStamped, self.on_pose, queue_size=1000)
        player = bag_replay.LockstepPlayer(bag)
        # What a user adds for a bag without tf: the laser at base_footprint.
        mount = TransformStamped()
        mount.header.frame_id = "base_footprint"
        mount.child_frame_id = "laser"
        mount.transform.rotation.w = 1.0
        broadcaster = tf2_ros.StaticTransformBroadcaster()  # noqa: F841 (kept alive)
        broadcaster.sendTransform(mount)
        self.assertTrue(player.wait_for_subscriber(START_TIMEOUT), "the node did not subscribe")

        # Latched at start-up, before any scan (hector publishes its metadata at once too).
        self.assertTrue(util.wait_for_wall(lambda: "metadata" in self.latest, 10.0),
                        "no map_metadata before the first scan")
        self.assertAlmostEqual(self.latest["metadata"].resolution, 0.05, places=6)

        tf_buffer = tf2_ros.Buffer(cache_time=rospy.Duration(600.0))
        listener = tf2_ros.TransformListener(tf_buffer)  # noqa: F841 (kept alive)
        player.play(BEFORE_RESTART)
        with self.lock:
            last_stamp, last_pose = self.poses[-1]
        restart = rospy.ServiceProxy("restart_mapping_with_new_pose", ResetMapping)
        dynamic_map = rospy.ServiceProxy("dynamic_map", GetMap)
        before_restart = len(self.poses)

        # map -> nav although nothing publishes nav: hector's identity odometry, so nav stands
        # at the estimate.
        self.assertTrue(util.wait_for_wall(lambda: tf_buffer.can_transform("map", "nav", last_stamp), 10.0))
        t = tf_buffer.lookup_transform("map", "nav", last_stamp)
        distance, heading = util.pose_error(util.planar_transform(t.transform), last_pose)
        self.assertLess(distance, 1e-6)
        self.assertLess(heading, 1e-6)

        # Every scan so far posed, none after a wait for the missing frame; the levels asked for.
        values = self.values() or (util.wait_for_wall(lambda: self.values(), 10.0) and self.values())
        print("mapping_default: " + " ".join("%s=%s" % kv for kv in sorted(values.items())))
        self.assertGreaterEqual(before_restart, MIN_POSED_FRACTION * BEFORE_RESTART)
        self.assertEqual(player.unanswered, 0)
        self.assertLess(float(values["callback_max_ms"]), MAX_SCAN_WORK_MS)
        self.assertEqual(values["map_levels"], "2")
        self.assertEqual(values["dropped_queue_overflow"], "0")
        self.assertTrue(util.wait_for_wall(lambda: "map" in self.latest, 10.0))
        self.assertAlmostEqual(self.latest["map"].info.resolution, 0.05, places=6)
        known_before = util.known_cells(dynamic_map().map)

        # restart_mapping_with_new_pose: the map starts again, from the given pose.
        request = Pose()
        request.position.x, request.position.y = RESTART_POSE[0], RESTART_POSE[1]
        request.orientation.z = math.sin(RESTART_POSE[2] / 2.0)
        request.orientation.w = math.cos(RESTART_POSE[2] / 2.0)
        restart(initial_pose=request)
        played = player.play()
        self.assertEqual(player.unanswered, 0)
        with self.lock:
            after = self.poses[before_restart:]
        self.assertGreaterEqual(len(after), MIN_POSED_FRACTION * played)
        distance, heading = util.pose_error(after[0][1], RESTART_POSE)
        print("mapping_default: first pose after the restart %.3f m, %.3f rad from the one given"
              % (distance, heading))
        self.assertLess(distance, MAX_RESTART_OFFSET)
        total = BEFORE_RESTART + played
        self.assertGreaterEqual(len(self.poses), MIN_POSED_FRACTION * total)
        print("mapping_default: %d of %d scans posed" % (len(self.poses), total))
        # A fresh map: the walk's last seconds see far less than the whole office.
        known_after = util.known_cells(dynamic_map().map)
        print("mapping_default: %d known pixels before the restart, %d after" %
              (known_before, known_after))
        self.assertLess(known_after, 0.8 * known_before)


if __name__ == "__main__":
    rostest.rosrun("hex_slam", "mapping_default", MappingDefaultTest, sys.argv)
