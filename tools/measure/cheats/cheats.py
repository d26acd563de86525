"""Methods that try to buy score without mapping (docs/metrics.md, "The earned score"): the holes
issue 71 found in verified coverage, kept as a measurement. Each flies a fixed route and declares
free space it never measured:

  blanket   take off to 2 m, turn once on the spot; one 100 m disk over the start from t = 0
  ceiling   the same flight; a 0.3 m disk at the box's ceiling over every column node of the box
  high_spin climb to 25 m (the urban box's top is 7 m) and turn; the 100 m disk
  outside   climb to 10 m, fly 30 m past the box's +x side and turn; the 100 m disk
  kamikaze  the blanket's spin, then straight ahead along +x at 2 m until it hits something

run.sh flies each in urban beside MonoSpheres and prints the earned score against the paper's A.
"""
import math

KINDS = ("blanket", "ceiling", "high_spin", "outside", "kamikaze")


class Cheat:
    """A fixed route and a free space that no measurement backs."""

    def __init__(self, context, kind="blanket", radius=100.0, turn_step_deg=45.0):
        if kind not in KINDS:
            raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
        self.kind, self.radius = kind, radius
        self.lo, self.hi = list(context.box_min), list(context.box_max)
        x, y, z = context.start_position
        yaw = context.start_yaw_rad
        height = {"high_spin": 25.0, "outside": 10.0}.get(kind, 2.0)
        at = (x, y, z + height) if kind != "outside" else (self.hi[0] + 30.0, y, z + height)
        route = [(x, y, z + height, yaw)]
        if kind == "outside":
            route.append((*at, yaw))
        turns = int(round(360.0 / turn_step_deg))
        route += [(*at, math.remainder(yaw + (k + 1) * math.radians(turn_step_deg), 2 * math.pi))
                  for k in range(turns)]
        if kind == "kamikaze":
            route.append((x + 150.0, y, z + height, 0.0))
        self.route, self.next, self.sent = route, 0, False
        self.centre = (x, y, 1.5)

    def observe(self, frame):
        pass

    def plan(self, vehicle):
        # One leg at a time; hold after the last.
        if self.sent and not vehicle.path_finished:
            return None
        if self.next >= len(self.route):
            return None
        self.sent = True
        self.next += 1
        return [self.route[self.next - 1]]

    def free_space(self):
        if self.kind != "ceiling":
            return [(0, *self.centre, self.radius)]
        out, c = [], 2.5
        for i in range(math.ceil(self.lo[0] / c), math.floor(self.hi[0] / c) + 1):
            for j in range(math.ceil(self.lo[1] / c), math.floor(self.hi[1] / c) + 1):
                out.append((len(out), c * i, c * j, self.hi[2] - 0.25, 0.3))
        return out


def factory(context, **params):
    """msbench calls it with the run's Context and the scenario's params."""
    return Cheat(context, **params)
