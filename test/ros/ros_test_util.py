"""Helpers shared by the rostest checkers: recording the node's outputs next to the ground truth,
comparing poses, reading occupancy grids and the files save_map writes."""
import math
import os
import struct
import threading
import time

import rospy
import yaml
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import LaserScan

import room_world


def yaw_of(q):
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def planar(pose):
    """(x, y, yaw) of a geometry_msgs/Pose."""
    return (pose.position.x, pose.position.y, yaw_of(pose.orientation))


def planar_transform(transform):
    """(x, y, yaw) of a geometry_msgs/Transform."""
    return (transform.translation.x, transform.translation.y, yaw_of(transform.rotation))


def pose_error(a, b):
    """(distance, |heading difference|) between two planar poses."""
    return math.hypot(a[0] - b[0], a[1] - b[1]), abs(room_world.wrap(a[2] - b[2]))


class Recorder:
    """Keeps the truth by stamp, the node's poses, the latest map, scans and diagnostics."""

    def __init__(self, scan_history=200):
        self.lock = threading.Lock()
        self.truth = {}  # stamp (ros Time) -> (x, y, yaw)
        self.travelled = 0.0
        self._last_truth = None
        self.poses = []  # (stamp, (x, y, yaw)) from slam_out_pose
        self.pose_updates = []
        self.map = None
        self.map_pose_stamp = None  # the node's latest pose when the latest map arrived
        self.scans = []  # the latest real scans, oldest first
        self.scan_history = scan_history
        self.diagnostics = None
        rospy.Subscriber("true_pose", PoseStamped, self._on_truth, queue_size=1000)
        rospy.Subscriber("slam_out_pose", PoseStamped, self._on_pose, queue_size=100)
        rospy.Subscriber("poseupdate", PoseWithCovarianceStamped, self._on_pose_update,
                         queue_size=100)
        rospy.Subscriber("map", OccupancyGrid, self._on_map, queue_size=1)
        rospy.Subscriber("diagnostics", DiagnosticArray, self._on_diagnostics, queue_size=10)
        self._scan_sub = rospy.Subscriber("scan", LaserScan, self._on_scan, queue_size=50)

    def _on_truth(self, msg):
        pose = planar(msg.pose)
        with self.lock:
            self.truth[msg.header.stamp] = pose
            if self._last_truth is not None:
                self.travelled += math.hypot(pose[0] - self._last_truth[0],
                                             pose[1] - self._last_truth[1])
            self._last_truth = pose

    def _on_pose(self, msg):
        with self.lock:
            self.poses.append((msg.header.stamp, planar(msg.pose)))

    def _on_pose_update(self, msg):
        with self.lock:
            self.pose_updates.append(msg)

    def _on_map(self, msg):
        with self.lock:
            self.map = msg
            self.map_pose_stamp = self.poses[-1][0] if self.poses else None

    def _on_scan(self, msg):
        # Only the simulator's scans, not those a checker injects.
        if msg._connection_header.get("callerid") != "/room_scan_publisher":
            return
        with self.lock:
            self.scans.append(msg)
            del self.scans[:-self.scan_history]

    def _on_diagnostics(self, msg):
        for status in msg.status:
            if status.name.endswith("scan matching"):
                with self.lock:
                    self.diagnostics = {kv.key: kv.value for kv in status.values}

    def matched_errors(self, since=None):
        """(stamp, distance, heading error) for every node pose with a truth at its stamp."""
        with self.lock:
            pairs = [(s, p, self.truth.get(s)) for s, p in self.poses]
        return [(s,) + pose_error(p, t) for s, p, t in pairs
                if t is not None and (since is None or s >= since)]

    def first_truth(self):
        """The truth at the earliest stamp (read under the lock: the truth keeps arriving)."""
        with self.lock:
            return self.truth[min(self.truth)] if self.truth else None

    def latest_pose(self):
        with self.lock:
            return self.poses[-1] if self.poses else None

    def latest_pose_with_truth(self):
        """The latest (stamp, pose) whose stamp has a truth: on a loaded machine the truth of the
        very last scan may still be on its way when the pose is."""
        with self.lock:
            for stamp, pose in reversed(self.poses):
                if stamp in self.truth:
                    return stamp, pose
        return None

    def latest_scan(self):
        with self.lock:
            return self.scans[-1] if self.scans else None


def wait_for_wall(predicate, timeout, period=0.05):
    """wait_for in wall time, for tests that drive a simulated clock themselves (it stands still
    whenever they do not publish it)."""
    deadline = time.time() + timeout
    value = predicate()
    while not value and time.time() < deadline and not rospy.is_shutdown():
        time.sleep(period)
        value = predicate()
    return value


