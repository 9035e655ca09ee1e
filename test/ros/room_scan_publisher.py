#!/usr/bin/python3
"""Simulates a robot driving loops through room_world's room and publishes what a real one would:
sensor_msgs/LaserScan on `scan` (ray-cast, with Gaussian range noise), tf odom->base_link from
drifting odometry, a static base_link->laser mount, and the ground truth on `true_pose` (the
base's pose in the map frame, stamped like the scan it belongs to).

Private parameters: rate (Hz), linear_speed, angular_speed, beams, range_noise, odom_noise
(fraction of each step's motion), publish_odom, odom_frame, base_frame, laser_frame, laser_x,
laser_yaw (an RPLidar's cable faces backwards: pi), seed, start_delay (s standing at the origin
before driving, so that the map frame, where the first scan is taken, is room_world's),
reverse_every (every n-th scan is sent as an upside-down lidar sends it: from angle_max down to
angle_min with a negative angle_increment, the same beams; 0 never), duration (s of driving after
which the publisher exits; 0 never).
"""
import math

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import PoseStamped, TransformStamped
from sensor_msgs.msg import LaserScan

import room_world


def yaw_quaternion(yaw):
    return (0.0, 0.0, math.sin(0.5 * yaw), math.cos(0.5 * yaw))


def transform(parent, child, stamp, pose, z=0.0):
    t = TransformStamped()
    t.header.stamp = stamp
    t.header.frame_id = parent
    t.child_frame_id = child
    t.transform.translation.x, t.transform.translation.y = pose[0], pose[1]
    t.transform.translation.z = z
    q = yaw_quaternion(pose[2])
    (t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
     t.transform.rotation.w) = q
    return t


def main():
    rospy.init_node("room_scan_publisher")
    p = lambda name, default: rospy.get_param("~" + name, default)
    rate = p("rate", 20.0)
    odom_frame, base_frame, laser_frame = p("odom_frame", "odom"), p("base_frame", "base_link"), \
        p("laser_frame", "laser")
    publish_odom = p("publish_odom", True)
    odom_noise = p("odom_noise", 0.03)
    mount = (p("laser_x", 0.15), 0.0, p("laser_yaw", math.pi))
    seed = p("seed", 1)
    start_delay = p("start_delay", 2.5)
    reverse_every = p("reverse_every", 0)
    duration = p("duration", 0.0)

    lidar = room_world.Lidar(beams=p("beams", 360), noise=p("range_noise", 0.01), seed=seed)
    drive = room_world.LoopDrive(p("linear_speed", 0.8), p("angular_speed", 1.5))
    rng = np.random.default_rng(seed + 1)

    scan_pub = rospy.Publisher("scan", LaserScan, queue_size=10)
    truth_pub = rospy.Publisher("true_pose", PoseStamped, queue_size=50)
    tf_pub = tf2_ros.TransformBroadcaster()
    static_pub = tf2_ros.StaticTransformBroadcaster()
    static_pub.sendTransform(transform(base_frame, laser_frame, rospy.Time.now(), mount, z=0.2))

    dt = 1.0 / rate
    truth = drive.pose
    odom = truth
    ticker = rospy.Rate(rate)
    start = rospy.Time.now()
    count = 0
    while not rospy.is_shutdown():
        count += 1
        if duration and (rospy.Time.now() - start).to_sec() > start_delay + duration:
            break
        stamp = rospy.Time.now()
        previous = truth
        if (stamp - start).to_sec() >= start_delay:
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
        laser = room_world.compose(truth, mount)
        scan = LaserScan()
        scan.header.stamp = stamp
        scan.header.frame_id = laser_frame
        scan.angle_min = lidar.angle_min
        scan.angle_max = lidar.angle_max
        scan.angle_increment = lidar.angle_increment
        scan.scan_time = dt
        scan.range_min = lidar.range_min
        scan.range_max = lidar.range_max
        ranges = lidar.ranges(*laser).astype(np.float32)
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
