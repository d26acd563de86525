"""The metric's worst case at the footprint limit (docs/metrics.md, "Limits on a method's output"):
a method that stays on the ground and declares `n` disks of `radius` m at the box centre from the
start (flood.yaml runs it)."""


class Flood:
    """n disks of `radius` m at the box centre; never flies."""

    def __init__(self, context, n=15, radius=145.0):
        lo, hi = context.box_min, context.box_max
        self.c = ((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, 1.5)
        self.n, self.r = n, radius

    def observe(self, frame):
        pass

    def plan(self, vehicle):
        return None

    def free_space(self):
        return [(i, self.c[0] + 0.01 * i, self.c[1], self.c[2], self.r) for i in range(self.n)]
