"""The rostests' world: a rectangular room with a few boxes, a lidar that ray-casts it exactly,
and a robot driving a loop through it. Shared by the scan publisher (which simulates) and the
checkers (which know the truth).

The map frame is where the robot starts: at the origin, facing +x. The room is turned by
ROOM_YAW against it so that no wall lies along a row of cells.
"""
import math

import numpy as np

ROOM_YAW = 0.3  # rad

# In the room's own frame (x along its long side), metres.
_ROOM_OUTLINE = [(-2.0, -2.0), (6.0, -2.0), (6.0, 4.0), (-2.0, 4.0)]
_BOXES = [((1.0, 1.5), (1.6, 2.1)), ((3.5, -1.2), (4.3, -0.6)), ((-1.2, 2.5), (-0.6, 3.2))]
_WALL_STUBS = [((2.5, 3.3), (2.5, 4.0))]
# The loop the robot drives, in the room's frame; it starts at the origin and comes back to it.
_LOOP = [(0.0, 0.0), (5.0, 0.0), (5.0, 2.6), (0.0, 2.6)]


def _rotate(points, yaw):
    c, s = math.cos(yaw), math.sin(yaw)
    return [(c * x - s * y, s * x + c * y) for x, y in points]


def _closed(corners):
    return [(corners[i], corners[(i + 1) % len(corners)]) for i in range(len(corners))]


def _box_corners(lo, hi):
    return [lo, (hi[0], lo[1]), hi, (lo[0], hi[1])]


def _room_segments():
    segments = _closed(_ROOM_OUTLINE)
    for lo, hi in _BOXES:
        segments += _closed(_box_corners(lo, hi))
    segments += _WALL_STUBS
    return [tuple(_rotate([a, b], ROOM_YAW)) for a, b in segments]


SEGMENTS = _room_segments()  # in the map frame
WAYPOINTS = _rotate(_LOOP, ROOM_YAW)


def _point_segment_distance(p, a, b):
    p, a, b = np.asarray(p), np.asarray(a), np.asarray(b)
    ab = b - a
    t = np.clip(np.dot(p - a, ab) / np.dot(ab, ab), 0.0, 1.0)
    return float(np.linalg.norm(p - (a + t * ab)))


def distance_to_walls(point):
    return min(_point_segment_distance(point, a, b) for a, b in SEGMENTS)


def inside_room(point, margin):
    """True when `point` is in the room, at least `margin` from its outline and out of the boxes
    by at least `margin`."""
    c, s = math.cos(-ROOM_YAW), math.sin(-ROOM_YAW)
    x = c * point[0] - s * point[1]
    y = s * point[0] + c * point[1]
    (x0, y0), (x1, y1) = _ROOM_OUTLINE[0], _ROOM_OUTLINE[2]
    if not (x0 + margin <= x <= x1 - margin and y0 + margin <= y <= y1 - margin):
        return False
    for (bx0, by0), (bx1, by1) in _BOXES:
        if bx0 - margin <= x <= bx1 + margin and by0 - margin <= y <= by1 + margin:
            return False
    return distance_to_walls(point) >= margin


def wall_samples(spacing):
    """Points along every wall, `spacing` apart."""
    points = []
    for a, b in SEGMENTS:
        length = math.hypot(b[0] - a[0], b[1] - a[1])
        n = max(1, int(length / spacing))
        for i in range(n + 1):
            t = i / n
            points.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
    return points


