"""N exploration environments stepped together, one subprocess each (docs/python.md, "Vector
environments").

    venv = msbench.vector.VectorEnv("scenarios/missions/grid_random.yaml", n=2, set={"world": "urban"})
    obs, infos = venv.reset(seed=1)              # env i gets seed 1 + i
    actions = [(o["position"][0] + 5, o["position"][1], 2.0) for o in obs]
    obs, rewards, terminated, truncated, infos = venv.step(actions)
    venv.close()

Each environment is an `msbench.gym.ExplorationEnv` in its own process (fork-free `spawn`: one
MuJoCo, OSMesa and OpenCV per process, single-threaded as in every run), so N environments use N
cores. An environment that ends is reset automatically with its next seed (seed + i + k·n for its
k-th episode; the ending step's observation and info are `infos[i]["final_observation"]` and
`["final_info"]`), as gymnasium's vector environments do. Each environment is deterministic by its
seed: the hash of env i's episode equals that of a single ExplorationEnv reset with the same seed.
Observations come back as a list of dicts (one per env); rewards and flags as numpy arrays.
"""
import multiprocessing as _mp

import numpy as np


def _worker(conn, scenario, sets, decision_period_s):
    """One environment's process: answers ("reset", seed), ("step", action), ("hash",), ("close",)."""
    from .gym import ExplorationEnv  # imported in the child: its own extension instance
    env = ExplorationEnv(scenario, set=sets, decision_period_s=decision_period_s)
    conn.send(("ready", (env.action_space, env.observation_space)))
    while True:
        cmd, arg = conn.recv()
        try:
            if cmd == "reset":
                conn.send(("ok", env.reset(seed=arg)))
            elif cmd == "step":
                conn.send(("ok", env.step(arg)))
            elif cmd == "hash":
                conn.send(("ok", env.mission.hash))
            elif cmd == "close":
                conn.send(("ok", None))
                return
        except Exception as e:  # noqa: BLE001 - sent to the parent, which raises it
            conn.send(("error", e))


class VectorEnv:
    """n ExplorationEnvs in subprocesses, reset and stepped together (autoreset on episode end)."""

    def __init__(self, scenario, n=2, set=(), decision_period_s=2.0):
        """scenario and set as for ExplorationEnv (a path or Scenario; a dict or list); n >= 1."""
        from .gym import _scenario_source
        if int(n) < 1:
            raise ValueError("VectorEnv: n must be at least 1")
        self.num_envs = int(n)
        path, sets = _scenario_source(scenario, set)
        ctx = _mp.get_context("spawn")
        self._conns, self._procs = [], []
        for _ in range(self.num_envs):
            parent, child = ctx.Pipe()
            p = ctx.Process(target=_worker, args=(child, path, sets, decision_period_s), daemon=True)
            p.start()
            child.close()  # the parent keeps only its end: a dead worker then reads as EOF, not a hang
            self._conns.append(parent)
            self._procs.append(p)
        spaces = [self._receive(c) for c in self._conns]
        self.single_action_space, self.single_observation_space = spaces[0]
        self._seeds = [None] * self.num_envs
        self._episodes = [0] * self.num_envs

    def _receive(self, conn):
        try:
            kind, value = conn.recv()
        except EOFError:
            raise RuntimeError("VectorEnv: an environment's process ended unexpectedly (see its stderr; a script "
                               "using VectorEnv needs an `if __name__ == '__main__':` guard)") from None
        if kind == "error":
            raise value
        return value

    def _call(self, cmd, args):
        for conn, arg in zip(self._conns, args):
            conn.send((cmd, arg))
        return [self._receive(c) for c in self._conns]

    def _seed_of(self, i):
        base = self._seeds[i]
        return None if base is None else base + self._episodes[i] * self.num_envs

    def reset(self, seed=None):
        """Resets every env (env i with seed + i); returns (list of obs, list of info)."""
        self._seeds = [None if seed is None else int(seed) + i for i in range(self.num_envs)]
        self._episodes = [0] * self.num_envs
        out = self._call("reset", [self._seed_of(i) for i in range(self.num_envs)])
        return [o for o, _ in out], [info for _, info in out]

    def step(self, actions):
        """One action per env; returns (obs list, rewards, terminated, truncated, infos)."""
        if len(actions) != self.num_envs:
            raise ValueError(f"VectorEnv.step: {self.num_envs} actions expected, got {len(actions)}")
        out = self._call("step", list(actions))
        obs, infos = [], []
        rewards = np.array([r for _, r, _, _, _ in out], dtype=float)
        terminated = np.array([t for _, _, t, _, _ in out], dtype=bool)
        truncated = np.array([t for _, _, _, t, _ in out], dtype=bool)
        for i, (o, _, term, trunc, info) in enumerate(out):
            if term or trunc:  # autoreset: the next episode of this env, its next seed
                info = dict(info, final_observation=o, final_info=info, final_hash=self._hash(i))
                self._episodes[i] += 1
                self._conns[i].send(("reset", self._seed_of(i)))
                o, _ = self._receive(self._conns[i])
            obs.append(o)
            infos.append(info)
        return obs, rewards, terminated, truncated, infos

    def _hash(self, i):
        self._conns[i].send(("hash", None))
        return self._receive(self._conns[i])

    def close(self):
        """Stops the processes."""
        for conn, p in zip(self._conns, self._procs):
            if p.is_alive():
                try:
                    conn.send(("close", None))
                    conn.recv()
                except (EOFError, OSError, BrokenPipeError):
                    pass
            p.join(timeout=10)
            if p.is_alive():
                p.terminate()
        self._conns, self._procs = [], []

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
