"""hover_turn in Python: the twin of msbench's example method (core/methods/hover_turn), and a
template for a Python exploration method (docs/python.md).

It takes off, turns on the spot in steps of `turn_step_deg` (one full turn), then descends to
`land_altitude_m` above the start and holds; its map is one free-space sphere around the hover
point, as large as the nearest SLAM point seen during the turn allows.

Run the twin beside the C++ method and compare hashes:
    s = msbench.Scenario.load("scenarios/missions/urban_short.yaml", set=["method.type=hover_turn"])
    m = msbench.Mission(s, method=hover_turn.factory)

The determinism rule: decide with Python floats and the `math` module, in the order the C++ twin
computes (sqrt(dx*dx + dy*dy + dz*dz), left to right) — not with numpy's vectorised functions or
np.sum, whose SIMD kernels and pairwise summation differ from libm and from a loop in the last bits.
Arrays from msbench are read with .tolist(): plain floats, the same bits.
"""
import math


class HoverTurn:
    """Take off, turn once, descend; one free-space sphere around the hover point."""

    CLIMB, TURN, DESCEND, HOLD = range(4)

    def __init__(self, context, takeoff_altitude_m=2.0, turn_step_deg=45.0, land_altitude_m=0.3,
                 max_radius_m=5.0, margin_m=0.5):
        if not 1.0 <= turn_step_deg <= 180.0:
            raise ValueError(f"turn_step_deg must be in [1, 180], got {turn_step_deg}")
        x, y, z = context.start_position
        self.hover = (x, y, z + takeoff_altitude_m)
        self.start_yaw = context.start_yaw_rad
        self.takeoff_altitude_m = takeoff_altitude_m
        self.turn_step_deg = turn_step_deg
        self.land_altitude_m = land_altitude_m
        self.max_radius_m = max_radius_m
        self.margin_m = margin_m
        self.phase = self.CLIMB
        self.sent = False
        self.turn_steps_done = 0
        self.nearest = max_radius_m + margin_m
        self.points_seen = 0

    def observe(self, frame):
        # Only the turn maps: the sphere is centred at the hover point.
        if self.phase != self.TURN:
            return
        hx, hy, hz = self.hover
        for px, py, pz in frame.points.tolist():
            dx, dy, dz = px - hx, py - hy, pz - hz
            self.nearest = min(self.nearest, math.sqrt(dx * dx + dy * dy + dz * dz))
            self.points_seen += 1

    def plan(self, vehicle):
        # Each phase sends one path and moves on when the tracker has finished it.
        if self.sent and not vehicle.path_finished:
            return None
        if self.sent:
            self.sent = False
            if self.phase == self.CLIMB:
                self.phase = self.TURN
            elif self.phase == self.TURN:
                self.turn_steps_done += 1
                if self.turn_steps_done * self.turn_step_deg >= 360.0:
                    self.phase = self.DESCEND
            elif self.phase == self.DESCEND:
                self.phase = self.HOLD
        if self.phase == self.HOLD:
            return None
        x, y, z = self.hover
        heading = self.start_yaw
        if self.phase == self.TURN:
            heading = math.remainder(self.start_yaw + (self.turn_steps_done + 1) * self.turn_step_deg * math.pi / 180.0,
                                     2.0 * math.pi)
        if self.phase == self.DESCEND:
            z += self.land_altitude_m - self.takeoff_altitude_m
        self.sent = True
        return [(x, y, z, heading)]

    def free_space(self):
        # After the turn: the ball around the hover point that holds no observed point.
        r = min(self.max_radius_m, self.nearest - self.margin_m)
        if self.turn_steps_done > 0 and r > 0.0:
            return [(0, *self.hover, r, "disk")]
        return []

    def counters(self):
        return {"turn_steps": float(self.turn_steps_done), "points_seen": float(self.points_seen)}


def factory(context, **params):
    """The method's factory: msbench calls it with the run's Context (and the scenario's params)."""
    return HoverTurn(context, **params)
