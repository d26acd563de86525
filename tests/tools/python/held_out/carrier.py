"""A method that carries a world's truth in its own directory (the issue's shipped truth, after
the kit's `oracle_big`): it flies the route an honest run flew there (route.csv) and declares, as it
goes, every point of the metric's 0.5 m lattice within 10 m of its route that its truth
(shapes.csv, copied from msbench's world cache) says is free. On the world it memorised nothing
it declares is an obstacle; on a held-out world its truth no longer fits."""
import csv
import math
import os

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def _inside(points, row, margin):
    """Which points lie within `margin` of one shape of shapes.csv (anything but a box, cylinder or
    sphere counts as its box; the ground's half-space as nothing)."""
    c = np.array([float(row[k]) for k in ("x", "y", "z")])
    w, x, y, z = (float(row[k]) for k in ("qw", "qx", "qy", "qz"))
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    s = np.array([float(row[k]) for k in ("sx", "sy", "sz")])
    local = (points - c) @ R
    if row["type"] == "halfspace":
        return np.zeros(len(points), bool)
    if row["type"] == "cylinder":
        return (np.hypot(local[:, 0], local[:, 1]) <= s[0] + margin) & (np.abs(local[:, 2]) <= s[1] + margin)
    if row["type"] == "sphere":
        return np.linalg.norm(local, axis=1) <= s[0] + margin
    return np.all(np.abs(local) <= s + margin, axis=1)


class Carrier:
    def __init__(self, context):
        self.route = np.loadtxt(os.path.join(HERE, "route.csv"), delimiter=",", ndmin=2)  # t, x, y, z
        with open(os.path.join(HERE, "shapes.csv")) as f:
            rows = list(csv.DictReader(f))
        lo, hi = np.asarray(context.box_min, float), np.asarray(context.box_max, float)
        axes = [np.arange(math.ceil(lo[0] * 2) / 2, hi[0], 0.5), np.arange(math.ceil(lo[1] * 2) / 2, hi[1], 0.5),
                np.arange(lo[2] + 0.25, hi[2], 0.5)]
        pts = np.stack([a.ravel() for a in np.meshgrid(*axes, indexing="ij")], axis=1)
        occupied = np.zeros(len(pts), bool)
        for row in rows:
            occupied |= _inside(pts, row, 0.3)
        pts = pts[~occupied]
        first = np.full(len(pts), np.inf)  # when the route first passes within 10 m
        for t, x, y, _ in self.route:
            near = np.hypot(pts[:, 0] - x, pts[:, 1] - y) <= 10.0
            first = np.where(near & np.isinf(first), t, first)
        keep = np.isfinite(first)
        self.points, self.first = pts[keep], first[keep]
        self.t, self.sent = 0.0, False

    def observe(self, frame):
        pass

    def plan(self, vehicle):
        self.t = vehicle.t_s
        if self.sent:
            return None
        self.sent = True
        return [(float(x), float(y), float(max(z, 1.0))) for _, x, y, z in self.route[1:]]

    def free_space(self):
        now = self.points[self.first <= self.t]
        return [(i + 1, float(p[0]), float(p[1]), float(p[2]), 0.3) for i, p in enumerate(now)]
