#!/usr/bin/python3
"""Plots hex_slam_bench's results (run by the bench itself; or by hand on its --work folder):

  bench_rmse.png            position RMSE per row: hex (hex_slam), square (hector's method), the
                            ablation (hex plain, square sub-cell), and the paper's two figures
  bench_trajectory_ID.png   the true path and both estimates, whole and a close-up (as the
                            paper's Figure 8), for each row ID given with --rows
  bench_error_ID.png        position error over time for both lattices, same rows

usage: scripts/plot_bench.py --work out/bench --figures docs/figures [--rows ID,ID]
"""
import argparse
import csv
import math
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

COLOURS = {"truth": "#28aa3c", "hex": "#d62728", "square": "#1f77b4",
           "hex plain": "#ff9896", "square sub-cell": "#17becf",
           "paper hex": "#bbbbbb", "paper hector": "#666666"}
# The close-up: a window of this size (m) around the point where the square error peaks.
CLOSE_UP = 0.6
DPI = 110


def read_tum(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            t, x, y, _z, _qx, _qy, qz, qw = map(float, line.split())
            rows.append((t, x, y, 2.0 * math.atan2(qz, qw)))
    return np.array(rows)


def plot_rmse(results, out):
    names = [r["row"] for r in results]
    series = [("hex", "hex_position_rmse"), ("square", "square_position_rmse"),
              ("hex plain", "hex_plain_position_rmse"),
              ("square sub-cell", "square_subcell_position_rmse"),
              ("paper hex", "paper_hex_position"), ("paper hector", "paper_square_position")]
    x = np.arange(len(names))
    width = 0.13
    fig, ax = plt.subplots(figsize=(max(7, 1.1 * len(names) + 2), 4.4))
    for i, (label, key) in enumerate(series):
        values = [float(r[key]) for r in results]
        ax.bar(x + (i - (len(series) - 1) / 2) * width, [v if v > 0 else np.nan for v in values],
               width, label=label, color=COLOURS[label])
    ax.set_xticks(x)
    ax.set_xticklabels(names, rotation=30, ha="right", fontsize=8)
    ax.set_ylabel("position RMSE (m)")
    ax.set_title("Position RMSE per scenario: hex_slam (hex), hector's method (square), the same "
                 "methods swapped, the paper's Table 1", fontsize=9)
    ax.set_yscale("log")
    ax.legend(fontsize=7, ncol=3)
    ax.grid(axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=DPI)
    plt.close(fig)


def plot_trajectory(truth, hex_, square, title, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.2))
    err = np.hypot(square[:, 1] - truth[:, 1], square[:, 2] - truth[:, 2])
    centre = truth[int(np.argmax(err)), 1:3]
    for ax, close in zip(axes, (False, True)):
        ax.plot(truth[:, 1], truth[:, 2], color=COLOURS["truth"], lw=2.5, label="ground truth")
        ax.plot(hex_[:, 1], hex_[:, 2], color=COLOURS["hex"], lw=1, label="hex")
        ax.plot(square[:, 1], square[:, 2], color=COLOURS["square"], lw=1, label="square")
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.set_xlabel("x (m, map frame)")
        if close:
            ax.set_xlim(centre[0] - CLOSE_UP / 2, centre[0] + CLOSE_UP / 2)
            ax.set_ylim(centre[1] - CLOSE_UP / 2, centre[1] + CLOSE_UP / 2)
            ax.set_title("close-up where the square error peaks")
        else:
            ax.set_ylabel("y (m)")
            ax.set_title(title)
            ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    fig.savefig(out, dpi=DPI)
    plt.close(fig)


def plot_error(truth, hex_, square, title, out):
    fig, ax = plt.subplots(figsize=(9, 3.4))
    for label, est in (("hex", hex_), ("square", square)):
        e = np.hypot(est[:, 1] - truth[:, 1], est[:, 2] - truth[:, 2])
        rmse = math.sqrt(float(np.mean(e * e)))
        ax.plot(truth[:, 0], e, color=COLOURS[label], lw=1, label="%s (RMSE %.4f m)" % (label, rmse))
    ax.set_xlabel("time (s)")
    ax.set_ylabel("position error (m)")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=DPI)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description="plots of hex_slam_bench's results")
    parser.add_argument("--work", required=True, help="the bench's --work folder")
    parser.add_argument("--figures", required=True, help="where the PNGs go")
    parser.add_argument("--rows", default="", help="row ids (map_area_angle_beams) to plot")
    args = parser.parse_args()
    os.makedirs(args.figures, exist_ok=True)
    with open(os.path.join(args.work, "results.csv")) as f:
        results = list(csv.DictReader(f))
    if not results:
        print("error: no rows in results.csv", file=sys.stderr)
        return 1
    written = ["bench_rmse.png"]
    plot_rmse(results, os.path.join(args.figures, written[0]))
    for row_id in filter(None, args.rows.split(",")):
        paths = [os.path.join(args.work, "%s_%s.tum" % (row_id, k))
                 for k in ("truth", "hex", "square")]
        if not all(os.path.exists(p) for p in paths):
            print("warning: no trajectories for %s" % row_id, file=sys.stderr)
            continue
        truth, hex_, square = (read_tum(p) for p in paths)
        title = row_id.replace("_", " / ") + " (seed 1)"
        for kind, plot in (("trajectory", plot_trajectory), ("error", plot_error)):
            name = "bench_%s_%s.png" % (kind, row_id)
            plot(truth, hex_, square, title, os.path.join(args.figures, name))
            written.append(name)
    print("plot_bench: wrote %s in %s" % (", ".join(written), args.figures))
    return 0


if __name__ == "__main__":
    sys.exit(main())
