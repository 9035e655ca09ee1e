#!/usr/bin/python3
"""The live node as a hector_mapping user runs it: a bag played at 1x and faster with `rosbag
play --clock`, the node started from hector_mapping's mapping_default.launch settings with only
pkg/type changed, optionally with busy cores. Prints one row per run: poses/scans, scan->pose
latency (p50/p99/max, seen by one subscriber of both topics), the node's longest map snapshot
(hex_slam's /diagnostics), its CPU time and peak RSS, and for hex_slam the largest distance to
hex_slam_offline's trajectory of the same bag. hector_mapping runs too where `rospack find
hector_mapping` succeeds (source its workspace first, or pass --hector-setup).

Usage (scripts/live_bench builds first and calls this):
  live_bench.py --bag A.bag [--bag B.bag] [--rate 1 --rate 5] [--busy 2] [--nodes hex,hector]
"""
import argparse
import math
import os
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time

import rosbag

# hector_mapping's launch/mapping_default.launch, value for value (its frames: base_footprint
# and an odom frame "nav" that nothing publishes).
MAPPING_DEFAULT = [
    ("map_frame", "map"), ("base_frame", "base_footprint"), ("odom_frame", "nav"),
    ("use_tf_scan_transformation", "true"), ("use_tf_pose_start_estimate", "false"),
    ("pub_map_odom_transform", "true"),
    ("map_resolution", "0.050"), ("map_size", "2048"), ("map_start_x", "0.5"),
    ("map_start_y", "0.5"), ("map_multi_res_levels", "2"),
    ("update_factor_free", "0.4"), ("update_factor_occupied", "0.9"),
    ("map_update_distance_thresh", "0.4"), ("map_update_angle_thresh", "0.06"),
    ("laser_z_min_value", "-1.0"), ("laser_z_max_value", "1.0"),
    ("advertise_map_service", "true"), ("scan_subscriber_queue_size", "5"),
    ("tf_map_scanmatch_transform_frame_name", "scanmatcher_frame"),
]
NODES = {"hex": ("hex_slam", "hex_slam_node"), "hector": ("hector_mapping", "hector_mapping")}
SETTLE_S = 2.0  # wall s without a new pose after the bag ends: the node has caught up


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def bag_facts(path):
    """(scan topic, laser frame, scans, the laser's parent in the bag's tf or None)."""
    with rosbag.Bag(path) as bag:
        info = bag.get_type_and_topic_info().topics
        scan_topics = [t for t, i in info.items() if i.msg_type == "sensor_msgs/LaserScan"]
        if not scan_topics:
            raise SystemExit("error: %s has no sensor_msgs/LaserScan topic" % path)
        topic = scan_topics[0]
        frame = None
        for _, msg, _ in bag.read_messages(topics=[topic]):
            frame = msg.header.frame_id.lstrip("/")
            break
        parent = None
        for _, msg, _ in bag.read_messages(topics=["/tf", "/tf_static"]):
            for t in msg.transforms:
                if t.child_frame_id.lstrip("/") == frame:
                    parent = t.header.frame_id.lstrip("/")
            if parent:
                break
        return topic, frame, info[topic].message_count, parent


def settings_for(parent, overrides):
    """mapping_default.launch's parameters; base_frame the laser's parent where the bag's tf has
    one (the launch file's base_frame argument); then --set overrides."""
    settings = dict(MAPPING_DEFAULT)
    if parent:
        settings["base_frame"] = parent
    settings.update(overrides)
    return list(settings.items())


def launch_file(node, topic, settings, name, prefix=""):
    """mapping_default.launch's node with `settings`, named `name`, started through `prefix`
    (roslaunch's launch-prefix: a profiler) when one is given."""
    package, executable = NODES[node]
    prefix = ' launch-prefix="%s"' % prefix if prefix else ""
    params = "\n".join('    <param name="%s" value="%s"/>' % kv for kv in settings)
    return """<launch>
  <param name="/use_sim_time" value="true"/>
  <node pkg="%s" type="%s" name="%s" output="log"%s>
%s
    <param name="scan_topic" value="%s"/>
  </node>
</launch>
""" % (package, executable, name, prefix, params, topic)


