#!/usr/bin/python3
"""Generates the simulated worlds in worlds/: map_server PGM+YAML images at 1 cm per pixel and a
waypoint path through each, for hex_slam_sim and hex_slam_bench.

  maze   6x6 cells of 90 cm with 2 cm walls (5.4 m square), like the paper's robotcraft maze but
         our own layout: a maze carved by a seeded depth-first search, three extra openings so it
         has loops, an entrance on the left of the top row and an exit at the bottom. The path is
         a depth-first tour of every cell from the entrance and back.
  rooms  an 8 m x 6 m floor with 10 cm walls: five rooms off a corridor, doors, furniture. The
         path visits every room and returns.

With --robotcraft BITMAP (the paper's maze, ../shared/data/robotcraft_maze/540x540-90cm.png, not
shipped) it also writes worlds/robotcraft_maze_path.yaml: the same kind of tour through that maze
from stage's start pose (0.05, 4.95). Deterministic: the same script gives the same files.

usage: scripts/make_worlds.py [--out worlds] [--robotcraft BITMAP]
"""
import argparse
import os
import random
import sys

import numpy as np

RESOLUTION = 0.01  # m per pixel
FREE, OCCUPIED = 254, 0  # map_server gray levels

MAZE_CELLS = 6
MAZE_CELL = 0.90  # m
MAZE_WALL = 0.02  # m
MAZE_SEED = 20220816  # the paper's access date; any fixed seed gives a fixed maze
MAZE_EXTRA_OPENINGS = 3
# stage's start pose in the robotcraft world: in the entrance, left of the top row.
MAZE_START = (0.05, 4.95)
# Every path keeps this far from the walls (a small robot's radius plus a margin).
CLEARANCE = 0.15


def write_map(out_dir, name, occupied):
    """occupied: bool array, row 0 at the bottom (world y up). Writes name.pgm and name.yaml."""
    height, width = occupied.shape
    gray = np.where(occupied, OCCUPIED, FREE).astype(np.uint8)[::-1]  # image rows top first
    with open(os.path.join(out_dir, name + ".pgm"), "wb") as f:
        f.write(b"P5\n# hex_slam world %s, %.2f m per pixel\n%d %d\n255\n"
                % (name.encode(), RESOLUTION, width, height))
        f.write(gray.tobytes())
    with open(os.path.join(out_dir, name + ".yaml"), "w") as f:
        f.write("image: %s.pgm\nresolution: %.3f\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n" % (name, RESOLUTION))


def simplify(points):
    """Drops waypoints that lie on the straight line between their neighbours."""
    kept = [points[0]]
    for i in range(1, len(points) - 1):
        a, b, c = np.array(kept[-1]), np.array(points[i]), np.array(points[i + 1])
        cross = (b - a)[0] * (c - b)[1] - (b - a)[1] * (c - b)[0]
        forward = np.dot(b - a, c - b) > 0
        if abs(cross) > 1e-9 or not forward:
            kept.append(points[i])
    kept.append(points[-1])
    return kept


def check_clearance(occ, waypoints, clearance, what):
    """Fails unless every point of the polyline keeps `clearance` metres from every wall."""
    radius = int(np.ceil(clearance / RESOLUTION))
    padded = np.pad(occ, radius)
    grown = np.zeros_like(occ)
    height, width = occ.shape
    for dy in range(-radius, radius + 1):
        for dx in range(-radius, radius + 1):
            if dx * dx + dy * dy <= radius * radius:
                grown |= padded[radius + dy:radius + dy + height, radius + dx:radius + dx + width]
    for a, b in zip(waypoints[:-1], waypoints[1:]):
        a, b = np.array(a), np.array(b)
        steps = max(1, int(np.linalg.norm(b - a) / RESOLUTION))
        for k in range(steps + 1):
            x, y = a + (b - a) * k / steps
            col, row = int(x / RESOLUTION), int(y / RESOLUTION)
            inside = 0 <= row < occ.shape[0] and 0 <= col < occ.shape[1]
            if inside and grown[row, col]:
                raise SystemExit("error: the %s path passes within %.2f m of a wall at (%.2f, %.2f)"
                                 % (what, clearance, x, y))


def write_path(out_dir, name, waypoints, start_heading=0.0, comment=""):
    with open(os.path.join(out_dir, name), "w") as f:
        if comment:
            f.write("# %s\n" % comment)
        f.write("format: hex_slam_waypoint_path\nversion: 1\nstart_heading: %.6f\nwaypoints:\n"
                % start_heading)
        for x, y in waypoints:
            f.write("  - [%.3f, %.3f]\n" % (x, y))


def cell_centre(i, j):
    return ((i + 0.5) * MAZE_CELL, (j + 0.5) * MAZE_CELL)


