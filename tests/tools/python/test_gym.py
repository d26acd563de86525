"""The goal-only helper (goals chosen in Python on msbench's OctoMap, or among MonoSpheres'
viewpoints) and the gym-style adapter over it: what the chooser sees and may answer, errors,
determinism, reward = coverage gained."""
import os

import numpy as np
import pytest

import msbench
from conftest import FAST, SOURCE_DIR

GRID = os.path.join(SOURCE_DIR, "scenarios/missions/grid_random.yaml")
MONOSPHERES = os.path.join(SOURCE_DIR, "scenarios/missions/urban_short.yaml")


def grid_scenario(duration_s=12, seed=1):
    return msbench.Scenario.load(GRID, set=FAST + ["world=urban", f"duration_s={duration_s}", f"seed={seed}"])


def ahead(request):
    """A chooser: 6 m ahead in x whenever a goal is needed."""
    if not request.needs_goal:
        return None
    x, y, _ = request.position.tolist()
    return (x + 6.0, y, 2.0)


def test_the_chooser_sees_the_vehicle_and_the_octomap_and_its_goals_are_flown():
    seen = []

    def chooser(request):
        free, occupied = request.free(), request.occupied()
        seen.append((request.t_s, request.needs_goal, free.shape, occupied.shape, free.flags.writeable))
        return ahead(request)

    m = msbench.Mission(grid_scenario(), goals=chooser)
    m.run(progress=False)
    assert seen, "the chooser was never asked"
    assert seen[0][1] is True  # the first check needs a goal
    assert all(f[1] == 4 and o[1] == 4 and not w for _, _, f, o, w in seen)
    assert seen[-1][2][0] > 0  # the map has free leaves by then
    times = [t for t, *_ in seen]
    assert all(b - a == pytest.approx(1.0, abs=0.01) for a, b in zip(times, times[1:]))  # every goal period
    counters = m.result()["counters"]
    assert counters["goals_chosen"] >= 1 and counters["paths_sent"] >= 2  # take-off, then A* to the goal
    assert m.result()["coverage"]["area_m2"] > 0


def test_the_same_choices_give_the_same_hash_and_a_path_is_flown_as_given():
    hashes = []
    for _ in range(2):
        m = msbench.Mission(grid_scenario(), goals=ahead)
        m.run(progress=False)
        hashes.append(m.hash)
    assert hashes[0] == hashes[1]

    def path(request):
        if not request.needs_goal:
            return None
        x, y, _ = request.position.tolist()
        return [(x + 1.0, y, 2.0), (x + 2.0, y + 1.0, 2.0)]

    m = msbench.Mission(grid_scenario(), goals=path)
    m.run(progress=False)
    assert m.hash != hashes[0]
    assert m.result()["counters"]["paths_to_closest_cell"] == 0  # no A* was needed for a given path


def test_the_map_is_valid_only_during_the_call_and_errors_end_the_run():
    kept = []

    def keeper(request):
        kept.append(request)
        return None

    m = msbench.Mission(grid_scenario(duration_s=10), goals=keeper)
    m.run(progress=False)
    with pytest.raises(RuntimeError, match="only during"):
        kept[0].free()

    def bad(request):
        raise ValueError("no goal today")

    m = msbench.Mission(grid_scenario(), goals=bad)
    with pytest.raises(msbench.MethodError, match="no goal today"):
        m.run(progress=False)
    assert m.status == "error"

    m = msbench.Mission(grid_scenario(), goals=lambda r: (1.0, 2.0))  # not a point
    with pytest.raises(msbench.MethodError, match="must return None"):
        m.run(progress=False)


def test_goals_need_a_method_with_a_goal_rule():
    hover_turn = os.path.join(SOURCE_DIR, "examples/hover_turn.yaml")
    with pytest.raises(ValueError, match=r"takes a goal chooser \(monospheres, grid_random; got .hover_turn.\)"):
        msbench.Mission(msbench.Scenario.load(hover_turn, set=FAST), goals=ahead)
    with pytest.raises(ValueError, match="not both"):
        msbench.Mission(grid_scenario(), method=lambda c: None, goals=ahead)


def run_episode(env, seed):
    obs, info = env.reset(seed=seed)
    rewards, steps = [], 0
    while True:
        x, y, _ = obs["position"].tolist()
        obs, reward, terminated, truncated, info = env.step((x + 4.0, y + (3.0 if steps % 2 else -3.0), 2.0))
        rewards.append(reward)
        steps += 1
        if terminated or truncated:
            return obs, rewards, terminated, truncated, info


def test_the_gym_adapter_steps_a_mission_and_rewards_coverage_gained():
    env = msbench.gym.ExplorationEnv(GRID, set=FAST + ["world=urban", "duration_s=12"], decision_period_s=2.0)
    with pytest.raises(RuntimeError, match="reset"):
        env.step((0.0, 0.0, 2.0))
    obs, info = env.reset(seed=1)
    assert obs["frame"].shape == env.frame_shape and not obs["frame"].flags.writeable
    assert obs["pose"].shape == (4, 4) and obs["position"].shape == (3,)
    with pytest.raises(ValueError):
        env.step([(1.0, 2.0)])
    obs, rewards, terminated, truncated, info = run_episode(env, seed=1)
    assert truncated and not terminated and info["status"] == "completed"
    assert len(rewards) == 6  # 12 s in steps of 2 s
    assert all(r >= 0 for r in rewards)
    assert sum(rewards) == pytest.approx(env.mission.result()["coverage"]["area_m2"])
    first = env.mission.hash
    run_episode(env, seed=1)
    assert env.mission.hash == first  # reset(seed) really seeds
    run_episode(env, seed=2)
    assert env.mission.hash != first
    with pytest.raises(RuntimeError, match="ended"):
        env.step((0.0, 0.0, 2.0))