def mount_laser(frame):
    """What a user adds for a bag without tf (Debian has no static_transform_publisher): the
    laser at base_footprint's origin, latched. Returns the broadcaster (keep it alive)."""
    import rospy
    import tf2_ros
    from geometry_msgs.msg import TransformStamped
    t = TransformStamped()
    t.header.stamp = rospy.Time(0)
    t.header.frame_id = "base_footprint"
    t.child_frame_id = frame
    t.transform.rotation.w = 1.0
    broadcaster = tf2_ros.StaticTransformBroadcaster()
    broadcaster.sendTransform(t)
    return broadcaster


def yaml_config(settings):
    return "".join("%s: %s\n" % kv for kv in settings)


def proc_figures(pid):
    """(CPU s, peak RSS MB) of a live process."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    ticks = os.sysconf("SC_CLK_TCK")
    cpu = (int(fields[11]) + int(fields[12])) / ticks
    rss = 0.0
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmHWM:"):
                rss = int(line.split()[1]) / 1024.0
    return cpu, rss


def thread_figures(pid):
    """CPU s of each of the process's threads, busiest first: where the time goes."""
    ticks = os.sysconf("SC_CLK_TCK")
    threads = []
    for tid in os.listdir("/proc/%d/task" % pid):
        try:
            with open("/proc/%d/task/%s/stat" % (pid, tid)) as f:
                name = f.read().split("(", 1)[1].rsplit(")", 1)[0]
                f.seek(0)
                fields = f.read().rsplit(")", 1)[1].split()
            threads.append((int(fields[11]) + int(fields[12])) / ticks)
        except (OSError, IndexError):
            continue
    return sorted(threads, reverse=True)


def is_node(pid, name):
    """Whether process `pid` is the node `name` itself (not a launcher or shell naming it)."""
    try:
        with open("/proc/%s/cmdline" % pid) as f:
            args = f.read().split("\0")
    except OSError:
        return False
    return "__name:=" + name in args and "python" not in os.path.basename(args[0])


def find_pid(name, timeout=30.0):
    deadline = time.time() + timeout
    while time.time() < deadline:
        out = subprocess.run(["pgrep", "-f", "__name:=" + name], capture_output=True, text=True)
        pids = [int(p) for p in out.stdout.split() if is_node(p, name)]
        if pids:
            return pids[0]
        time.sleep(0.2)
    return None


def percentile(values, q):
    if not values:
        return float("nan")
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(math.ceil(q * len(ordered))) - 1)]


class Watcher:
    """Wall arrival of each scan and each pose, by stamp; the node's diagnostics."""

    def __init__(self, rospy, topic):
        from diagnostic_msgs.msg import DiagnosticArray
        from geometry_msgs.msg import PoseStamped
        self.lock = threading.Lock()
        self.scan_at = {}
        self.pose_at = {}
        self.poses = {}
        self.snapshot_ms = 0.0
        self.diag = {}
        self.last_pose_wall = time.time()
        # Scans unparsed: deserialising a 1000-beam scan in Python at 200 Hz would load the core
        # the node runs on and show as the node's latency. Only the header's stamp is read.
        rospy.Subscriber(topic, rospy.AnyMsg, self._scan, queue_size=1000)
        rospy.Subscriber("slam_out_pose", PoseStamped, self._pose, queue_size=1000)
        rospy.Subscriber("/diagnostics", DiagnosticArray, self._diag, queue_size=10)

    def _scan(self, msg):
        now = time.monotonic()
        # std_msgs/Header first: uint32 seq, uint32 secs, uint32 nsecs, little-endian.
        _, secs, nsecs = struct.unpack_from("<III", msg._buff, 0)
        with self.lock:
            self.scan_at.setdefault(secs * 1000000000 + nsecs, now)

    def _pose(self, msg):
        now = time.monotonic()
        with self.lock:
            stamp = msg.header.stamp.to_nsec()
            self.pose_at[stamp] = now
            p = msg.pose
            yaw = math.atan2(2 * (p.orientation.w * p.orientation.z),
                             1 - 2 * p.orientation.z ** 2)
            self.poses[stamp] = (p.position.x, p.position.y, yaw)
            self.last_pose_wall = time.time()

    def _diag(self, msg):
        for status in msg.status:
            values = {kv.key: kv.value for kv in status.values}
            with self.lock:
                self.diag = values
                for key in ("snapshot_ms_max", "snapshot_ms"):
                    if key in values:
                        try:
                            self.snapshot_ms = max(self.snapshot_ms, float(values[key]))
                        except ValueError:
                            pass

    def arrivals(self):
        with self.lock:
            return sorted(self.scan_at.values())

    def latencies(self):
        with self.lock:
            return [1000.0 * (self.pose_at[s] - self.scan_at[s])
                    for s in self.pose_at if s in self.scan_at]


