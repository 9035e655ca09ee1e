#!/usr/bin/python3
"""sim_evaluator: scores a SLAM's pose against the simulator's ground truth, live.

Subscribes ~truth_topic (nav_msgs/Odometry, default base_pose_ground_truth) and ~estimate_topic
(geometry_msgs/PoseStamped, default slam_out_pose, as hector_mapping and hex_slam_node publish
it) and pairs messages with the same stamp (the simulator stamps the truth with each scan's
stamp, the SLAM its pose with the scan's). The estimate lives in the SLAM's map frame, the truth
in the world: the first pair fixes the transform between them. Prints running figures every
~report_period seconds and, when the simulator's path_finished arrives (or after ~duration
simulated seconds), one line

    RESULT label=hex position_rmse_m=0.0243 angle_rmse_rad=0.0042 position_max_m=0.061 poses=3712

which it also publishes, latched, on ~result (std_msgs/String) for sim_compare.py. It then exits,
or with ~exit_when_done false stays until shut down (several evaluators side by side, none of
them the one that ends the launch). With ~requires_package set (e.g. hector_mapping) and that
package not installed it says so and exits at once: the SLAM it would score is not running.

With ~max_position_rmse set it runs as a rostest test instead and asserts the error is below it
(and above ~min_position_rmse, if set: how the evaluator itself is tested against a known error).
"""
import math
import sys
import threading
import unittest

import rospkg
import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry
from std_msgs.msg import Bool, String

PKG = "hex_slam"


def yaw(q):
    return 2.0 * math.atan2(q.z, q.w)


