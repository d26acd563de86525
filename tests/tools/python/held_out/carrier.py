"""A method that carries a world's truth in its own directory (the issue's shipped truth, after
the kit's `oracle_big`): it flies the route an honest run flew there (route.csv: its commanded pose
every 0.1 s, followed in time) and, as it goes,
declares every point of the metric's 0.5 m lattice that its truth (shapes.csv, copied from
msbench's world cache) says is free and in sight: within 10 m of the camera, in front of it, with
no shape between. With box.csv (the box it memorised) it also reads the box it is given: a held-out
world mirrored across the start's heading line has its box mirrored too, and the carrier then
mirrors its truth and its route (docs/worlds.md, "Held-out worlds": what that leaves of the
protection). On the world it memorised that is what its camera crosses, nothing it declares is
an obstacle and it outscores the honest run that drew its route; on a held-out world its truth no
longer fits."""
import csv
import math
import os

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
RANGE_M = 10.0  # the earned score credits what the camera crosses within 10 m


class Shape:
    """One row of shapes.csv as an oriented box (a cylinder or sphere as its box)."""

    def __init__(self, row):
        self.c = np.array([float(row[k]) for k in ("x", "y", "z")])
        w, x, y, z = (float(row[k]) for k in ("qw", "qx", "qy", "qz"))
        self.R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                           [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                           [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
        s = [float(row[k]) for k in ("sx", "sy", "sz")]
        self.half = np.array({"cylinder": [s[0], s[0], s[1]], "sphere": [s[0]] * 3}.get(row["type"], s))
        self.reach = float(np.linalg.norm(self.half))

    def mirrored(self, start, heading):
        """This box mirrored across the vertical plane through `start` along `heading`."""
        n = np.array([-heading[1], heading[0], 0.0])  # the plane's normal
        M = np.eye(3) - 2.0 * np.outer(n, n)
        m = Shape.__new__(Shape)
        m.c, m.R, m.half, m.reach = start + M @ (self.c - start), M @ self.R @ M, self.half, self.reach
        return m

    def contains(self, points, margin):
        return np.all(np.abs((points - self.c) @ self.R) <= self.half + margin, axis=1)

    def blocks(self, eye, points):
        """Which segments eye -> point pass through the box (slab test)."""
        a = (eye - self.c) @ self.R
        d = (points - self.c) @ self.R - a
        with np.errstate(divide="ignore", invalid="ignore"):
            t1, t2 = (-self.half - a) / d, (self.half - a) / d
        lo = np.where(d == 0, np.where(np.abs(a) <= self.half, -np.inf, np.inf), np.minimum(t1, t2))
        hi = np.where(d == 0, np.where(np.abs(a) <= self.half, np.inf, -np.inf), np.maximum(t1, t2))
        enter, leave = lo.max(axis=1), hi.min(axis=1)
        return (enter <= leave) & (leave >= 0) & (enter <= 1)


class Carrier:
    def __init__(self, context):
        self.route = np.loadtxt(os.path.join(HERE, "route.csv"), delimiter=",", ndmin=2)  # t, x, y, z, yaw
        with open(os.path.join(HERE, "shapes.csv")) as f:
            self.shapes = [Shape(r) for r in csv.DictReader(f) if r["type"] != "halfspace"]
        lo, hi = np.asarray(context.box_min, float), np.asarray(context.box_max, float)
        box_file = os.path.join(HERE, "box.csv")
        memorised = np.loadtxt(box_file, delimiter=",") if os.path.exists(box_file) else np.concatenate([lo, hi])
        if not np.allclose(memorised, np.concatenate([lo, hi]), atol=0.01):  # a mirrored world
            start = np.asarray(context.start_position, float)
            heading = np.array([math.cos(context.start_yaw_rad), math.sin(context.start_yaw_rad)])
            self.shapes = [sh.mirrored(start, heading) for sh in self.shapes]
            n = np.array([-heading[1], heading[0], 0.0])
            M = np.eye(3) - 2.0 * np.outer(n, n)
            self.route[:, 1:4] = start + (self.route[:, 1:4] - start) @ M.T
            self.route[:, 4] = 2.0 * context.start_yaw_rad - self.route[:, 4]
        axes = [np.arange(math.ceil(lo[0] * 2) / 2, hi[0], 0.5), np.arange(math.ceil(lo[1] * 2) / 2, hi[1], 0.5),
                np.arange(lo[2] + 0.25, hi[2], 0.5)]
        pts = np.stack([a.ravel() for a in np.meshgrid(*axes, indexing="ij")], axis=1)
        occupied = np.zeros(len(pts), bool)
        for s in self.shapes:
            occupied |= s.contains(pts, 0.3)
        self.points = pts[~occupied]
        self.declared = np.zeros(len(self.points), bool)
        self.last, self.sent_t = None, -1.0

    def observe(self, frame):
        pass

    def _look(self, eye, yaw):
        """Declares the free lattice points in sight from `eye`, facing `yaw`."""
        d = self.points - eye
        near = (np.linalg.norm(d, axis=1) <= RANGE_M) & (d[:, 0] * math.cos(yaw) + d[:, 1] * math.sin(yaw) > -1.0)
        idx = np.flatnonzero(near & ~self.declared)
        seen = np.ones(len(idx), bool)
        for s in self.shapes:
            if np.linalg.norm(s.c - eye) <= RANGE_M + s.reach:
                seen &= ~s.blocks(eye, self.points[idx])
        self.declared[idx[seen]] = True

    def plan(self, vehicle):
        eye = np.asarray(vehicle.position, float)
        if self.last is None or np.linalg.norm(eye - self.last) > 0.5:
            self._look(eye, float(vehicle.yaw_rad))
            self.last = eye
        # The honest run's commands over the next 3 s, sent once a second.
        if vehicle.t_s - self.sent_t < 1.0:
            return None
        self.sent_t = vehicle.t_s
        ahead = self.route[(self.route[:, 0] > vehicle.t_s) & (self.route[:, 0] <= vehicle.t_s + 3.0)][::5]
        return [(float(x), float(y), float(z), float(yaw)) for _, x, y, z, yaw in ahead] or None

    def free_space(self):
        now = self.points[self.declared]
        return [(i + 1, float(p[0]), float(p[1]), float(p[2]), 0.3) for i, p in enumerate(now)]