def offline_trajectory(devel_lib, bag, workdir, overrides):
    topic, _, _, parent = bag_facts(bag)
    config = os.path.join(workdir, "mapping_default.yaml")
    with open(config, "w") as f:
        f.write(yaml_config(settings_for(parent, overrides)))
    out = os.path.join(workdir, "offline")
    run = subprocess.run([os.path.join(devel_lib, "hex_slam_offline"), "--bag", bag, "--topic",
                          topic, "--config", config, "--out", out, "--no-progress"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        print("warning: hex_slam_offline failed:\n" + run.stdout + run.stderr, file=sys.stderr)
        return {}
    poses = {}
    with open(os.path.join(out, "trajectory.tum")) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            t, x, y, _, qx, qy, qz, qw = (float(v) for v in line.split()[:8])
            poses[int(round(t * 1e9))] = (x, y)
    return poses


def nearest_difference(live, offline):
    """Largest planar distance between live and offline poses at the same stamps (1 us slack)."""
    if not offline:
        return float("nan")
    stamps = sorted(offline)
    import bisect
    worst = 0.0
    for stamp, pose in live.items():
        i = bisect.bisect_left(stamps, stamp)
        for j in (i - 1, i):
            if 0 <= j < len(stamps) and abs(stamps[j] - stamp) <= 1000:
                o = offline[stamps[j]]
                worst = max(worst, math.hypot(pose[0] - o[0], pose[1] - o[1]))
    return worst


def queue_drops(arrivals, capacity, service_s):
    """Scans a node would lose that took `service_s` for every scan behind a queue of
    `capacity` dropping the oldest (hector's subscriber queue and ours): what the delivery's
    bursts alone force on any node, whatever its own speed beyond that."""
    dropped = 0
    waiting = []  # arrival times of the queued scans, oldest first
    free_at = float("-inf")  # when the node finishes the scan it is working on
    for t in arrivals:
        while waiting and free_at <= t:  # the node takes the oldest once it is free
            free_at = max(free_at, waiting.pop(0)) + service_s
        if not waiting and free_at <= t:
            free_at = t + service_s
            continue
        waiting.append(t)
        if len(waiting) > capacity:
            waiting.pop(0)
            dropped += 1
    return dropped


def run_once(args, node, bag, rate, workdir, offline):
    topic, frame, scans, parent = bag_facts(bag)
    port = free_port()
    name = "slam_under_test_%d" % port  # unique: a previous run's node may still be exiting
    env = dict(os.environ, ROS_MASTER_URI="http://localhost:%d" % port,
               ROS_HOME=os.path.join(workdir, "ros_home"))
    os.environ.update(ROS_MASTER_URI=env["ROS_MASTER_URI"])
    procs = []
    busy = []
    log = open(os.path.join(workdir, "%s_%s.log" % (node, rate)), "w")
    try:
        procs.append(subprocess.Popen(["rosmaster", "--core", "-p", str(port)], env=env,
                                      stdout=log, stderr=subprocess.STDOUT))
        time.sleep(1.0)
        launch = os.path.join(workdir, "%s.launch" % node)
        with open(launch, "w") as f:
            f.write(launch_file(node, topic, settings_for(parent, args.overrides), name,
                                args.launch_prefix))
        procs.append(subprocess.Popen(["roslaunch", "-p", str(port), launch], env=env,
                                      stdout=log, stderr=subprocess.STDOUT))
        pid = find_pid(name)
        if pid is None:
            raise RuntimeError("the node did not start; see " + log.name)
        import rospy
        rospy.init_node("live_bench", anonymous=True, disable_signals=True)
        watcher = Watcher(rospy, topic)
        mount = mount_laser(frame) if not parent else None  # noqa: F841 (kept alive)
        # The node is ready once it subscribes to the scans.
        deadline = time.time() + 30.0
        while time.time() < deadline:
            subs = subprocess.run(["rostopic", "info", topic], env=env, capture_output=True,
                                  text=True).stdout
            if name in subs.split("Subscribers:")[-1]:
                break
            time.sleep(0.2)
        for _ in range(args.busy):
            busy.append(subprocess.Popen(["yes"], stdout=subprocess.DEVNULL))
        play = subprocess.run(["rosbag", "play", "--clock", "-q", "-d", "1", "-r", str(rate), bag],
                              env=env, stdout=log, stderr=subprocess.STDOUT)
        if play.returncode != 0:
            raise RuntimeError("rosbag play failed; see " + log.name)
        deadline = time.time() + 60.0
        while time.time() < deadline and time.time() - watcher.last_pose_wall < SETTLE_S:
            time.sleep(0.2)
        cpu, rss = proc_figures(pid)
        threads = thread_figures(pid)
        latency = watcher.latencies()
        capacity = int(dict(settings_for(parent, args.overrides))["scan_subscriber_queue_size"])
        forced = queue_drops(watcher.arrivals(), capacity, args.burst_service_ms / 1000.0)
        difference = nearest_difference(watcher.poses, offline) if node == "hex" else float("nan")
        return {
            "node": node, "bag": os.path.basename(bag), "rate": rate, "busy": args.busy,
            "poses": len(watcher.poses), "scans": scans,
            "p50": percentile(latency, 0.5), "p99": percentile(latency, 0.99),
            "max": max(latency) if latency else float("nan"),
            "snapshot": watcher.snapshot_ms if node == "hex" else float("nan"),
            # The node's own arrival-to-pose figures (hex_slam's /diagnostics), beside the
            # watcher's, which include the watcher's and the transport's delays.
            "node_p99": float(watcher.diag.get("latency_p99_ms", "nan")),
            "node_max": float(watcher.diag.get("latency_max_ms", "nan")),
            "dropped": watcher.diag.get("dropped_queue_overflow", "-"), "forced": forced,
            "cpu": cpu, "cpu_ms_per_scan": 1000.0 * cpu / max(1, scans), "rss": rss,
            "offline_diff": difference, "diag": dict(watcher.diag), "threads": threads,
        }
    finally:
        for p in busy:
            p.kill()
        for p in reversed(procs):
            p.send_signal(signal.SIGINT)
            try:
                p.wait(timeout=15)
            except subprocess.TimeoutExpired:
                p.kill()
        log.close()


def unexplained_missing_poses(row):
    """hex_slam_node's scans that got no pose and were not dropped from its queue (a scan it
    could not match, or one lost in transport), beyond 1 % of the scans; 0 for other nodes."""
    if row["node"] != "hex":
        return 0
    try:
        dropped = int(row["dropped"])
    except ValueError:
        return 0
    missing = row["scans"] - row["poses"] - dropped
    return missing if missing > 0.01 * row["scans"] else 0


def run_isolated(*run_args):
    """run_once in a child process: each run has a master of its own, and a process can join
    only one ROS master."""
    import multiprocessing
    results = multiprocessing.get_context("fork").Queue()

    def child():
        try:
            results.put(run_once(*run_args))
        except Exception as e:  # reported by the parent
            results.put(e)

    process = multiprocessing.get_context("fork").Process(target=child)
    process.start()
    result = results.get()
    process.join()
    if isinstance(result, Exception):
        raise result
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bag", action="append", required=True)
    parser.add_argument("--rate", action="append", type=float)
    parser.add_argument("--busy", type=int, default=0, help="cores kept busy by `yes`")
    parser.add_argument("--nodes", default="hex,hector")
    parser.add_argument("--devel-lib", default=os.environ.get("DEVEL_LIB", ""))
    parser.add_argument("--keep", action="store_true",
                        help="keep the work folder (logs); it is kept anyway after a hex run "
                             "with scans neither posed nor dropped")
    parser.add_argument("--threads", action="store_true",
                        help="also print each run's CPU seconds per thread, busiest first")
    parser.add_argument("--launch-prefix", default="",
                        help="roslaunch launch-prefix for the node, e.g. 'heaptrack -o FILE'")
    parser.add_argument("--burst-service-ms", type=float, default=1.0,
                        help="per-scan time of the ideal node whose drops the delivery's "
                             "bursts force (the 'forced' column)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a parameter over mapping_default.launch's, for both nodes")
    args = parser.parse_args()
    args.overrides = dict(kv.split("=", 1) for kv in args.set)
    rates = args.rate or [1.0]
    workdir = tempfile.mkdtemp(prefix="live_bench_")
    nodes = [n.strip() for n in args.nodes.split(",") if n.strip()]
    rows = []
    keep = args.keep
    try:
        for node in nodes:
            package = NODES[node][0]
            if subprocess.run(["rospack", "find", package], capture_output=True).returncode:
                print("note: %s is not installed (rospack find %s fails): skipping it" %
                      (package, package))
                continue
            for bag in args.bag:
                offline = {}
                if node == "hex" and args.devel_lib:
                    offline = offline_trajectory(args.devel_lib, bag, workdir, args.overrides)
                for rate in rates:
                    row = run_isolated(args, node, bag, rate, workdir, offline)
                    rows.append(row)
                    print_row(row, header=len(rows) == 1)
                    unexplained = unexplained_missing_poses(row)
                    if unexplained > 0:
                        # A rare run that loses track (stop 55) is worth its node's log.
                        print("note: %d scans neither posed nor dropped from the queue: "
                              "keeping the work folder" % unexplained)
                        keep = True
                    if args.threads:
                        print("  threads' CPU s: " +
                              " ".join("%.2f" % t for t in row["threads"][:8]))
                        print("  diagnostics: " + " ".join(
                            "%s=%s" % kv for kv in sorted(row["diag"].items())))
                    sys.stdout.flush()
    finally:
        if keep:
            print("work folder: " + workdir)
        else:
            shutil.rmtree(workdir, ignore_errors=True)
    return 0


def print_row(r, header):
    if header:
        print("| node | bag | rate | busy cores | poses / scans | dropped (queue) | forced | "
              "latency p50 / p99 / max ms | in-node p99 / max ms | longest snapshot ms | CPU s | "
              "CPU ms/scan | peak RSS MB | max distance to offline m |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    in_node = "-" if math.isnan(r["node_p99"]) else "%.1f / %.1f" % (r["node_p99"], r["node_max"])
    print("| %s | %s | %gx | %d | %d / %d | %s | %d | %.1f / %.1f / %.1f | %s | %s | %.2f | %.2f | %.0f | %s |" % (
        r["node"], r["bag"], r["rate"], r["busy"], r["poses"], r["scans"], r["dropped"], r["forced"], r["p50"],
        r["p99"], r["max"], in_node, "-" if math.isnan(r["snapshot"]) else "%.1f" % r["snapshot"], r["cpu"],
        r["cpu_ms_per_scan"], r["rss"],
        "-" if math.isnan(r["offline_diff"]) else "%.4f" % r["offline_diff"]))


if __name__ == "__main__":
    sys.exit(main())
