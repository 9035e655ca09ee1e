#!/usr/bin/python3
"""run_if_installed.py PACKAGE EXECUTABLE [ARGS...]: becomes that package's node (same process,
same ROS arguments: name, namespace, remappings, private parameters) when the package is
installed, and otherwise says it is not and exits cleanly. Lets one launch file run an optional
comparison, e.g. hector_mapping beside hex_slam_node where hector_mapping exists."""
import os
import sys

import rospkg
import roslib.packages


def main():
    if len(sys.argv) < 3:
        sys.stderr.write("usage: run_if_installed.py PACKAGE EXECUTABLE [ARGS...]\n")
        return 2
    package, executable = sys.argv[1], sys.argv[2]
    try:
        rospkg.RosPack().get_path(package)
    except rospkg.ResourceNotFound:
        print("run_if_installed: %s is not installed (rospack find %s fails): skipping %s" %
              (package, package, executable))
        return 0
    found = roslib.packages.find_node(package, executable)
    if not found:
        print("run_if_installed: %s has no executable %s: skipping it" % (package, executable))
        return 0
    sys.stdout.flush()
    os.execv(found[0], [found[0]] + sys.argv[3:])


if __name__ == "__main__":
    sys.exit(main())