def tour(open_between, start):
    """A depth-first walk over the cells from `start`, back to it: every cell is visited and each
    corridor is driven once in each direction (as a robot exploring the maze would)."""
    visited = {start}
    walk = [start]

    def visit(cell):
        for nxt in sorted(open_between.get(cell, ())):
            if nxt not in visited:
                visited.add(nxt)
                walk.append(nxt)
                visit(nxt)
                walk.append(cell)

    visit(start)
    return walk


def carve_maze():
    """Returns the set of open passages {(cell, cell)} of a 6x6 maze."""
    rng = random.Random(MAZE_SEED)
    n = MAZE_CELLS
    passages = set()
    stack, seen = [(0, n - 1)], {(0, n - 1)}
    while stack:
        i, j = stack[-1]
        options = [(i + di, j + dj) for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))
                   if 0 <= i + di < n and 0 <= j + dj < n and (i + di, j + dj) not in seen]
        if not options:
            stack.pop()
            continue
        nxt = options[rng.randrange(len(options))]
        passages.add(frozenset(((i, j), nxt)))
        seen.add(nxt)
        stack.append(nxt)
    walls = [frozenset(((i, j), (i + di, j + dj))) for i in range(n) for j in range(n)
             for di, dj in ((1, 0), (0, 1)) if i + di < n and j + dj < n]
    closed = sorted((w for w in walls if w not in passages), key=lambda w: sorted(w))
    for w in rng.sample(closed, MAZE_EXTRA_OPENINGS):
        passages.add(w)
    return passages


