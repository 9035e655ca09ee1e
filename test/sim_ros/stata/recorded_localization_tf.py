#!/usr/bin/python3
"""Stands in for the localisation a PR2 ran while the MIT Stata Center bags were recorded: keeps
publishing map -> odom_combined on /tf (a fixed, clearly wrong offset, ~rate Hz), so the
recorded bag carries it as the real ones do, and a replay that fails to drop it shows."""
import math

import rospy
from geometry_msgs.msg import TransformStamped
from tf2_msgs.msg import TFMessage

OFFSET = (1.0, -0.5, 0.3)  # m, m, rad


def main():
    rospy.init_node("recorded_localization_tf")
    publisher = rospy.Publisher("/tf", TFMessage, queue_size=10)
    rate = rospy.Rate(rospy.get_param("~rate", 20.0))
    last = rospy.Time(0)
    while not rospy.is_shutdown():
        now = rospy.Time.now()
        if now > last:  # tf rejects a stamp twice
            t = TransformStamped()
            t.header.stamp = now
            t.header.frame_id = "map"
            t.child_frame_id = rospy.get_param("~odom_frame", "odom_combined")
            t.transform.translation.x, t.transform.translation.y = OFFSET[0], OFFSET[1]
            t.transform.rotation.z = math.sin(OFFSET[2] / 2)
            t.transform.rotation.w = math.cos(OFFSET[2] / 2)
            publisher.publish(TFMessage(transforms=[t]))
            last = now
        try:
            rate.sleep()
        except rospy.ROSTimeMovedBackwardsException:
            pass


if __name__ == "__main__":
    main()