def test_the_observation_can_carry_a_top_down_map_of_the_octomap():
    env = msbench.gym.ExplorationEnv(GRID, set=FAST + ["world=urban", "duration_s=14"], decision_period_s=2.0,
                                     map_cells=40, map_cell_m=1.0)
    assert env.observation_space["map"].shape == (40, 40)
    obs, _ = env.reset(seed=1)
    assert obs["map"].shape == (40, 40) and obs["map"].dtype == np.uint8
    assert not obs["map"].any()  # no goal check yet: all unknown
    for _ in range(6):  # the first goal check comes after the take-off
        obs, *_ = env.step((float(obs["position"][0]) + 3.0, float(obs["position"][1]), 2.0))
    assert env.observation_space.contains(obs)
    values = set(np.unique(obs["map"]).tolist())
    assert values == {0, 1, 2}  # free space and obstacles seen at flight height, the rest unknown
    with pytest.raises(ValueError, match="map_cells"):
        msbench.gym.ExplorationEnv(GRID, map_cells=-1)


def test_the_gym_adapter_is_a_gymnasium_env_when_gymnasium_is_there():
    try:
        import gymnasium
    except ImportError:
        assert msbench.gym.ExplorationEnv.__bases__ == (object,)
    else:
        assert issubclass(msbench.gym.ExplorationEnv, gymnasium.Env)
    with pytest.raises(ValueError, match="grid_random"):
        msbench.gym.ExplorationEnv(MONOSPHERES)
    with pytest.raises(msbench.ConfigError):
        msbench.gym.ExplorationEnv(GRID, set=["world=urban", "no_such_key=1"])


def test_an_empty_answer_means_no_goal_and_the_vehicle_hovers():
    m = msbench.Mission(grid_scenario(), goals=lambda request: [])
    m.run(progress=False)
    counters = m.result()["counters"]
    assert counters["goals_chosen"] == 0
    assert counters["paths_sent"] == 2  # the take-off's two legs only: no goal, nothing else flown


def spheres_scenario(duration_s=14, seed=1):
    return msbench.Scenario.load(MONOSPHERES, set=FAST + [f"duration_s={duration_s}", f"seed={seed}"])


def test_a_viewpoint_chooser_picks_monospheres_goals_among_the_reachable_viewpoints():
    own = msbench.Mission(spheres_scenario())
    own.run(progress=False)
    # Always None: MonoSpheres' own choice, the same run.
    asked = []

    def watch(request):
        asked.append((request.ids.tolist(), request.path_costs.tolist(), request.positions.shape))
        return None

    m = msbench.Mission(spheres_scenario(), goals=watch)
    m.run(progress=False)
    assert m.hash == own.hash
    assert asked and any(ids for ids, _, _ in asked)
    for ids, costs, shape in asked:
        assert shape == (len(ids), 3) and costs == sorted(costs)
    # The farthest reachable viewpoint each time: another run, every goal a candidate.
    m = msbench.Mission(spheres_scenario(), goals=lambda r: int(r.ids[-1]) if len(r.ids) else None)
    m.run(progress=False)
    assert m.hash != own.hash and m.result()["counters"]["goals_chosen"] >= 1
    # 0: no goal at all.
    m = msbench.Mission(spheres_scenario(), goals=lambda r: 0)
    m.run(progress=False)
    assert m.result()["counters"]["goals_chosen"] == 0
    # Not a candidate: the run ends with an error.
    m = msbench.Mission(spheres_scenario(), goals=lambda r: 987654321 if len(r.ids) else None)
    with pytest.raises(msbench.MethodError, match="not a candidate"):
        m.run(progress=False)
    assert m.status == "error"


def test_the_viewpoint_env_lets_an_agent_pick_monospheres_goals():
    sets = FAST + ["duration_s=30", "seed=1"]
    env = msbench.gym.ViewpointEnv(MONOSPHERES, set=sets, decision_period_s=1.0, max_candidates=8)
    assert env.action_space.n == 9 and env.observation_space["candidates"].shape == (8, 6)
    own = msbench.Mission(msbench.Scenario.load(MONOSPHERES, set=sets))
    own.run(progress=False)
    # Always 8 (= K): MonoSpheres' own choice, the same run.
    obs, _ = env.reset(seed=1)
    seen = 0
    while env.mission.running:
        obs, *_ = env.step(8)
        seen = max(seen, int(obs["mask"].sum()))
        assert env.observation_space.contains(obs)
    assert env.mission.hash == own.hash and seen >= 1
    # The farthest listed rank whenever there is a list: another run, goals from the candidates.
    obs, _ = env.reset(seed=1)
    while env.mission.running:
        n = int(obs["mask"].sum())
        obs, *_ = env.step(n - 1 if n else 8)
    assert env.mission.hash != own.hash and env.mission.result()["counters"]["goals_chosen"] >= 3
    with pytest.raises(ValueError, match="index"):
        env.reset(seed=1) and env.step(9)
    with pytest.raises(ValueError, match="monospheres"):
        msbench.gym.ViewpointEnv(GRID, set=["world=urban"])

