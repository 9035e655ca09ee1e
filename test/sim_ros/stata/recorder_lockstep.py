#!/usr/bin/python3
"""Answers hex_slam_sim's lockstep for a rosbag record, which cannot (record_stata_sim.launch):
republishes each ground truth on ~truth_seen once ~publisher (the simulator) sends ~subscriber
(the recorder) every one of ~topics. The robot stands at its start until then, so the bag holds
the whole drive however late the recorder came up. Sends as the simulator's own connections
(getBusInfo) list them, not as the master's registrations: the master knows of a subscription
before the publisher has connected it, and scans published in between would miss the bag."""
import xmlrpc.client

import rosgraph
import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry


def sending(master, publisher, subscriber):
    """The topics along which `publisher` has a connection to `subscriber` (none while either
    is not up yet)."""
    try:
        code, _, bus = xmlrpc.client.ServerProxy(master.lookupNode(publisher)).getBusInfo(
            rospy.get_name())
    except (rosgraph.MasterError, OSError, xmlrpc.client.Error):
        return set()
    if code != 1:
        return set()
    # getBusInfo rows: connection id, the other node, direction ("o": we send), transport, topic.
    return {row[4] for row in bus if row[1] == subscriber and row[2] == "o"}


def main():
    rospy.init_node("recorder_lockstep")
    publisher = rospy.resolve_name(rospy.get_param("~publisher"))
    subscriber = rospy.resolve_name(rospy.get_param("~subscriber"))
    topics = {rospy.resolve_name(t) for t in rospy.get_param("~topics").split()}
    seen_pub = rospy.Publisher("~truth_seen", PoseStamped, queue_size=100)
    master = rosgraph.Master(rospy.get_name())
    recording = []

    # The simulator publishes a truth at every step, standing too: each one is the moment to
    # look again whether the recorder is connected, and once it is, the answer.
    def on_truth(msg):
        if not recording:
            if not topics <= sending(master, publisher, subscriber):
                return
            recording.append(True)
            rospy.loginfo("recorder_lockstep: %s records %s from %s: answering the lockstep",
                          subscriber, " ".join(sorted(topics)), publisher)
        seen_pub.publish(PoseStamped(header=msg.header, pose=msg.pose.pose))

    rospy.Subscriber("base_pose_ground_truth", Odometry, on_truth, queue_size=1000)
    rospy.spin()


if __name__ == "__main__":
    main()
