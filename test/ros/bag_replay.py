"""Helpers of the rostest checkers that replay real logs through hex_slam_node: where the data is,
running our own tools, playing a bag on its own clock, trajectories as TUM files, and comparing
a live run with hex_slam_offline's run of the same bag (poses at matching stamps, maps)."""
import bisect
import math
import os
import subprocess
import threading
import time

import rosbag
import roslib.packages
import rospkg
import rospy
import tf2_ros
from geometry_msgs.msg import PoseStamped
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from tf2_msgs.msg import TFMessage

import ros_test_util as util

PKG = "hex_slam"


def package_dir():
    return os.path.realpath(rospkg.RosPack().get_path(PKG))


def data_dir():
    """$HEX_SLAM_DATA_DIR, else ../shared/data beside the package's source."""
    return os.environ.get("HEX_SLAM_DATA_DIR",
                          os.path.normpath(os.path.join(package_dir(), "..", "shared", "data")))


def run_tool(name, *args, timeout=120):
    """Runs one of the package's executables; returns its stdout's RESULT line as a dict (numbers
    as floats). Fails loudly with the tool's output."""
    found = roslib.packages.find_node(PKG, name)
    if not found:
        raise RuntimeError("%s is not built" % name)
    run = subprocess.run([found[0]] + [str(a) for a in args], capture_output=True, text=True,
                         timeout=timeout)
    if run.returncode != 0:
        raise RuntimeError("%s failed (%d):\n%s%s" % (name, run.returncode, run.stdout, run.stderr))
    lines = [l for l in run.stdout.splitlines() if l.strip()]
    if not lines or not lines[-1].startswith("RESULT "):
        raise RuntimeError("%s printed no RESULT line:\n%s" % (name, run.stdout))
    result = {}
    for word in lines[-1].split()[1:]:
        key, _, value = word.partition("=")
        try:
            result[key] = float(value)
        except ValueError:
            result[key] = value
    return result


class PoseRecorder:
    """slam_out_pose by stamp."""

    def __init__(self, topic="slam_out_pose"):
        self.poses = {}
        self.subscriber = rospy.Subscriber(topic, PoseStamped, self._on_pose, queue_size=1000)

    def _on_pose(self, msg):
        self.poses[msg.header.stamp.to_nsec()] = util.planar(msg.pose)


def latch_static_transforms(bag):
    """Publishes the bag's /tf_static now, as a robot's description would before any scan. The
    bag replays it too, but at the instant of its first scan, which then reaches the node before
    the laser's mounting does and is dropped. Returns the broadcaster (keep it alive)."""
    transforms = []
    with rosbag.Bag(bag) as b:
        for _, msg, _ in b.read_messages(topics=["/tf_static"]):
            transforms.extend(msg.transforms)
    broadcaster = tf2_ros.StaticTransformBroadcaster()
    if transforms:
        broadcaster.sendTransform(transforms)
    return broadcaster


def play_bag(bag, rate, done, keep_clock=10.0):
    """rosbag play --clock at `rate`, then keeps simulated time running on the wall clock (the
    bag's clock stops with the bag, and with it the node's timers and tf waits) until `done()` or
    `keep_clock` wall seconds."""
    clock = {}
    sub = rospy.Subscriber("clock", Clock, lambda m: clock.__setitem__("now", m.clock))
    player = subprocess.run(["rosbag", "play", "--clock", "-q", "-d", "1", "-r", str(rate), bag],
                            capture_output=True, text=True, timeout=300)
    if player.returncode != 0:
        raise RuntimeError("rosbag play failed: %s" % player.stderr)
    clock_pub = rospy.Publisher("clock", Clock, queue_size=10)
    now = clock.get("now", rospy.Time(0))
    deadline = time.time() + keep_clock
    while time.time() < deadline and not done():
        now += rospy.Duration(0.1)
        clock_pub.publish(Clock(clock=now))
        time.sleep(0.1)
    sub.unregister()


