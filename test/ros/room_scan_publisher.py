#!/usr/bin/python3
"""Simulates a robot driving loops through room_world's room and publishes what a real one would:
sensor_msgs/LaserScan on `scan` (ray-cast, with Gaussian range noise), tf odom->base_link from
drifting odometry, a static base_link->laser mount, and the ground truth on `true_pose` (the
base's pose in the map frame, stamped like the scan it belongs to).

Private parameters: rate (Hz), linear_speed, angular_speed, beams, range_noise, odom_noise
(fraction of each step's motion), publish_odom, odom_frame, base_frame, laser_frame, laser_x,
laser_yaw (an RPLidar's cable faces backwards: pi), seed, start_delay (s standing at the origin
before driving, so that the map frame, where the first scan is taken, is room_world's),
start_after (topics, space-separated, default "slam_out_pose": the robot also stands until a
message has come on each, i.e. the nodes under test have taken a scan at the origin; "" for no
wait), truth_listeners (default 1: and until that many subscribe to `true_pose`, the checker
among them), start_timeout (s: drive anyway after this long, with a warning), reverse_every
(every n-th scan is sent as an upside-down lidar sends it: from angle_max down to angle_min with
a negative angle_increment, the same beams; 0 never), duration (s of driving after which the
publisher exits, counted in scans, so a slow machine drives the same path; 0 never).

Topics in (std_msgs/Bool), for the tracking-state test: `~hold` stops the robot where it is
(true) or lets it drive on; `~blind` makes every beam read +inf, no return (true), or real again.

A moving mount (a pitching, rolling, sliding laser, as on an IMU-stabilised or a badly fixed
bracket): mount_pitch_amplitude and mount_roll_amplitude (rad), mount_shift_amplitude (m, along
x), over mount_period (s). The mount then goes on /tf at every scan's stamp instead of
/tf_static, at laser_z above the floor, and the scans are cast in 3D: a tilted beam meets a wall
higher or lower, or the floor.
"""
import math

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import PoseStamped, TransformStamped
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Bool

import room_world


def yaw_quaternion(yaw):
    return (0.0, 0.0, math.sin(0.5 * yaw), math.cos(0.5 * yaw))