def draw_maze(passages):
    n = MAZE_CELLS
    size = int(round(n * MAZE_CELL / RESOLUTION))
    cell = int(round(MAZE_CELL / RESOLUTION))
    wall = int(round(MAZE_WALL / RESOLUTION))
    occ = np.zeros((size, size), dtype=bool)
    # Outer walls inside the square; inner walls centred on the cell boundaries.
    occ[:wall, :] = occ[-wall:, :] = occ[:, :wall] = occ[:, -wall:] = True
    for i in range(n):
        for j in range(n):
            x0, y0 = i * cell, j * cell
            if i + 1 < n and frozenset(((i, j), (i + 1, j))) not in passages:
                occ[y0 - wall // 2:y0 + cell + wall // 2, x0 + cell - wall // 2:x0 + cell + wall // 2] = True
            if j + 1 < n and frozenset(((i, j), (i, j + 1))) not in passages:
                occ[y0 + cell - wall // 2:y0 + cell + wall // 2, x0 - wall // 2:x0 + cell + wall // 2] = True
    occ[:wall, :] = occ[-wall:, :] = occ[:, :wall] = occ[:, -wall:] = True
    # Entrance: the left wall of the top-left cell; exit: the bottom wall of the bottom-right one.
    occ[(n - 1) * cell + wall:n * cell - wall, :wall] = False
    occ[:wall, (n - 1) * cell + wall:n * cell - wall] = False
    return occ


def maze_path(open_between, start_cell):
    cells = tour(open_between, start_cell)
    points = [MAZE_START] + [cell_centre(i, j) for i, j in cells] + [MAZE_START]
    return simplify(points)


def make_maze(out_dir):
    passages = carve_maze()
    write_map(out_dir, "maze", draw_maze(passages))
    open_between = {}
    for p in passages:
        a, b = tuple(p)
        open_between.setdefault(a, set()).add(b)
        open_between.setdefault(b, set()).add(a)
    path = maze_path(open_between, (0, MAZE_CELLS - 1))
    check_clearance(draw_maze(passages), path, CLEARANCE, "maze")
    write_path(out_dir, "maze_path.yaml", path,
               comment="a depth-first tour of worlds/maze from its entrance and back")


def passages_from_bitmap(occ):
    """Reads which neighbouring cells of a 6x6, 90 cm maze bitmap (1 cm pixels, row 0 at the
    bottom) are open: the midpoint of their shared boundary is free."""
    cell = int(round(MAZE_CELL / RESOLUTION))
    open_between = {}
    for i in range(MAZE_CELLS):
        for j in range(MAZE_CELLS):
            cx, cy = i * cell + cell // 2, j * cell + cell // 2
            for di, dj in ((1, 0), (0, 1)):
                if i + di >= MAZE_CELLS or j + dj >= MAZE_CELLS:
                    continue
                # Probe a short line across the boundary between the two centres.
                bx, by = cx + di * cell // 2, cy + dj * cell // 2
                if not occ[by - 3:by + 3, bx - 3:bx + 3].any():
                    open_between.setdefault((i, j), set()).add((i + di, j + dj))
                    open_between.setdefault((i + di, j + dj), set()).add((i, j))
    return open_between


def make_robotcraft_path(out_dir, bitmap):
    import matplotlib.image as mpimg
    image = mpimg.imread(bitmap)
    gray = image[..., :3].mean(axis=2) if image.ndim == 3 else image
    occ = (gray < 0.5)[::-1]  # row 0 at the bottom
    open_between = passages_from_bitmap(occ)
    path = maze_path(open_between, (0, MAZE_CELLS - 1))
    check_clearance(occ, path, CLEARANCE, "robotcraft maze")
    write_path(out_dir, "robotcraft_maze_path.yaml", path,
               comment="a depth-first tour of the robotcraft maze (the paper's world, not shipped) "
                       "from stage's start pose and back")


# The rooms world: outer box 8 m x 6 m, a corridor along y in [2.5, 3.5].
ROOMS_SIZE = (8.0, 6.0)
ROOMS_WALL = 0.10
ROOMS_DOOR = 0.90


def make_rooms(out_dir):
    w, h = ROOMS_SIZE
    width, height = int(round(w / RESOLUTION)), int(round(h / RESOLUTION))
    occ = np.zeros((height, width), dtype=bool)

    def box(x0, y0, x1, y1, value=True):
        occ[int(round(y0 / RESOLUTION)):int(round(y1 / RESOLUTION)),
            int(round(x0 / RESOLUTION)):int(round(x1 / RESOLUTION))] = value

    t = ROOMS_WALL
    box(0, 0, w, t), box(0, h - t, w, h), box(0, 0, t, h), box(w - t, 0, w, h)
    # Corridor walls with a door into each room.
    box(0, 2.5 - t / 2, w, 2.5 + t / 2)
    box(0, 3.5 - t / 2, w, 3.5 + t / 2)
    # Rooms above the corridor: x in [0, 2.5], [2.5, 5.5], [5.5, 8]; below: [0, 4], [4, 8].
    for x in (2.5, 5.5):
        box(x - t / 2, 3.5, x + t / 2, h)
    box(4.0 - t / 2, 0, 4.0 + t / 2, 2.5)
    for x in (1.0, 3.6, 6.3):  # doors from the corridor into the upper rooms
        box(x, 3.5 - t / 2 - 0.01, x + ROOMS_DOOR, 3.5 + t / 2 + 0.01, False)
    for x in (1.6, 5.9):  # and into the lower ones
        box(x, 2.5 - t / 2 - 0.01, x + ROOMS_DOOR, 2.5 + t / 2 + 0.01, False)
    box(4.0 - t / 2 - 0.01, 0.6, 4.0 + t / 2 + 0.01, 0.6 + ROOMS_DOOR, False)  # between lower rooms
    # Furniture: tables, a cupboard, pillars in the corridor-side corners.
    box(0.4, 4.6, 1.2, 5.4)
    box(3.2, 5.2, 4.6, 5.7)
    box(6.6, 4.2, 7.0, 4.6), box(7.2, 5.1, 7.6, 5.5)
    box(0.5, 0.5, 1.3, 1.0)
    box(2.8, 1.4, 3.4, 2.0)
    box(6.5, 0.4, 7.4, 0.8)
    box(4.9, 1.6, 5.2, 1.9)
    write_map(out_dir, "rooms", occ)
    y = 3.0  # corridor centre line
    points = [(0.6, y), (1.45, y), (1.45, 5.6), (0.6, 5.6), (2.1, 5.6), (2.1, 4.3), (1.45, 4.3),
              (1.45, y), (4.05, y), (4.05, 4.6), (5.1, 4.6), (5.1, 4.0), (2.9, 4.0), (2.9, 4.6),
              (4.05, 4.6), (4.05, y), (6.75, y), (6.75, 3.9), (7.6, 3.9), (7.6, 4.8), (6.0, 4.8),
              (6.0, 3.9), (6.75, 3.9), (6.75, y), (6.35, y), (6.35, 2.1), (7.5, 2.1), (7.5, 1.05),
              (2.2, 1.05), (2.2, 0.3), (0.3, 0.3), (0.3, 2.1), (2.05, 2.1), (2.05, y), (0.6, y)]
    check_clearance(occ, points, CLEARANCE, "rooms")
    write_path(out_dir, "rooms_path.yaml", simplify(points),
               comment="through the corridor into every room of worlds/rooms and back")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "worlds"))
    parser.add_argument("--robotcraft", help="the paper's maze bitmap (not shipped)")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    make_maze(args.out)
    make_rooms(args.out)
    if args.robotcraft:
        make_robotcraft_path(args.out, args.robotcraft)
    print("wrote", ", ".join(sorted(os.listdir(args.out))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
