#!/usr/bin/python3
"""rostest checker: a real lidar log through hex_slam_node. Plays the CCNY scan_tools demo bag
(a hand-held Hokuyo walked through an office: /scan in frame "/laser" with tf1's leading slash,
no tf, no odometry) on its own clock and checks that every scan is matched, none dropped, and
that a map and a trajectory come out. Skipped when the data folder is absent."""
import os
import subprocess
import sys
import time
import unittest

import rospkg
import rospy
import rostest
from nav_msgs.msg import OccupancyGrid, Path
from diagnostic_msgs.msg import DiagnosticArray
from rosgraph_msgs.msg import Clock

BAG = "ccny_demo/laser_scan_matcher_demo.bag"
BAG_SCANS = 360
RATE = 4.0  # times real time: 36 s of log in 9 s


def data_dir():
    package = os.path.realpath(rospkg.RosPack().get_path("hex_slam"))
    return os.environ.get("HEX_SLAM_DATA_DIR",
                          os.path.normpath(os.path.join(package, "..", "shared", "data")))


class CcnyBagTest(unittest.TestCase):
    latest = {}

    @classmethod
    def keep(cls, key):
        return lambda msg: cls.latest.__setitem__(key, msg)

    def test_every_scan_of_the_real_log_is_matched(self):
        bag = os.path.join(data_dir(), BAG)
        if not os.path.exists(bag):
            self.skipTest("%s not found (set HEX_SLAM_DATA_DIR)" % bag)
        rospy.Subscriber("diagnostics", DiagnosticArray, self.keep("diagnostics"))
        rospy.Subscriber("map", OccupancyGrid, self.keep("map"))
        rospy.Subscriber("trajectory", Path, self.keep("trajectory"))
        rospy.Subscriber("clock", Clock, self.keep("clock"))
        clock_pub = rospy.Publisher("clock", Clock, queue_size=10)
        player = subprocess.run(["rosbag", "play", "--clock", "-q", "-d", "1", "-r", str(RATE),
                                 bag], capture_output=True, text=True, timeout=60)
        self.assertEqual(player.returncode, 0, player.stderr)
        # The bag's clock stops with the bag, and with it the node's timers: keep time going (on
        # the wall clock) until the last scans are reported.
        now = self.latest["clock"].clock
        deadline = time.time() + 10.0
        values = {}
        while time.time() < deadline:
            now += rospy.Duration(0.1)
            clock_pub.publish(Clock(clock=now))
            for status in getattr(self.latest.get("diagnostics"), "status", []):
                if status.name.endswith("scan matching"):
                    values = {kv.key: kv.value for kv in status.values}
            if int(values.get("scans_matched", 0)) >= BAG_SCANS - 5:
                break
            time.sleep(0.1)
        print("ccny bag: " + " ".join("%s=%s" % kv for kv in sorted(values.items())))
        # The subscriber queue may drop the odd scan while the node starts; none is rejected.
        self.assertGreaterEqual(int(values.get("scans_matched", 0)), BAG_SCANS - 5)
        for key in ("dropped_invalid", "dropped_late", "dropped_no_laser_transform", "errors"):
            self.assertEqual(values[key], "0", key)
        grid = self.latest.get("map")
        self.assertIsNotNone(grid)
        known = sum(1 for v in grid.data if v >= 0)
        occupied = sum(1 for v in grid.data if v == 100)
        print("ccny map: %d x %d pixels, %d known, %d occupied" % (grid.info.width,
                                                                  grid.info.height, known,
                                                                  occupied))
        # The walk covers a room of about 4 m x 5 m and a doorway: some 9000 pixels of 4.65 cm,
        # bounded by walls that each take one or two pixels (a smeared, lost map takes more).
        self.assertGreater(known, 5000)
        self.assertGreater(occupied, 300)
        self.assertLess(occupied, 0.2 * known)
        self.assertGreater(len(self.latest["trajectory"].poses), 20)


if __name__ == "__main__":
    rospy.init_node("test_ccny_bag")
    rostest.rosrun("hex_slam", "ccny_bag", CcnyBagTest, sys.argv)
