#!/usr/bin/python3
"""sim_compare: the hex/square (and hector_mapping) comparison of one simulated drive, live.

launch/sim_maze.launch compare:=true runs hex_slam_node twice on the same scans, in namespaces
hex (hex lattice) and square (hector_mapping's method on squares of equal area), and
hector_mapping itself in namespace hector where it is installed; a sim_evaluator scores each and
publishes its RESULT line on <ns>/sim_evaluator/result. This node waits for those lines and
prints one

    RESULT hex_position_rmse_m=0.0111 ... square_position_rmse_m=0.0602 ... square_over_hex=5.42

(with hector_position_rmse_m and hector_over_hex when hector_mapping ran). Without hector_mapping
(`rospack find hector_mapping` fails) its run is skipped and the line says hector_skipped=1.

With ~max_hex_position_rmse set it runs as a rostest test and asserts the hex error is below it,
that every run scored at least ~min_poses poses, and that square/hex is at least
~min_square_over_hex (if set).
"""
import sys
import threading
import unittest

import rospkg
import rospy
from std_msgs.msg import String

PKG = "hex_slam"
HECTOR = "hector_mapping"


def parse_result(line):
    """{key: value} of a 'RESULT key=value ...' line; numbers as floats."""
    fields = {}
    for word in line.split()[1:]:
        key, _, value = word.partition("=")
        try:
            fields[key] = float(value)
        except ValueError:
            fields[key] = value
    return fields


def hector_installed():
    try:
        rospkg.RosPack().get_path(HECTOR)
        return True
    except rospkg.ResourceNotFound:
        return False


class Comparison:
    def __init__(self):
        self.runs = ["hex", "square"] + (["hector"] if hector_installed() else [])
        self.results = {}
        self.lock = threading.Lock()
        self.complete = threading.Event()
        self.subscribers = [
            rospy.Subscriber(rospy.get_param("~%s_topic" % run, "/%s/sim_evaluator/result" % run),
                             String, self.on_result, callback_args=run) for run in self.runs]

    def on_result(self, msg, run):
        with self.lock:
            self.results[run] = parse_result(msg.data)
            if all(r in self.results for r in self.runs):
                self.complete.set()

    def ratio(self, run):
        return (self.results[run]["position_rmse_m"] / self.results["hex"]["position_rmse_m"]
                if self.results["hex"]["position_rmse_m"] > 0 else float("inf"))

    def result_line(self):
        with self.lock:
            words = []
            for run in self.runs:
                r = self.results.get(run, {})
                for key in ("position_rmse_m", "angle_rmse_rad", "position_max_m", "poses"):
                    if key in r:
                        words.append("%s_%s=%g" % (run, key, r[key]))
            for run in self.runs[1:]:
                if run in self.results and "hex" in self.results:
                    words.append("%s_over_hex=%.3f" % (run, self.ratio(run)))
            if "hector" not in self.runs:
                words.append("hector_skipped=1")
            return "RESULT " + " ".join(words)

    def skip_note(self):
        return ("" if "hector" in self.runs else
                "sim_compare: %s is not installed (rospack find %s fails): its run on the same "
                "scans is skipped" % (HECTOR, HECTOR))


class ComparisonTest(unittest.TestCase):
    def test_hex_beats_its_bound_and_square_is_reported(self):
        comparison = Comparison()
        limit = rospy.get_param("~time_limit", 600.0)  # wall seconds
        self.assertTrue(comparison.complete.wait(limit),
                        "results of %s not all in within %.0f s (got %s)" %
                        (comparison.runs, limit, sorted(comparison.results)))
        print(comparison.result_line())
        if comparison.skip_note():
            print(comparison.skip_note())
        for run in comparison.runs:
            print("sim_compare: %s position RMSE %.4f m, angle RMSE %.5f rad, max %.4f m over %d "
                  "poses" % (run, comparison.results[run]["position_rmse_m"],
                             comparison.results[run]["angle_rmse_rad"],
                             comparison.results[run]["position_max_m"],
                             comparison.results[run]["poses"]))
        print("sim_compare: square/hex position RMSE ratio %.2f" % comparison.ratio("square"))
        sys.stdout.flush()
        min_poses = rospy.get_param("~min_poses", 20)
        for run in comparison.runs:
            self.assertGreaterEqual(comparison.results[run]["poses"], min_poses, run)
        self.assertLess(comparison.results["hex"]["position_rmse_m"],
                        rospy.get_param("~max_hex_position_rmse"))
        if rospy.has_param("~min_square_over_hex"):
            self.assertGreaterEqual(comparison.ratio("square"),
                                    rospy.get_param("~min_square_over_hex"))


def main():
    rospy.init_node("sim_compare")
    if rospy.has_param("~max_hex_position_rmse"):
        import rostest
        rostest.rosrun(PKG, "sim_compare", ComparisonTest, sys.argv)
        return 0
    comparison = Comparison()
    if comparison.skip_note():
        print(comparison.skip_note())
    while not rospy.is_shutdown() and not comparison.complete.wait(0.5):
        pass
    print(comparison.result_line())
    sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