class Lidar:
    """A planar lidar of `beams` beams over 360 degrees, ray-casting SEGMENTS exactly."""

    def __init__(self, beams=360, range_min=0.15, range_max=12.0, noise=0.01, seed=1):
        self.beams = beams
        self.range_min = range_min
        self.range_max = range_max
        self.noise = noise
        self.angle_increment = 2.0 * math.pi / beams
        self.angle_min = -math.pi
        self.angle_max = self.angle_min + (beams - 1) * self.angle_increment
        self._rng = np.random.default_rng(seed)
        seg = np.array(SEGMENTS)
        self._a = seg[:, 0, :]
        self._e = seg[:, 1, :] - seg[:, 0, :]

    def beam_angles(self):
        return self.angle_min + self.angle_increment * np.arange(self.beams)

    def ranges(self, x, y, heading):
        """Ranges from the sensor at (x, y) facing `heading`; +inf where nothing is hit."""
        angles = heading + self.beam_angles()
        d = np.stack([np.cos(angles), np.sin(angles)], axis=1)  # beams x 2
        return self._finish(self._cast(x, y, d))

    def ranges_3d(self, position, rotation):
        """Ranges of a lidar at 3D `position` (map frame, z above the floor) whose frame has the
        3x3 `rotation` in the map frame: its beams sweep its own x-y plane, so a tilted one
        meets the walls (vertical, as tall as needed) higher or lower, or the floor (z = 0)."""
        a = self.beam_angles()
        d = rotation @ np.stack([np.cos(a), np.sin(a), np.zeros_like(a)])  # 3 x beams
        horizontal = np.hypot(d[0], d[1])
        with np.errstate(divide="ignore", invalid="ignore"):
            flat = np.stack([d[0] / horizontal, d[1] / horizontal], axis=1)
            wall = self._cast(position[0], position[1], flat) / horizontal
            floor = np.where(d[2] < 0.0, position[2] / -d[2], np.inf)
        return self._finish(np.minimum(wall, floor))

    def _finish(self, t):
        t = t + self._rng.normal(0.0, self.noise, size=t.shape)
        t[(t > self.range_max) | (t < self.range_min)] = np.inf
        return t

    def _cast(self, x, y, d):
        """Distance along each unit direction (rows of d) to the nearest segment; inf if none."""
        ao = self._a - np.array([x, y])  # segments x 2
        cross = lambda u, v: u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
        denom = cross(d[:, None, :], self._e[None, :, :])  # beams x segments
        with np.errstate(divide="ignore", invalid="ignore"):
            t = cross(ao[None, :, :], self._e[None, :, :]) / denom
            u = cross(ao[None, :, :], d[:, None, :]) / denom
        hit = (np.abs(denom) > 1e-12) & (t > 0.0) & (u >= 0.0) & (u <= 1.0)
        return np.where(hit, t, np.inf).min(axis=1)


def compose(a, b):
    """a * b for planar poses (x, y, theta)."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], wrap(a[2] + b[2]))


def inverse(a):
    c, s = math.cos(a[2]), math.sin(a[2])
    return (-c * a[0] - s * a[1], s * a[0] - c * a[1], -a[2])


def wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))


def seen_wall_samples(samples, laser_poses, radius=0.05, min_hits=3):
    """The samples that beams of the default Lidar, noise-free, hit within `radius` at least
    `min_hits` times from `laser_poses` (x, y, heading): the walls a map of that drive can show
    occupied. Box sides that face away from every pose are not among them."""
    lidar = Lidar(noise=0.0)
    hits = []
    for x, y, heading in laser_poses:
        ranges = lidar.ranges(x, y, heading)
        angles = heading + lidar.beam_angles()
        ok = np.isfinite(ranges)
        hits.append(np.stack([x + ranges[ok] * np.cos(angles[ok]),
                              y + ranges[ok] * np.sin(angles[ok])], axis=1))
    hits = np.concatenate(hits) if hits else np.zeros((0, 2))
    return [p for p in samples
            if np.count_nonzero(np.hypot(hits[:, 0] - p[0], hits[:, 1] - p[1]) < radius)
            >= min_hits]


class LoopDrive:
    """Drives WAYPOINTS round and round: turn in place towards the next waypoint, then straight
    to it, at constant speeds. step(dt) advances and returns the pose (x, y, theta)."""

    def __init__(self, linear_speed, angular_speed):
        self.v = linear_speed
        self.w = angular_speed
        self.pose = (0.0, 0.0, 0.0)
        self.target = 1

    def step(self, dt):
        x, y, th = self.pose
        budget = dt
        while budget > 1e-12:
            tx, ty = WAYPOINTS[self.target]
            dx, dy = tx - x, ty - y
            dist = math.hypot(dx, dy)
            if dist < 1e-9:
                self.target = (self.target + 1) % len(WAYPOINTS)
                continue
            turn = wrap(math.atan2(dy, dx) - th)
            if abs(turn) > 1e-9:
                dt_turn = min(budget, abs(turn) / self.w)
                th = wrap(th + math.copysign(self.w * dt_turn, turn))
                budget -= dt_turn
                if dt_turn * self.w >= abs(turn) - 1e-12:
                    th = math.atan2(dy, dx)
                continue
            dt_drive = min(budget, dist / self.v)
            x += math.cos(th) * self.v * dt_drive
            y += math.sin(th) * self.v * dt_drive
            budget -= dt_drive
            if dt_drive * self.v >= dist - 1e-12:
                x, y = tx, ty
        self.pose = (x, y, th)
        return self.pose
