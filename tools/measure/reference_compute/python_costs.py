#!/usr/bin/env python3
"""Per-element costs of the operations the authors' Python MonoSpheres repeats every map update
and planning step (ctu-mrs/monospheres at 43fca1f), written here in the same numpy/Python style
and timed on this machine: the fit of `timing.compute_model: reference_python` (docs/compute.md,
"The reference profile"). Prints one coefficient per line.

    /usr/bin/python3 tools/measure/reference_compute/python_costs.py

Each operation is timed at two sizes; the slope is its cost per element and the intercept its
fixed cost (best of several repetitions, process CPU time)."""
import copy
import heapq
import time

import numpy as np


def best(fn, reps=7):
    t = []
    for _ in range(reps):
        t0 = time.process_time()
        fn()
        t.append(time.process_time() - t0)
    return min(t)


def slope(make, sizes):
    (a, b) = sizes
    ta, tb = best(make(a)), best(make(b))
    per = (tb - ta) / (b - a)
    return per, ta - per * a


rng = np.random.default_rng(1)

# Map update: new visible points against every stored obstacle point (a distance matrix and a
# mask, as the surfel merge does), ~150 new points per update.
def merge(n_stored):
    stored = rng.random((n_stored, 3)) * 100
    new = rng.random((150, 3)) * 100
    def run():
        d = np.sqrt(((new[:, None, :] - stored[None, :, :]) ** 2).sum(axis=2))
        keep = np.sum(d > 0.5, axis=1) == n_stored
        return stored[np.any(d < 0.5, axis=0)], new[keep]
    return run

# Map update: the deep copy of the sphere map the update hands to planning (points, radii, a
# list of neighbour arrays per sphere).
def deep_copy(n_spheres):
    smap = {"points": rng.random((n_spheres, 3)), "radii": rng.random(n_spheres),
            "connections": [rng.integers(0, n_spheres, 6) for _ in range(n_spheres)]}
    return lambda: copy.deepcopy(smap)

# Planning: one candidate viewpoint's frontier value (transform frontiers and normals into the
# camera, project, masks); the authors sample 300 per planning step.
def viewpoint_value(n_frontiers):
    fr = rng.random((n_frontiers, 3)) * 50
    nr = rng.random((n_frontiers, 3))
    K = np.array([[300.0, 0, 320], [0, 300.0, 240], [0, 0, 1]])
    def run():
        for _ in range(300):
            T = np.eye(4)
            T[:3, 3] = rng.random(3)
            Ti = np.linalg.inv(T)
            p = (Ti[:3, :3] @ fr.T).T + Ti[:3, 3]
            n = (Ti[:3, :3] @ nr.T).T
            pix = (K @ p.T).T
            pix = pix[:, :2] / pix[:, 2:3]
            inside = (pix[:, 0] > 0) & (pix[:, 1] > 0) & (pix[:, 0] < 640) & (pix[:, 1] < 480) & (p[:, 2] > 0)
            d = np.linalg.norm(p, axis=1)
            dirs = p / d.reshape((d.size, 1))
            ok = np.sum(dirs * -n, axis=1) / 2 > np.cos(np.pi / 2)
            np.sum(inside & ok & (d < 10))
    return run

# Planning: a Dijkstra over the sphere graph in Python (heapq), as the reachability search runs.
def dijkstra(n_spheres):
    nbrs = [list(rng.integers(0, n_spheres, 6)) for _ in range(n_spheres)]
    pts = rng.random((n_spheres, 3)) * 100
    def run():
        dist = {0: 0.0}
        q = [(0.0, 0)]
        done = set()
        while q:
            c, u = heapq.heappop(q)
            if u in done:
                continue
            done.add(u)
            for v in nbrs[u]:
                nc = c + float(np.linalg.norm(pts[u] - pts[v]))
                if nc < dist.get(v, 1e18):
                    dist[v] = nc
                    heapq.heappush(q, (nc, v))
    return run


if __name__ == "__main__":
    per, fixed = slope(merge, (5000, 20000))
    print(f"map: per obstacle point {per:.3e} s (fixed {fixed:.3e} s)")
    per, fixed = slope(deep_copy, (1000, 4000))
    print(f"map: per sphere (deep copy) {per:.3e} s (fixed {fixed:.3e} s)")
    per, fixed = slope(viewpoint_value, (500, 2000))
    print(f"plan: per frontier (300 viewpoints) {per:.3e} s (fixed {fixed:.3e} s)")
    per, fixed = slope(dijkstra, (1000, 4000))
    print(f"plan: per sphere (Dijkstra) {per:.3e} s (fixed {fixed:.3e} s)")