class LockstepPlayer:
    """Plays a bag's scans (and its /tf, /tf_static) one at a time on the bag's own clock, each
    scan only once the node has answered the previous one with its pose (or `timeout` wall
    seconds passed): the node gets all the time it asks for, so a test can count on every scan
    arriving however loaded the machine is. Counts the scans left unanswered."""

    def __init__(self, bag, pose_topic="slam_out_pose"):
        with rosbag.Bag(bag) as b:
            topics = b.get_type_and_topic_info().topics
            self.scan_topic = next(t for t, i in topics.items()
                                   if i.msg_type == "sensor_msgs/LaserScan")
            # In bag time, and tf before a scan of the same time: the node looks the scan's
            # odometry up at its stamp, and must not wait for a transform the player holds back.
            timed = [(t, topic != self.scan_topic, i, topic, msg) for i, (topic, msg, t) in
                     enumerate(b.read_messages(topics=[self.scan_topic, "/tf", "/tf_static"]))]
        self.messages = [(topic, msg) for _, _, _, topic, msg in
                         sorted(timed, key=lambda m: (m[0], not m[1], m[2]))]
        self.scans = sum(1 for topic, _ in self.messages if topic == self.scan_topic)
        self.answered = set()
        self.unanswered = 0
        self.lock = threading.Lock()
        self.answer = threading.Condition(self.lock)
        self.clock_pub = rospy.Publisher("/clock", Clock, queue_size=10)
        self.scan_pub = rospy.Publisher(self.scan_topic, LaserScan, queue_size=10)
        self.tf_pub = rospy.Publisher("/tf", TFMessage, queue_size=100)
        self.static_pub = rospy.Publisher("/tf_static", TFMessage, queue_size=10, latch=True)
        self.pose_sub = rospy.Subscriber(pose_topic, PoseStamped, self._on_pose, queue_size=1000)
        self.position = 0

    def _on_pose(self, msg):
        with self.answer:
            self.answered.add(msg.header.stamp)
            self.answer.notify_all()

    def wait_for_subscriber(self, timeout=30.0):
        """Waits (wall time: the bag's clock has not started) for the node to subscribe to the
        scans, tf and the clock, and for this player's own subscription to the node's poses: a
        message sent before its connection is up is lost (the first scan's tf, or its answer)."""
        links = (self.scan_pub, self.tf_pub, self.clock_pub, self.pose_sub)

        def connected():
            return all(link.get_num_connections() > 0 for link in links)

        return util.wait_for_wall(connected, timeout)

    def play(self, scans=None, timeout=5.0):
        """Plays the next `scans` scans (all the rest by default)."""
        played = 0
        while self.position < len(self.messages) and (scans is None or played < scans):
            topic, msg = self.messages[self.position]
            self.position += 1
            if topic == "/tf_static":
                self.static_pub.publish(msg)
                continue
            if topic == "/tf":
                self.tf_pub.publish(msg)
                continue
            self.clock_pub.publish(Clock(clock=msg.header.stamp))
            self.scan_pub.publish(msg)
            played += 1
            with self.answer:
                if not self.answer.wait_for(lambda: msg.header.stamp in self.answered, timeout):
                    self.unanswered += 1
        return played


def stamp_ns(text):
    """A decimal stamp in seconds, exactly, as integer nanoseconds (a double keeps only ~0.1 us
    of a 1e9 s stamp, and carmen_to_bag's stamps can be 1 us apart)."""
    seconds, _, fraction = text.partition(".")
    return int(seconds) * 1000000000 + int((fraction + "000000000")[:9])


def read_tum(path):
    """{stamp in ns: (x, y, yaw)} of a TUM trajectory ('t x y z qx qy qz qw' lines)."""
    poses = {}
    with open(path) as f:
        for line in f:
            fields = line.split()
            if len(fields) != 8 or line.startswith("#"):
                continue
            x, y, _, qx, qy, qz, qw = (float(v) for v in fields[1:])
            yaw = math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
            poses[stamp_ns(fields[0])] = (x, y, yaw)
    return poses


def write_tum(path, poses):
    with open(path, "w") as f:
        for stamp in sorted(poses):
            x, y, yaw = poses[stamp]
            f.write("%d.%09d %.6f %.6f 0 0 0 %.9f %.9f\n" % (stamp // 1000000000,
                                                             stamp % 1000000000, x, y,
                                                             math.sin(yaw / 2), math.cos(yaw / 2)))


def matched_differences(a, b, tolerance_ns=500):
    """(stamp, distance, |heading difference|) for each pose of `a` whose nearest pose of `b` is
    within `tolerance_ns`: both are stamped with the bag's scan stamps, which a TUM file written
    by hex_slam_offline keeps to the microsecond."""
    b_stamps = sorted(b)
    out = []
    for stamp in sorted(a):
        i = bisect.bisect_left(b_stamps, stamp)
        nearest = min(b_stamps[max(0, i - 1):i + 1], key=lambda s: abs(s - stamp), default=None)
        if nearest is not None and abs(nearest - stamp) <= tolerance_ns:
            d, h = util.pose_error(a[stamp], b[nearest])
            out.append((stamp, d, h))
    return out


def occupied_points(grid_values, width, height, resolution, origin):
    """World points of the occupied (100) pixels of a row-major, bottom-row-first grid."""
    points = []
    for row in range(height):
        for col in range(width):
            if grid_values[row * width + col] == 100:
                points.append((origin[0] + (col + 0.5) * resolution,
                               origin[1] + (row + 0.5) * resolution))
    return points


def wall_agreement(points, reference, radius):
    """The fraction of `points` that have a point of `reference` within `radius` m: how much of
    one map's walls the other map has too. A wall drawn twice (a pass that drifted) adds points
    the reference lacks."""
    if not points:
        return 0.0
    cell = radius
    buckets = {}
    for p in reference:
        buckets.setdefault((int(math.floor(p[0] / cell)), int(math.floor(p[1] / cell))),
                           []).append(p)
    near = 0
    for p in points:
        cx, cy = int(math.floor(p[0] / cell)), int(math.floor(p[1] / cell))
        found = False
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for q in buckets.get((cx + dx, cy + dy), ()):
                    if math.hypot(p[0] - q[0], p[1] - q[1]) <= radius:
                        found = True
                        break
                if found:
                    break
            if found:
                break
        near += found
    return near / float(len(points))
