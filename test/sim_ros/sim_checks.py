"""What the robot-launch rostests check against the simulator's ground truth: the pose error of
slam_out_pose (scored by sim_evaluator's TrajectoryScore), the map's walls against the world
the simulator drew the scans from, and the tf tree."""
import math
import os
import sys
import threading

import numpy
import rospkg
import rospy
import tf2_ros
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import OccupancyGrid, Odometry

PACKAGE = os.path.realpath(rospkg.RosPack().get_path("hex_slam"))
sys.path.insert(0, os.path.join(PACKAGE, "scripts"))
sys.path.insert(0, os.path.join(PACKAGE, "test", "ros"))
import bag_replay  # noqa: E402  (test/ros)
import ros_test_util as util  # noqa: E402  (test/ros)
import sim_evaluator  # noqa: E402  (scripts)


class _PairKeepingScore(sim_evaluator.TrajectoryScore):
    def __init__(self):
        super().__init__()
        self.pairs = []  # (stamp, estimate, truth)

    def _pair(self, stamp, truth, estimate):
        super()._pair(stamp, truth, estimate)
        self.pairs.append((stamp, estimate, truth))


class LiveScore:
    """slam_out_pose (or, with estimate_topic="odom", the robot's odometry) against
    base_pose_ground_truth, paired by stamp; the latest map."""

    def __init__(self, truth_topic="base_pose_ground_truth", estimate_topic="slam_out_pose"):
        self.lock = threading.Lock()
        self.score = _PairKeepingScore()
        self.map = None
        odometry = estimate_topic.endswith("odom")
        self._subs = [
            rospy.Subscriber(truth_topic, Odometry, self._on_truth, queue_size=1000),
            rospy.Subscriber(estimate_topic, Odometry if odometry else PoseStamped,
                             self._on_odometry if odometry else self._on_estimate,
                             queue_size=1000),
            rospy.Subscriber("map", OccupancyGrid, self._on_map, queue_size=1)]

    def _on_truth(self, msg):
        with self.lock:
            self.score.add(self.score.truth, msg.header.stamp, util.planar(msg.pose.pose))

    def _on_estimate(self, msg):
        with self.lock:
            self.score.add(self.score.estimate, msg.header.stamp, util.planar(msg.pose))

    def _on_odometry(self, msg):
        with self.lock:
            self.score.add(self.score.estimate, msg.header.stamp, util.planar(msg.pose.pose))

    def _on_map(self, msg):
        with self.lock:
            self.map = msg

    def world_from_map(self):
        """The SLAM's map frame in the world, fixed by the first pair (sim_evaluator's way)."""
        with self.lock:
            return self.score.align

    def summary(self):
        with self.lock:
            s = self.score
            return s.count, s.position_rmse(), s.angle_rmse(), s.max_error


class LockstepAnswer:
    """Answers the simulator's lockstep on ~truth_seen (rosbot_rplidar.launch's lockstep_topics,
    as sim_evaluator does) with each ground truth, once every one of `scores` has its first pair:
    the robot stands at its start until then, so the frames are aligned there and the scores see
    the whole tour, however late this checker came up."""

    def __init__(self, scores, truth_topic="base_pose_ground_truth"):
        self.scores = scores
        self._pub = rospy.Publisher("~truth_seen", PoseStamped, queue_size=100)
        self._sub = rospy.Subscriber(truth_topic, Odometry, self._on_truth, queue_size=1000)

    def _on_truth(self, msg):
        if all(score.world_from_map() is not None for score in self.scores):
            self._pub.publish(PoseStamped(header=msg.header, pose=msg.pose.pose))


class World:
    """The simulator's world (a map_server YAML + image): where its walls are."""

    def __init__(self, yaml_path):
        meta, width, height, values = util.load_map_server_map(yaml_path)
        self.resolution = meta["resolution"]
        self.origin = meta["origin"]
        self.occupied = numpy.array(values, dtype=numpy.int16).reshape(height, width) == 100

    def fraction_near_walls(self, points, radius):
        """The fraction of world `points` with a wall pixel within `radius` m (a square window)."""
        if not points:
            return 0.0
        r = int(math.ceil(radius / self.resolution))
        padded = numpy.pad(self.occupied, r)
        # Summed-area table: any wall in the window around a pixel, in O(1) per point.
        table = numpy.zeros((padded.shape[0] + 1, padded.shape[1] + 1), dtype=numpy.int64)
        table[1:, 1:] = padded.cumsum(0).cumsum(1)
        near = 0
        for x, y in points:
            col = int(math.floor((x - self.origin[0]) / self.resolution)) + r
            row = int(math.floor((y - self.origin[1]) / self.resolution)) + r
            if not (r <= row < padded.shape[0] - r and r <= col < padded.shape[1] - r):
                continue
            total = (table[row + r + 1, col + r + 1] - table[row - r, col + r + 1] -
                     table[row + r + 1, col - r] + table[row - r, col - r])
            near += total > 0
        return near / float(len(points))


def map_walls_in_world(grid, world_from_map):
    """The occupied pixels of an OccupancyGrid, as world points."""
    info = grid.info
    points = bag_replay.occupied_points(grid.data, info.width, info.height, info.resolution,
                                        (info.origin.position.x, info.origin.position.y))
    return [sim_evaluator.compose(world_from_map, (x, y, 0.0))[:2] for x, y in points]


def tf_parents(tf_buffer):
    """{frame: parent} of everything the tf buffer holds."""
    import yaml
    frames = yaml.safe_load(tf_buffer.all_frames_as_yaml()) or {}
    return {frame: data["parent"] for frame, data in frames.items()}


# tf's map -> base against the published pose, at every stamp the tf buffer still holds: equal to
# rounding (TF_AGREEMENT, m and rad) at no fewer than MIN_TF_AGREEMENT of them. Not all: a scan
# whose odometry came after it was posed keeps the last correction (a busy machine, or the last
# scans of a run, whose odometry publisher the launch stops with the node).
TF_AGREEMENT = 1e-3
MIN_TF_AGREEMENT = 0.98


def check_tf_agrees(test, label, tf_buffer, pairs, parent, child, min_stamps):
    """Asserts on `test` that tf's parent -> child is the pose of `pairs` (LiveScore's (stamp,
    estimate, truth)) at more than `min_stamps` of the stamps `tf_buffer` holds (its last 10 s),
    and at MIN_TF_AGREEMENT of them. A single stamp is a poor test: the last one of a run is the
    likeliest to have missed its odometry."""
    agree, off = 0, []
    for stamp, estimate, _ in pairs:
        try:
            t = tf_buffer.lookup_transform(parent, child, stamp)
        except tf2_ros.TransformException:
            continue  # older than tf's cache, or past the last odometry
        distance, heading = util.pose_error(transform_pose(t), estimate)
        if distance < TF_AGREEMENT and heading < TF_AGREEMENT:
            agree += 1
        else:
            off.append((stamp.to_sec(), distance, heading))
    print("%s: tf agrees with slam_out_pose at %d of %d stamps; off at %s" %
          (label, agree, agree + len(off), off[:5]))
    test.assertGreater(agree, min_stamps)
    test.assertGreaterEqual(agree / float(agree + len(off)), MIN_TF_AGREEMENT, off[:5])


def transform_pose(transform):
    t, q = transform.transform.translation, transform.transform.rotation
    return (t.x, t.y, util.yaw_of(q))
