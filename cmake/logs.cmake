# Real robots' logs: CARMEN and bag readers, hex_slam_offline, hex_slam_eval, carmen_to_bag.