def wait_for(predicate, timeout, period=0.1):
    """Polls `predicate` until it is true or `timeout` s pass; returns its last value."""
    deadline = rospy.Time.now() + rospy.Duration(timeout)
    value = predicate()
    while not value and rospy.Time.now() < deadline and not rospy.is_shutdown():
        rospy.sleep(period)
        value = predicate()
    return value


def grid_value(grid, point):
    """The occupancy grid's value under a map-frame point, or None outside it."""
    info = grid.info
    col = int(math.floor((point[0] - info.origin.position.x) / info.resolution))
    row = int(math.floor((point[1] - info.origin.position.y) / info.resolution))
    if not (0 <= col < info.width and 0 <= row < info.height):
        return None
    return grid.data[row * info.width + col]


def grid_values_near(grid, point, radius_pixels):
    info = grid.info
    r = radius_pixels * info.resolution
    values = []
    steps = range(-radius_pixels, radius_pixels + 1)
    for i in steps:
        for j in steps:
            v = grid_value(grid, (point[0] + i * info.resolution, point[1] + j * info.resolution))
            if v is not None and math.hypot(i, j) * info.resolution <= r + 1e-9:
                values.append(v)
    return values


def known_cells(grid):
    return sum(1 for v in grid.data if v >= 0)


def read_pgm(path):
    """(width, height, maxval, pixels as bytes) of a binary (P5) PGM, comments allowed."""
    with open(path, "rb") as f:
        data = f.read()
    tokens, pos = [], 0
    while len(tokens) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        start = pos
        while not data[pos:pos + 1].isspace():
            pos += 1
        tokens.append(data[start:pos])
    if tokens[0] != b"P5":
        raise ValueError("%s: not a binary PGM" % path)
    width, height, maxval = int(tokens[1]), int(tokens[2]), int(tokens[3])
    pixels = data[pos + 1:pos + 1 + width * height]
    if len(pixels) != width * height:
        raise ValueError("%s: truncated" % path)
    return width, height, maxval, pixels


def load_map_server_map(yaml_path):
    """Reads a map_server map the way map_server does (trinary mode): returns (metadata dict,
    width, height, values row-major from the bottom row, -1/0/100)."""
    with open(yaml_path) as f:
        meta = yaml.safe_load(f)
    image = meta["image"]
    if not os.path.isabs(image):
        image = os.path.join(os.path.dirname(yaml_path), image)
    width, height, maxval, pixels = read_pgm(image)
    values = []
    for row in range(height):
        line = pixels[(height - 1 - row) * width:(height - row) * width]
        for gray in line:
            p = (maxval - gray) / float(maxval) if not meta["negate"] else gray / float(maxval)
            values.append(100 if p > meta["occupied_thresh"] else
                          0 if p < meta["free_thresh"] else -1)
    return meta, width, height, values


def read_hexmap_header(path):
    """The fixed header of a .hexmap, each level's rectangle and (version 3) the loop-closure
    graph's counts; checks the size adds up."""
    with open(path, "rb") as f:
        data = f.read()
    magic = data[:8]
    version, lattice = struct.unpack_from("<II", data, 8)
    (spacing,) = struct.unpack_from("<d", data, 16)
    (levels,) = struct.unpack_from("<I", data, 40)
    pos, rects, hit_cells = 44, [], []
    for _ in range(levels):
        rect = struct.unpack_from("<iiii", data, pos)
        rects.append(rect)
        pos += 16 + 4 * rect[2] * rect[3]
        if version >= 2:  # the hit records: a count, then 16 bytes each
            (hits,) = struct.unpack_from("<I", data, pos)
            hit_cells.append(hits)
            pos += 4 + 16 * hits
    graph = {"submaps": 0, "nodes": 0, "constraints": 0}
    if version >= 3:  # submaps, nodes and constraints, each a count and its records
        (graph["submaps"],) = struct.unpack_from("<I", data, pos)
        pos += 4
        for _ in range(graph["submaps"]):
            (k,) = struct.unpack_from("<I", data, pos + 48)
            pos += 52 + 4 * k
        (graph["nodes"],) = struct.unpack_from("<I", data, pos)
        pos += 4
        for _ in range(graph["nodes"]):
            (points,) = struct.unpack_from("<I", data, pos + 64)
            pos += 68 + 8 * points
        (graph["constraints"],) = struct.unpack_from("<I", data, pos)
        pos += 4 + 40 * graph["constraints"]
    return {"magic": magic, "version": version, "lattice": lattice, "spacing": spacing,
            "levels": levels, "rects": rects, "hit_cells": hit_cells, "graph": graph,
            "size_ok": pos + 8 == len(data)}