def compose(a, b):
    """a * b for 2D poses (x, y, theta): b expressed in a's frame."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])


def inverse(a):
    c, s = math.cos(a[2]), math.sin(a[2])
    return (-c * a[0] - s * a[1], s * a[0] - c * a[1], -a[2])


def wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))


class TrajectoryScore:
    """Pairs truth and estimate by stamp and accumulates the errors after aligning the first pair."""

    def __init__(self):
        self.truth, self.estimate = {}, {}
        self.align = None
        self.count = 0
        self.sum_sq = self.sum_sq_angle = self.max_error = 0.0
        self.first_stamp = self.last_stamp = None

    def add(self, table, stamp, pose):
        table[stamp] = pose
        if stamp in self.truth and stamp in self.estimate:
            self._pair(stamp, self.truth.pop(stamp), self.estimate.pop(stamp))

    def _pair(self, stamp, truth, estimate):
        if self.align is None:
            self.align = compose(truth, inverse(estimate))
            self.first_stamp = stamp
        aligned = compose(self.align, estimate)
        e = math.hypot(aligned[0] - truth[0], aligned[1] - truth[1])
        a = wrap(aligned[2] - truth[2])
        self.count += 1
        self.sum_sq += e * e
        self.sum_sq_angle += a * a
        self.max_error = max(self.max_error, e)
        self.last_stamp = stamp

    def position_rmse(self):
        return math.sqrt(self.sum_sq / self.count) if self.count else float("nan")

    def angle_rmse(self):
        return math.sqrt(self.sum_sq_angle / self.count) if self.count else float("nan")

    def elapsed(self):
        return (self.last_stamp - self.first_stamp).to_sec() if self.count else 0.0


class Evaluator:
    def __init__(self):
        self.label = rospy.get_param("~label", "slam")
        self.duration = rospy.get_param("~duration", 0.0)
        self.report_period = rospy.get_param("~report_period", 10.0)
        self.score = TrajectoryScore()
        self.lock = threading.Lock()
        self.done = threading.Event()
        self.last_report = None
        self.latest_truth = None  # the newest ground-truth stamp received
        self.finish_stamp = None  # the newest one when path_finished arrived
        self.seen_pub = rospy.Publisher("~truth_seen", PoseStamped, queue_size=100)
        # Queues long enough for a whole drive: a loaded machine delays this scorer, and every
        # pose it dropped would be a pose the SLAM node is blamed for missing.
        rospy.Subscriber(rospy.get_param("~truth_topic", "base_pose_ground_truth"), Odometry,
                         self.on_truth, queue_size=100000)
        rospy.Subscriber(rospy.get_param("~estimate_topic", "slam_out_pose"), PoseStamped,
                         self.on_estimate, queue_size=100000)
        rospy.Subscriber("path_finished", Bool, self.on_finished)

    @staticmethod
    def pose(msg_pose):
        return (msg_pose.position.x, msg_pose.position.y, yaw(msg_pose.orientation))

    def on_truth(self, msg):
        # Tells a lockstep simulator (hex_slam_sim's lockstep_topics) this step's truth is in.
        self.seen_pub.publish(PoseStamped(header=msg.header, pose=msg.pose.pose))
        with self.lock:
            self.latest_truth = msg.header.stamp
            self.score.add(self.score.truth, msg.header.stamp, self.pose(msg.pose.pose))
        self.check()

    def on_estimate(self, msg):
        with self.lock:
            self.score.add(self.score.estimate, msg.header.stamp, self.pose(msg.pose))
        self.check()

    def on_finished(self, msg):
        # Done once the estimate of the last scan before the finish is scored too: the messages
        # of the drive's end may still be queued behind this one.
        if msg.data:
            with self.lock:
                self.finish_stamp = self.latest_truth
        self.check()

    def check(self):
        with self.lock:
            elapsed, count = self.score.elapsed(), self.score.count
            rmse = self.score.position_rmse()
            scored_to_finish = (self.finish_stamp is not None and count and
                                self.score.last_stamp >= self.finish_stamp)
        if scored_to_finish or (self.duration > 0 and elapsed >= self.duration):
            self.done.set()
        if count and (self.last_report is None or elapsed - self.last_report >= self.report_period):
            self.last_report = elapsed
            rospy.loginfo("sim_evaluator [%s]: %.0f s, %d poses, position RMSE %.4f m",
                          self.label, elapsed, count, rmse)

    def result_line(self):
        with self.lock:
            s = self.score
            return ("RESULT label=%s position_rmse_m=%.5f angle_rmse_rad=%.6f position_max_m=%.5f "
                    "poses=%d" % (self.label, s.position_rmse(), s.angle_rmse(), s.max_error,
                                  s.count))


class EvaluatorTest(unittest.TestCase):
    def test_position_error_within_bounds(self):
        evaluator = Evaluator()
        limit = rospy.get_param("~time_limit", 600.0)  # wall seconds
        self.assertTrue(evaluator.done.wait(limit) or rospy.is_shutdown(),
                        "neither path_finished nor ~duration within %.0f s" % limit)
        print(evaluator.result_line())
        s = evaluator.score
        self.assertGreaterEqual(s.count, rospy.get_param("~min_poses", 20))
        self.assertLessEqual(s.position_rmse(), rospy.get_param("~max_position_rmse"))
        if rospy.has_param("~min_position_rmse"):
            self.assertGreaterEqual(s.position_rmse(), rospy.get_param("~min_position_rmse"))


def package_installed(name):
    try:
        rospkg.RosPack().get_path(name)
        return True
    except rospkg.ResourceNotFound:
        return False


def main():
    rospy.init_node("sim_evaluator")
    if rospy.has_param("~max_position_rmse"):
        import rostest
        rostest.rosrun(PKG, "sim_evaluator", EvaluatorTest, sys.argv)
        return 0
    required = rospy.get_param("~requires_package", "")
    if required and not package_installed(required):
        print("sim_evaluator [%s]: %s is not installed (rospack find %s fails): nothing to score, "
              "skipped" % (rospy.get_param("~label", "slam"), required, required))
        sys.stdout.flush()
        return 0
    result_pub = rospy.Publisher("~result", String, queue_size=1, latch=True)
    evaluator = Evaluator()
    while not rospy.is_shutdown() and not evaluator.done.wait(0.5):
        pass
    line = evaluator.result_line()
    result_pub.publish(String(data=line))
    print(line)
    sys.stdout.flush()
    if not rospy.get_param("~exit_when_done", True):
        rospy.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main())
