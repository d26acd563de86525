"""A gym-style environment over an msbench mission (docs/python.md, "Gym-style adapter").

    env = msbench.gym.ExplorationEnv("scenarios/missions/grid_random.yaml", set=["world=urban"])
    obs, info = env.reset(seed=1)
    while True:
        goal = (obs["position"][0] + 5.0, obs["position"][1], 2.0)   # an action: a goal or a path
        obs, reward, terminated, truncated, info = env.step(goal)    # reward: coverage gained, m²
        if terminated or truncated:
            break

The action is a goal (x, y, z) that msbench's A* plans to on its OctoMap, or a path (K×3,
flown as given; the predicted-path check still stops the vehicle before an occupied cell), in the
estimate frame. Each step flies `decision_period_s` of simulated time; the action takes effect
at the grid method's next goal check (every `method.goal_period_s`, 1 s by default). The reward
is the coverage area gained during the step (the paper's metric, m²); `terminated` means the run
ended early (collision, VIO loss), `truncated` that the mission's duration ran out. The scenario
must use the grid method (`method.type: grid_random`): its map scores the free space and plans to
the goals; only the choice of goals is the agent's.

The class subclasses `gymnasium.Env` when gymnasium is importable (not packaged for Debian 12) and
is a plain class with the same methods otherwise; its `action_space` and `observation_space` are
gymnasium's spaces then, msbench's own (`msbench.spaces`: same fields, seeded `sample()`,
`contains()`) without it — never None.
"""
import math
import os

import numpy as np

from ._msbench import Mission, Scenario
from . import spaces as _spaces

try:  # gymnasium is optional
    import gymnasium as _gymnasium
    _Base = _gymnasium.Env
except ImportError:  # pragma: no cover - depends on the machine
    _gymnasium = None
    _Base = object

#: run statuses that end an episode early (anything else ending it is the time limit)
EARLY_END = ("collided", "vio_lost", "diverged", "error")


def _scenario_source(scenario, sets):
    """(path, list of KEY=VALUE) from a path or a Scenario plus more `sets` (list or dict)."""
    extra = [f"{k}={_set_value(v)}" for k, v in sets.items()] if isinstance(sets, dict) else list(sets)
    if isinstance(scenario, Scenario):
        return scenario.file, list(scenario.sets) + extra
    return os.fspath(scenario), extra


def _set_value(v):
    """A Python value as the text of a --set value (YAML): true/false, numbers, strings."""
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v)


def _as_action(action):
    """A goal as one (x, y, z) tuple, a path as a list of them (plain floats: deterministic)."""
    values = action.tolist() if hasattr(action, "tolist") else action
    if len(values) == 3 and not hasattr(values[0], "__len__"):
        return tuple(float(v) for v in values)
    path = [tuple(float(v) for v in p) for p in values]
    if not path or any(len(p) != 3 for p in path):
        raise ValueError("an action is a goal (x, y, z) or a non-empty path of (x, y, z)")
    return path


def _top_down(request, cells, cell_m, z_band):
    """The OctoMap's leaves reaching into the height band z_band, in a cells × cells window
    centred on the vehicle: 0 unknown, 1 free, 2 occupied (occupied wins in a column). A leaf
    larger than a cell fills every cell it covers."""
    grid = np.zeros((cells, cells), np.uint8)
    origin = np.asarray(request.position[:2], float) - 0.5 * cells * cell_m
    for value, leaves in ((1, request.free()), (2, request.occupied())):
        leaves = leaves[(leaves[:, 2] + 0.5 * leaves[:, 3] > z_band[0]) & (leaves[:, 2] - 0.5 * leaves[:, 3] < z_band[1])]
        if len(leaves) == 0:
            continue
        half = 0.5 * leaves[:, 3:4]
        lo = np.floor((leaves[:, :2] - half - origin) / cell_m).astype(int)
        hi = np.ceil((leaves[:, :2] + half - origin) / cell_m).astype(int)
        lo, hi = np.clip(lo, 0, cells), np.clip(hi, 0, cells)
        for (x0, y0), (x1, y1) in zip(lo, hi):
            if x1 > x0 and y1 > y0:
                view = grid[y0:y1, x0:x1]
                np.maximum(view, value, out=view)
    return grid


