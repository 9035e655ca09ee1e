#!/usr/bin/python3
"""rostest checker: hex_slam_node reads its private parameters once, refuses to start on
nonsense and on keys it does not know (exit code 1, a ROS_FATAL naming the key, and for a
misspelling the key meant), warns about hector_mapping keys that have no effect here and about
tf1-style frame ids (read without their leading '/'), and otherwise starts."""
import signal
import subprocess
import sys
import unittest

import roslib.packages
import rospy
import rostest

START_TIMEOUT = 15.0  # s for the node to start (or refuse to)


class ParametersTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_parameters")
        cls.node = roslib.packages.find_node("hex_slam", "hex_slam_node")[0]
        cls.runs = 0

    def start(self, params):
        """Starts the node with private parameters `params` (set on the master first)."""
        ParametersTest.runs += 1
        name = "param_check_%d" % ParametersTest.runs
        for key, value in params.items():
            rospy.set_param("/%s/%s" % (name, key), value)
        return subprocess.Popen([self.node, "__name:=" + name], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True), name

    def assert_refused(self, params, key):
        process, name = self.start(params)
        try:
            _, err = process.communicate(timeout=START_TIMEOUT)
        except subprocess.TimeoutExpired:
            process.kill()
            self.fail("the node started with %s" % params)
        self.assertEqual(process.returncode, 1, "exit code with %s" % params)
        self.assertIn("FATAL", err)
        self.assertIn(key, err, "the error does not name '%s': %s" % (key, err))

    def test_nonsense_values_stop_the_node_naming_the_key(self):
        cases = [({"map_resolution": -0.05}, "map_resolution"),
                 ({"map_multi_res_levels": 0}, "map_multi_res_levels"),
                 ({"lattice": "triangle"}, "lattice"),
                 ({"map_size": "big"}, "map_size"),
                 ({"use_odometry": "maybe"}, "use_odometry"),
                 ({"base_frame": "/"}, "base_frame"),
                 ({"map_resoluton": 0.05}, "did you mean 'map_resolution'"),
                 ({"map_pub_period": 0.0}, "map_pub_period"),
                 ({"laser_max_dist": 0.1, "laser_min_dist": 0.4}, "laser_max_dist"),
                 ({"map_size": [1024, 1024]}, "map_size")]
        for params, key in cases:
            self.assert_refused(params, key)

    def test_ineffective_keys_and_old_frame_ids_are_warnings_and_the_node_runs(self):
        process, name = self.start({"pub_drawings": True, "base_frame": "/base_footprint",
                                    "map_size": 256})
        try:
            # Started: its services are up.
            rospy.wait_for_service("/reset_map", timeout=START_TIMEOUT)
            self.assertIsNone(process.poll(), "the node exited")
        finally:
            process.send_signal(signal.SIGINT)
            out, err = process.communicate(timeout=START_TIMEOUT)
        self.assertEqual(process.returncode, 0, err)
        self.assertIn("pub_drawings is hector_mapping's and has no effect", err)
        self.assertIn("base_frame '/base_footprint' read as 'base_footprint'", err)
        self.assertIn("frames map 'map', odom 'odom', base 'base_footprint'", out + err)
        # The end-of-run summary.
        self.assertIn("hex_slam: timing scans=0", out)


if __name__ == "__main__":
    rostest.rosrun("hex_slam", "parameters", ParametersTest, sys.argv)
