#!/usr/bin/python3
"""Rebuilds the MIT Killian Court log as a CARMEN file that scripts/freiburg can score.

The Freiburg benchmark's mit-killian.clf is no longer served, and the public copies we found are
broken, except a ROS bag converted from it (INESCTEC/ricoslam,
inesctec_mrdt_slam_2d_datasets/bag/mit-killian.clf2bag.bag) and the relations beside it
(.../data/mit-killian.relations). The bag keeps every scan's ranges and odometry, but it
re-stamps the scans 0.1 s apart, while the relations name the log's own CARMEN stamps, and it
spreads the 180 beams over 180 deg in steps of pi/179 where CARMEN's FLASER convention (ours)
steps pi/180 from -90 deg.

The log's scans come about every 0.44 s, so consecutive stamps the relations name lie
round(dt / T) scans apart. What is left (where the relations start in the log, and a scan or two
at each of the long gaps) is fitted to the log's odometry: the short relations (under 5 s) must
agree with odometry's motion between the scans. The fit leaves 0.029 m mean between them, the
odometry's own error over 1.8 s; one scan off would add 0.1-0.3 m. Scans the relations do not
name get stamps interpolated between those that they do.

usage: scripts/killian_to_clf.py BAG RELATIONS OUT.clf
"""
import math
import os
import sys

import numpy as np
import rosbag

SHORT_RELATION_S = 5.0  # relations this short are compared with odometry
LONG_GAP_S = 3.0        # after a gap this long, the count of scans in it is refitted
GAP_SHIFTS = range(-3, 4)


def read_bag(path):
    """Per scan, in order: (ranges, odometry x, y, yaw)."""
    scans, odometry = [], []
    with rosbag.Bag(path) as bag:
        for topic, msg, _ in bag.read_messages(topics=['/scan', '/odom']):
            if topic == '/scan':
                scans.append(list(msg.ranges))
            else:
                q = msg.pose.pose.orientation
                yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
                odometry.append((msg.pose.pose.position.x, msg.pose.pose.position.y, yaw))
    if len(scans) != len(odometry) or not scans:
        sys.exit('error: %s: expected one /odom message per /scan message, got %d and %d'
                 % (path, len(odometry), len(scans)))
    return scans, np.array(odometry)


def odometry_motion(odometry, i, j):
    xi, yi, ti = odometry[i]
    xj, yj, tj = odometry[j]
    c, s = math.cos(ti), math.sin(ti)
    return np.array([c * (xj - xi) + s * (yj - yi), -s * (xj - xi) + c * (yj - yi)])


def misfit(index, stamp_position, short, odometry):
    """Per short relation, how far odometry's motion is from it (m)."""
    n = len(odometry)
    out = np.empty(len(short))
    for k, r in enumerate(short):
        i, j = index[stamp_position[r[0]]], index[stamp_position[r[1]]]
        if not (0 <= i < n and 0 <= j < n):
            out[k] = math.inf
            continue
        out[k] = np.linalg.norm(odometry_motion(odometry, i, j) - r[2:4])
    return out


def align(relations, odometry):
    """The scan index of every stamp the relations name (sorted stamps, indices)."""
    stamps = np.unique(np.concatenate([relations[:, 0], relations[:, 1]]))
    period = (stamps[-1] - stamps[0]) / (len(odometry) - 1)
    index = np.concatenate([[0], np.cumsum(np.rint(np.diff(stamps) / period).astype(int))])
    if index[-1] >= len(odometry):
        sys.exit('error: the relations span more scans than the bag holds')
    position = {s: k for k, s in enumerate(stamps)}
    short = relations[relations[:, 1] - relations[:, 0] < SHORT_RELATION_S]
    offsets = range(len(odometry) - index[-1])
    offset = min(offsets, key=lambda o: misfit(index + o, position, short, odometry).mean())
    index = index + offset
    # Refit the scan count of each long gap on the relations of the stretch after it.
    pairs = np.array([[position[r[0]], position[r[1]]] for r in short])
    starts = list(np.where(np.diff(stamps) > LONG_GAP_S)[0] + 1)
    for start, end in zip(starts, starts[1:] + [len(stamps)]):
        inside = (pairs[:, 0] >= start) & (pairs[:, 1] < end)
        if not inside.any():
            continue

        def cost(shift):
            trial = index.copy()
            trial[start:] += shift
            return misfit(trial, position, short[inside], odometry).mean()
        index[start:] += min(GAP_SHIFTS, key=cost)
    final = misfit(index, position, short, odometry)
    print('aligned %d stamps to scans %d-%d of %d; short relations against odometry: '
          '%.4f m mean, %.4f m at the 90th percentile'
          % (len(stamps), index[0], index[-1], len(odometry), final.mean(),
             np.percentile(final, 90)))
    return stamps, index


def all_stamps(stamps, index, n):
    """A stamp for every scan: the relations' where they name it, interpolated between."""
    period = (stamps[-1] - stamps[0]) / (index[-1] - index[0])
    scans = np.arange(n)
    out = np.interp(scans, index, stamps)
    out[scans < index[0]] = stamps[0] - (index[0] - scans[scans < index[0]]) * period
    out[scans > index[-1]] = stamps[-1] + (scans[scans > index[-1]] - index[-1]) * period
    return out


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__.strip().splitlines()[-1])
    bag, relations_path, out_path = sys.argv[1:]
    scans, odometry = read_bag(bag)
    relations = np.loadtxt(relations_path, ndmin=2)
    stamps, index = align(relations, odometry)
    stamp = all_stamps(stamps, index, len(scans))
    tmp = out_path + '.tmp'
    with open(tmp, 'w') as out:
        for ranges, (x, y, yaw), t in zip(scans, odometry, stamp):
            out.write('FLASER %d %s %.6f %.6f %.6f %.6f %.6f %.6f %.6f killian %.6f\n'
                      % (len(ranges), ' '.join('%.3f' % r for r in ranges),
                         x, y, yaw, x, y, yaw, t, t))
    os.replace(tmp, out_path)
    print('wrote %d scans to %s' % (len(scans), out_path))


if __name__ == '__main__':
    main()
