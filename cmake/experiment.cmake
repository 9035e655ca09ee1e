# The paper's experiment: the simulator node, worlds, and hex_slam_bench.