class ExplorationEnv(_Base):
    """An exploration mission as a gym-style environment: reset(seed) -> (obs, info),
    step(action) -> (obs, reward, terminated, truncated, info)."""

    metadata = {"render_modes": []}
    _METHOD = "grid_random"  # the method whose goal choice the agent makes

    def __init__(self, scenario, set=(), decision_period_s=2.0, map_cells=0, map_cell_m=1.0, map_z_m=(0.5, 4.0)):
        """scenario: a path or a loaded msbench.Scenario (its `set` values kept); set: more
        KEY=VALUE overrides (a list, or a dict); decision_period_s: simulated time per step;
        map_cells > 0 adds obs["map"]: a map_cells × map_cells top-down window of the grid
        method's OctoMap centred on the vehicle, map_cell_m a cell, of the leaves that reach into
        the height band map_z_m (the ground stays out): 0 unknown, 1 free, 2 occupied (occupied
        wins in a column); rows along y, columns along x, estimate frame; as of the last goal
        check (none before the first: all unknown)."""
        if not decision_period_s > 0:
            raise ValueError("decision_period_s must be > 0")
        if int(map_cells) != map_cells or not 0 <= map_cells <= 1024:
            raise ValueError("map_cells must be an integer in [0, 1024]")
        if not map_cell_m > 0:
            raise ValueError("map_cell_m must be > 0")
        if len(map_z_m) != 2 or not map_z_m[0] < map_z_m[1]:
            raise ValueError("map_z_m must be (low, high) with low < high")
        self._map_cells, self._map_cell_m, self._map_z_m = int(map_cells), float(map_cell_m), tuple(map_z_m)
        self._map = None
        self._path, self._sets = _scenario_source(scenario, set)
        self._period_s = float(decision_period_s)
        probe = Scenario.load(self._path, set=self._sets)  # bad files and keys fail here (ConfigError)
        if probe.method != self._METHOD:
            raise ValueError(f"{scenario}: {type(self).__name__} needs method.type {self._METHOD} (got '{probe.method}')")
        camera = probe.effective()["camera"]
        self.frame_shape = (int(camera["height_px"]), int(camera["width_px"]))
        self._mission = None
        self._pending = None
        self._area = 0.0
        self._goal_requests = 0
        self.action_space = _spaces.make_box(-math.inf, math.inf, (3,), float)
        self.observation_space = _spaces.make_dict({
            "frame": _spaces.make_box(0, 255, self.frame_shape, "uint8"),
            "pose": _spaces.make_box(-math.inf, math.inf, (4, 4), float),
            "position": _spaces.make_box(-math.inf, math.inf, (3,), float),
            "velocity": _spaces.make_box(-math.inf, math.inf, (3,), float),
            **({"map": _spaces.make_box(0, 2, (self._map_cells, self._map_cells), "uint8")} if self._map_cells else {}),
        })

    @property
    def mission(self):
        """The current msbench.Mission (result(), hash, write() once the episode ended)."""
        return self._mission

    def reset(self, seed=None, options=None):
        """Starts a new mission (the scenario's seed, or `seed`); returns (obs, info)."""
        sets = self._sets + ([f"seed={int(seed)}"] if seed is not None else [])
        self._mission = Mission(Scenario.load(self._path, set=sets), goals=self._choose)
        self._pending = None
        self._area = 0.0
        self._goal_requests = 0
        self._map = None
        tick = self._mission.step(1)
        while tick.frame is None and self._mission.running:  # up to the first rendered frame
            tick = self._mission.step(1)
        self._frame = tick.frame
        return self._observation(tick), self._info(tick)

    def step(self, action):
        """Flies decision_period_s towards the action; returns (obs, reward, terminated, truncated, info)."""
        if self._mission is None:
            raise RuntimeError("call reset() before step()")
        if not self._mission.running:
            raise RuntimeError("the episode has ended: call reset()")
        self._pending = self._action(action)
        tick = self._mission.step(max(1, round(self._period_s * self._mission.physics_hz)))
        if tick.frame is not None:
            self._frame = tick.frame
        area = self._area_now()
        reward = area - self._area
        self._area = area
        terminated = self._mission.status in EARLY_END
        truncated = not self._mission.running and not terminated
        return self._observation(tick), reward, terminated, truncated, self._info(tick)

    def _area_now(self):
        # The last periodic evaluation while running; the run's final coverage once it ended.
        if self._mission.running or self._mission.status == "error":
            return self._mission.area_m2
        return self._mission.result()["coverage"]["area_m2"]

    def _action(self, action):
        return _as_action(action)

    def _choose(self, request):
        # The grid method's goal check: the agent's pending action once, else keep the goal.
        self._goal_requests += 1
        if self._map_cells:
            self._map = _top_down(request, self._map_cells, self._map_cell_m, self._map_z_m)
        action, self._pending = self._pending, None
        return action

    def _observation(self, tick):
        pose = tick.est_pose
        obs = {"frame": self._frame, "pose": pose, "position": pose[:3, 3], "velocity": tick.est_velocity}
        if self._map_cells:
            obs["map"] = self._map if self._map is not None else np.zeros((self._map_cells,) * 2, np.uint8)
        return obs

    def _info(self, tick):
        return {
            "t_s": tick.t_s,
            "area_m2": self._area_now(),
            "status": self._mission.status,
            "points": tick.points,  # the newest SLAM points of the step (N×3), or None
            "track_ids": tick.track_ids,
            "goal_requests": self._goal_requests,
            "true_pose": tick.true_pose,  # ground truth: for analysis, not for the agent
        }


