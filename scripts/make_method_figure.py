#!/usr/bin/python3
"""Draws docs/figures/method.png: the hexagonal lattice in cube coordinates, the three centres
that interpolate the map at a point, and the cells an exact ray walk crosses.

Pure geometry, recomputed here from MATH.md's formulas (flat-top cells, centre spacing d,
x = X, y = -X/2 + sqrt(3)/2 Y, zeta = -X/2 - sqrt(3)/2 Y)."""
import math
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.patches import Polygon

D = 1.0                      # centre spacing
W = math.sqrt(3) / 2 * D     # cube scale


def centre(a, b):
    return (W * a, 0.5 * D * (a + 2 * b))


def cube(x, y):
    return (x, -x / 2 + math.sqrt(3) / 2 * y, -x / 2 - math.sqrt(3) / 2 * y)


def cell_of(x, y):
    u = [c / W for c in cube(x, y)]
    r = [round(c) for c in u]
    d = [abs(r[i] - u[i]) for i in range(3)]
    if d[0] > d[1] and d[0] > d[2]:
        r[0] = -r[1] - r[2]
    elif d[1] > d[2]:
        r[1] = -r[0] - r[2]
    return (r[0], r[1])


def hexagon(a, b):
    cx, cy = centre(a, b)
    r = D / math.sqrt(3)  # circumradius of a flat-top cell
    return [(cx + r * math.cos(math.radians(60 * k)), cy + r * math.sin(math.radians(60 * k)))
            for k in range(6)]


def main(out):
    fig, ax = plt.subplots(figsize=(7.5, 6.0))
    ray = ((-2.3, -1.55), (2.6, 1.25))
    crossed = set()
    steps = 4000
    for k in range(steps + 1):
        t = k / steps
        crossed.add(cell_of(ray[0][0] + t * (ray[1][0] - ray[0][0]),
                            ray[0][1] + t * (ray[1][1] - ray[0][1])))
    end = cell_of(*ray[1])
    for a in range(-4, 5):
        for b in range(-5, 5):
            cx, cy = centre(a, b)
            if abs(cx) > 3.3 or abs(cy) > 2.6:
                continue
            colour = "#2b2b2b" if (a, b) == end else ("#cfe3f7" if (a, b) in crossed else "white")
            ax.add_patch(Polygon(hexagon(a, b), closed=True, facecolor=colour,
                                 edgecolor="#8a8a8a", lw=0.8))
            ax.plot(cx, cy, ".", color="#8a8a8a", ms=3)
    ax.annotate("", xy=ray[1], xytext=ray[0],
                arrowprops=dict(arrowstyle="->", color="#1f5fa8", lw=1.8))
    ax.text(ray[0][0] - 0.1, ray[0][1] - 0.3, "beam: cells crossed -> free,\nend cell -> occupied",
            color="#1f5fa8", fontsize=9)
    # Cube axes at 0, 120, 240 degrees.
    for ang, name in ((0, "x"), (120, "y"), (240, "\u03b6")):
        dx, dy = 1.3 * math.cos(math.radians(ang)), 1.3 * math.sin(math.radians(ang))
        ax.annotate("", xy=(dx, dy), xytext=(0, 0),
                    arrowprops=dict(arrowstyle="->", color="#b03a2e", lw=1.5))
        ax.text(dx * 1.12, dy * 1.12, name, color="#b03a2e", fontsize=13, ha="center", va="center")
    # A point and the three nearest centres that interpolate M there.
    p = (1.55, -1.25)
    u = [c / W for c in cube(*p)]
    f = [math.floor(c) for c in u]
    if sum(f) == -1:
        tri = [(f[0] + 1, f[1]), (f[0], f[1] + 1), (f[0], f[1])]
    else:
        tri = [(f[0], f[1] + 1), (f[0] + 1, f[1]), (f[0] + 1, f[1] + 1)]
    pts = [centre(*c) for c in tri]
    ax.add_patch(Polygon(pts, closed=True, facecolor="#f5b041", alpha=0.45, edgecolor="#d68910"))
    for q in pts:
        ax.plot(*q, "o", color="#d68910", ms=6)
    ax.plot(*p, "*", color="#7d3c98", ms=13)
    ax.text(p[0] + 0.12, p[1] - 0.35, "M(P) = blend of the 3\nnearest centres", color="#7d3c98",
            fontsize=9)
    ax.text(-3.2, 2.35, "x + y + \u03b6 = 0;  centre spacing d;  cell area (\u221a3/2)d\u00b2",
            fontsize=9)
    ax.set_xlim(-3.3, 3.3)
    ax.set_ylim(-2.6, 2.6)
    ax.set_aspect("equal")
    ax.axis("off")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/figures/method.png")
