"""msbench.vector.VectorEnv: N environments in subprocesses, each deterministic by its seed (the
same hash as a single ExplorationEnv), autoreset with the next seed."""
import os

import numpy as np

import msbench
from conftest import FAST, SOURCE_DIR

GRID = os.path.join(SOURCE_DIR, "scenarios/missions/grid_random.yaml")
SETS = {"world": "urban", "duration_s": 6, **dict(s.split("=", 1) for s in FAST)}


def east(obs):
    return (float(obs["position"][0]) + 4.0, float(obs["position"][1]), 2.0)


def single_hash(seed):
    env = msbench.gym.ExplorationEnv(GRID, set=SETS, decision_period_s=2.0)
    obs, _ = env.reset(seed=seed)
    while True:
        obs, _, term, trunc, _ = env.step(east(obs))
        if term or trunc:
            return env.mission.hash


def test_a_vector_env_gives_each_env_the_single_envs_hash_and_autoresets():
    with msbench.vector.VectorEnv(GRID, n=2, set=SETS, decision_period_s=2.0) as venv:
        assert venv.num_envs == 2 and venv.single_action_space.shape == (3,)
        obs, infos = venv.reset(seed=5)
        assert len(obs) == 2 and obs[0]["frame"].shape == venv.single_observation_space["frame"].shape
        final = [None, None]
        for _ in range(10):
            obs, rewards, term, trunc, infos = venv.step([east(o) for o in obs])
            assert rewards.shape == (2,) and term.dtype == bool
            for i in range(2):
                if (term[i] or trunc[i]) and final[i] is None:
                    final[i] = infos[i]["final_hash"]
                    assert "final_observation" in infos[i]
            if all(final):
                break
    assert final == [single_hash(5), single_hash(6)]