class ViewpointEnv(ExplorationEnv):
    """MonoSpheres' goal choice as a gym-style environment: the agent picks one of the viewpoints
    MonoSpheres found reachable (its frontiers' viewpoints, by path cost along the sphere graph)
    whenever MonoSpheres takes a new goal; everything else — map, paths, safety — is MonoSpheres'.
    reset(seed) -> (obs, info), step(action) -> (obs, reward, terminated, truncated, info)."""

    _METHOD = "monospheres"

    def __init__(self, scenario, set=(), decision_period_s=2.0, max_candidates=32):
        """scenario: a MonoSpheres scenario (path or msbench.Scenario); set, decision_period_s as
        for ExplorationEnv; max_candidates: the observation lists the first K candidates of the
        last goal choice (by path cost; MonoSpheres makes its viewpoints anew as the map grows,
        so a list is only valid at its own choice). The action is a rank a < K — at the next goal
        choice take the a-th cheapest reachable viewpoint, MonoSpheres' own choice if there are
        fewer — or K to leave the choice to MonoSpheres."""
        if int(max_candidates) != max_candidates or not 1 <= max_candidates <= 4096:
            raise ValueError("max_candidates must be an integer in [1, 4096]")
        self._k = int(max_candidates)
        super().__init__(scenario, set=set, decision_period_s=decision_period_s)
        self._candidates = np.zeros((self._k, 6))
        self._ids = []
        self.action_space = _spaces.make_discrete(self._k + 1)
        self.observation_space = _spaces.make_dict({
            **self.observation_space.spaces,
            "candidates": _spaces.make_box(-math.inf, math.inf, (self._k, 6), float),
            "mask": _spaces.make_box(0, 1, (self._k,), "uint8"),
        })

    def reset(self, seed=None, options=None):
        """Starts a new mission (the scenario's seed, or `seed`); returns (obs, info)."""
        self._candidates = np.zeros((self._k, 6))
        self._ids = []
        return super().reset(seed=seed, options=options)

    def _action(self, action):
        a = int(action)
        if a != action or not 0 <= a <= self._k:
            raise ValueError(f"an action is an index in [0, {self._k}] ({self._k}: MonoSpheres' own choice)")
        return None if a == self._k else a

    def _choose(self, request):
        # MonoSpheres takes a new goal: the viewpoint of the agent's pending rank if there is one,
        # else its own; then the candidates the agent sees next.
        self._goal_requests += 1
        rank, self._pending = self._pending, None
        ids = [int(i) for i in request.ids]
        n = min(len(ids), self._k)
        self._ids = ids[:n]
        self._candidates = np.zeros((self._k, 6))
        if n:
            self._candidates[:n, :3] = request.positions[:n]
            self._candidates[:n, 3] = request.yaws[:n]
            self._candidates[:n, 4] = request.path_costs[:n]
            self._candidates[:n, 5] = request.values[:n]
        return ids[rank] if rank is not None and rank < len(ids) else None

    def _observation(self, tick):
        obs = super()._observation(tick)
        obs["candidates"] = self._candidates.copy()
        obs["mask"] = (np.arange(self._k) < len(self._ids)).astype(np.uint8)
        return obs
