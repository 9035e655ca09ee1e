#!/usr/bin/python3
"""tf_drop_frames: relays a bag's tf (~input, default tf_in) to /tf without the transforms that
touch ~drop_frames (default [map]): the frames a SLAM node publishes itself. Bags recorded on a
robot that was localising already carry map -> odom (the MIT Stata Center bags do); replayed as
they are, the odometry frame would get two parents, ours and the recording's, and tf would
flip between them. Leading slashes (tf1's "/map") are ignored when comparing names."""
import rospy
from tf2_msgs.msg import TFMessage


def main():
    rospy.init_node("tf_drop_frames")
    drop = set(f.lstrip("/") for f in rospy.get_param("~drop_frames", ["map"]))
    publisher = rospy.Publisher("/tf", TFMessage, queue_size=100)
    dropped = [0]

    def relay(msg):
        kept = [t for t in msg.transforms
                if t.header.frame_id.lstrip("/") not in drop and
                t.child_frame_id.lstrip("/") not in drop]
        if len(kept) != len(msg.transforms):
            if dropped[0] == 0:
                rospy.loginfo("tf_drop_frames: dropping the bag's transforms touching %s",
                              ", ".join(sorted(drop)))
            dropped[0] += len(msg.transforms) - len(kept)
        if kept:
            publisher.publish(TFMessage(transforms=kept))

    rospy.Subscriber(rospy.get_param("~input", "tf_in"), TFMessage, relay, queue_size=100)
    rospy.spin()


if __name__ == "__main__":
    main()