def euler_quaternion(roll, pitch, yaw):
    """(x, y, z, w) of Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr = math.cos(0.5 * roll), math.sin(0.5 * roll)
    cp, sp = math.cos(0.5 * pitch), math.sin(0.5 * pitch)
    cy, sy = math.cos(0.5 * yaw), math.sin(0.5 * yaw)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def euler_matrix(roll, pitch, yaw):
    """Rz(yaw) Ry(pitch) Rx(roll)."""
    rz = np.array([[math.cos(yaw), -math.sin(yaw), 0], [math.sin(yaw), math.cos(yaw), 0],
                   [0, 0, 1]])
    ry = np.array([[math.cos(pitch), 0, math.sin(pitch)], [0, 1, 0],
                   [-math.sin(pitch), 0, math.cos(pitch)]])
    rx = np.array([[1, 0, 0], [0, math.cos(roll), -math.sin(roll)],
                   [0, math.sin(roll), math.cos(roll)]])
    return rz @ ry @ rx


def transform(parent, child, stamp, pose, z=0.0, roll=0.0, pitch=0.0):
    t = TransformStamped()
    t.header.stamp = stamp
    t.header.frame_id = parent
    t.child_frame_id = child
    t.transform.translation.x, t.transform.translation.y = pose[0], pose[1]
    t.transform.translation.z = z
    q = euler_quaternion(roll, pitch, pose[2])
    (t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
     t.transform.rotation.w) = q
    return t


class Mount:
    """The laser on the base: fixed, or pitching, rolling and sliding over `period` seconds."""

    def __init__(self, x, yaw, z, pitch_amplitude, roll_amplitude, shift_amplitude, period):
        self.x, self.yaw, self.z = x, yaw, z
        self.pitch_amplitude, self.roll_amplitude = pitch_amplitude, roll_amplitude
        self.shift_amplitude, self.period = shift_amplitude, period
        self.moving = bool(pitch_amplitude or roll_amplitude or shift_amplitude)

    def at(self, t):
        """(planar pose on the base, roll, pitch) at time t (s)."""
        phase = 2.0 * math.pi * t / self.period
        return ((self.x + self.shift_amplitude * math.sin(phase), 0.0, self.yaw),
                self.roll_amplitude * math.sin(1.7 * phase), self.pitch_amplitude * math.cos(phase))


def main():
    rospy.init_node("room_scan_publisher")
    p = lambda name, default: rospy.get_param("~" + name, default)
    rate = p("rate", 20.0)
    odom_frame, base_frame, laser_frame = p("odom_frame", "odom"), p("base_frame", "base_link"), \
        p("laser_frame", "laser")
    publish_odom = p("publish_odom", True)
    odom_noise = p("odom_noise", 0.03)
    mount = Mount(p("laser_x", 0.15), p("laser_yaw", math.pi), p("laser_z", 0.2),
                  p("mount_pitch_amplitude", 0.0), p("mount_roll_amplitude", 0.0),
                  p("mount_shift_amplitude", 0.0), p("mount_period", 10.0))
    seed = p("seed", 1)
    start_delay = p("start_delay", 2.5)
    start_after = p("start_after", "slam_out_pose").split()
    truth_listeners = p("truth_listeners", 1)
    start_timeout = p("start_timeout", 30.0)
    reverse_every = p("reverse_every", 0)
    duration = p("duration", 0.0)

    lidar = room_world.Lidar(beams=p("beams", 360), noise=p("range_noise", 0.01), seed=seed)
    drive = room_world.LoopDrive(p("linear_speed", 0.8), p("angular_speed", 1.5))
    rng = np.random.default_rng(seed + 1)

    switches = {"hold": False, "blind": False}

    def switch(name):
        def set_switch(msg):
            switches[name] = msg.data
        return set_switch

    rospy.Subscriber("~hold", Bool, switch("hold"), queue_size=2)
    heard = set()

    def hear(topic):
        def on_message(_):
            heard.add(topic)
        return on_message

    for topic in start_after:
        rospy.Subscriber(topic, rospy.AnyMsg, hear(topic), queue_size=1)
    rospy.Subscriber("~blind", Bool, switch("blind"), queue_size=2)
    scan_pub = rospy.Publisher("scan", LaserScan, queue_size=10)
    truth_pub = rospy.Publisher("true_pose", PoseStamped, queue_size=50)
    tf_pub = tf2_ros.TransformBroadcaster()
    static_pub = tf2_ros.StaticTransformBroadcaster()
    if not mount.moving:
        static_pub.sendTransform(transform(base_frame, laser_frame, rospy.Time.now(),
                                           mount.at(0.0)[0], z=mount.z))

    dt = 1.0 / rate
    truth = drive.pose
    odom = truth
    ticker = rospy.Rate(rate)
    start = rospy.Time.now()
    count = 0
    driving_steps = None  # scans since the robot was let go

    def ready(now):
        if (now - start).to_sec() < start_delay:
            return False
        listening = (len(heard) == len(set(start_after)) and
                     truth_pub.get_num_connections() >= truth_listeners)
        if not listening and (now - start).to_sec() > start_timeout:
            rospy.logwarn("room_scan_publisher: driving after %.0f s without hearing from %s" %
                          (start_timeout, " ".join(sorted(set(start_after) - heard)) or
                           "the truth's listeners"))
            return True
        return listening

    while not rospy.is_shutdown():
        count += 1
        if duration and driving_steps is not None and driving_steps * dt > duration:
            break
        stamp = rospy.Time.now()
        previous = truth
        if driving_steps is None and ready(stamp):
            driving_steps = 0
        if driving_steps is not None:
            driving_steps += 1
            if not switches["hold"]:
                truth = drive.step(dt)
        # Odometry integrates the true step with errors proportional to it: it drifts.
        step = room_world.compose(room_world.inverse(previous), truth)
        moved = math.hypot(step[0], step[1]) + abs(step[2])
        noisy = (step[0] + rng.normal(0.0, odom_noise * moved),
                 step[1] + rng.normal(0.0, odom_noise * moved),
                 step[2] + rng.normal(0.0, odom_noise * moved))
        odom = room_world.compose(odom, noisy)

        if publish_odom:
            tf_pub.sendTransform(transform(odom_frame, base_frame, stamp, odom))
        planar_mount, roll, pitch = mount.at((stamp - start).to_sec())
        if mount.moving:
            tf_pub.sendTransform(transform(base_frame, laser_frame, stamp, planar_mount,
                                           z=mount.z, roll=roll, pitch=pitch))
        laser = room_world.compose(truth, planar_mount)
        scan = LaserScan()
        scan.header.stamp = stamp
        scan.header.frame_id = laser_frame
        scan.angle_min = lidar.angle_min
        scan.angle_max = lidar.angle_max
        scan.angle_increment = lidar.angle_increment
        scan.scan_time = dt
        scan.range_min = lidar.range_min
        scan.range_max = lidar.range_max
        if mount.moving:
            rotation = euler_matrix(roll, pitch, laser[2])
            ranges = lidar.ranges_3d((laser[0], laser[1], mount.z), rotation)
        else:
            ranges = lidar.ranges(*laser)
        ranges = ranges.astype(np.float32)
        if switches["blind"]:
            ranges = np.full_like(ranges, np.inf)
        if reverse_every and count % reverse_every == 0:
            scan.angle_min, scan.angle_max = scan.angle_max, scan.angle_min
            scan.angle_increment = -scan.angle_increment
            ranges = ranges[::-1]
        scan.ranges = ranges.tolist()
        scan_pub.publish(scan)

        true_pose = PoseStamped()
        true_pose.header.stamp = stamp
        true_pose.header.frame_id = "map"
        true_pose.pose.position.x, true_pose.pose.position.y = truth[0], truth[1]
        q = yaw_quaternion(truth[2])
        (true_pose.pose.orientation.x, true_pose.pose.orientation.y,
         true_pose.pose.orientation.z, true_pose.pose.orientation.w) = q
        truth_pub.publish(true_pose)
        try:
            ticker.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
