"""A goal chooser named in a scenario (`goals: {entry, path, params}`): it runs through
`msbench run`, sweeps and resumes, its config.yaml replays the run, and it is the same run as the
in-process `Mission(..., goals=chooser)`."""
import json
import os
import subprocess
import textwrap

import pytest

import msbench
from conftest import FAST, MSBENCH_BIN, SOURCE_DIR

GRID = os.path.join(SOURCE_DIR, "scenarios/missions/grid_random.yaml")
CHOOSER = textwrap.dedent('''
    def eastward(step_m):
        """A chooser factory: goals step_m east of the vehicle whenever one is needed."""
        def choose(request):
            if not request.needs_goal:
                return None
            x, y, z = request.position.tolist()
            return (x + step_m, y, 2.0)
        return choose
''')


def write_scenario(tmp_path):
    (tmp_path / "choosers").mkdir()
    (tmp_path / "choosers" / "east_goals.py").write_text(CHOOSER)
    scenario = tmp_path / "east.yaml"
    scenario.write_text(f"base: {GRID}\nworld: urban\nduration_s: 12\n"
                        "goals: {entry: 'east_goals:eastward', path: choosers, params: {step_m: 6.0}}\n")
    return scenario


def test_a_scenario_named_chooser_sweeps_resumes_and_replays(tmp_path):
    scenario = write_scenario(tmp_path)
    sweep = tmp_path / "sweep.yaml"
    sets = ", ".join(f"{k}: {v}" for k, v in (s.split("=", 1) for s in FAST))
    sweep.write_text(f"scenario: {scenario}\nset: {{{sets}}}\nseeds: [1, 2]\n")
    out = tmp_path / "out"
    first = subprocess.run([MSBENCH_BIN, "sweep", str(sweep), "--out", str(out)], capture_output=True, text=True)
    assert first.returncode == 0, first.stderr
    again = subprocess.run([MSBENCH_BIN, "sweep", str(sweep), "--out", str(out)], capture_output=True, text=True)
    assert "2 complete, 0 to run" in again.stderr, again.stderr
    run = out / "runs" / "s1"
    metrics = json.loads((run / "metrics.json").read_text())
    assert metrics["goal_chooser"] == "east_goals:eastward" and metrics["replayable"] is True
    assert metrics["counters"]["goals_chosen"] >= 1
    replay = subprocess.run([MSBENCH_BIN, "run", str(run / "config.yaml"), "--out", str(tmp_path / "replay")],
                            capture_output=True, text=True)
    assert replay.returncode == 0, replay.stderr
    assert f"hash {metrics['determinism_hash']}" in replay.stdout
    # The same run as the in-process chooser on the grid scenario.
    import sys
    sys.path.insert(0, str(tmp_path / "choosers"))
    import east_goals
    m = msbench.Mission(msbench.Scenario.load(GRID, set={"world": "urban", "duration_s": 12, "seed": 1,
                                                         **dict(s.split("=", 1) for s in FAST)}),
                        goals=east_goals.eastward(6.0))
    m.run(progress=False)
    assert m.hash == metrics["determinism_hash"]


def test_a_bad_goals_section_is_a_configuration_error(tmp_path):
    scenario = write_scenario(tmp_path)
    text = scenario.read_text()
    bad = tmp_path / "bad.yaml"
    bad.write_text(text.replace("east_goals:eastward", "east_goals:nowhere"))
    r = subprocess.run([MSBENCH_BIN, "run", str(bad), "--out", str(tmp_path / "r")], capture_output=True, text=True)
    assert r.returncode == 2 and "goals.entry" in r.stderr and not (tmp_path / "r").exists(), r.stderr
    # Methods whose explorer has no chooser hook refuse one (the method says so, not a list of names).
    base = os.path.join(SOURCE_DIR, "scenarios/missions/base.yaml")
    goals = "goals: {entry: 'east_goals:eastward', path: choosers, params: {step_m: 6.0}}\n"
    for method in ["{type: python, entry: 'x:y'}", "{type: hover_turn}", "{type: star_discovery}"]:
        bad.write_text(f"base: {base}\nworld: urban\nduration_s: 12\nmethod: {method}\n" + goals)
        r = subprocess.run([MSBENCH_BIN, "run", str(bad), "--out", str(tmp_path / "r")], capture_output=True, text=True)
        assert r.returncode == 2 and "takes no goal chooser" in r.stderr, (method, r.stderr)
        assert not (tmp_path / "r").exists()


def test_an_importable_in_process_chooser_is_recorded_as_a_goals_section_and_replays(tmp_path):
    # A module-level chooser (no params) imports back to itself: config.yaml names it in `goals`.
    (tmp_path / "mods").mkdir()
    (tmp_path / "mods" / "north_goals.py").write_text(textwrap.dedent('''
        def north(request):
            if not request.needs_goal:
                return None
            x, y, z = request.position.tolist()
            return (x, y + 5.0, 2.0)
    '''))
    import sys
    sys.path.insert(0, str(tmp_path / "mods"))
    import north_goals
    m = msbench.Mission(msbench.Scenario.load(GRID, set=["world=urban", "duration_s=10"] + FAST),
                        goals=north_goals.north)
    m.run(progress=False)
    out = m.write(str(tmp_path / "run"))
    metrics = json.load(open(os.path.join(out, "metrics.json")))
    assert metrics["goal_chooser"] == "north_goals:north" and metrics["replayable"] is True
    config = open(os.path.join(out, "config.yaml")).read()
    assert "NOT REPLAYABLE" not in config and "north_goals:north" in config
    replay = subprocess.run([MSBENCH_BIN, "run", os.path.join(out, "config.yaml"), "--quiet", "--out",
                             str(tmp_path / "replay")], capture_output=True, text=True)
    assert replay.returncode == 0, replay.stderr
    assert f"hash {m.hash}" in replay.stdout



@pytest.mark.parametrize("threads", [[], ["perception.latency_frames=0", "perception.threads=1"]])
@pytest.mark.parametrize("call", ["step", "result", "write"])
def test_a_chooser_that_calls_its_own_mission_back_is_refused_not_hung(tmp_path, call, threads):
    # Before: the chooser's mission.step(1) deadlocked the run (no output after 120 s). Under the
    # mission defaults (the chooser on the pipelined loop's second thread) and on one thread.
    scenario = msbench.Scenario.load(os.path.join(SOURCE_DIR, "scenarios/missions/grid_random.yaml"),
                                     set=FAST + ["world=urban", "duration_s=20"] + threads)
    holder = {}

    def chooser(request):
        m = holder["mission"]
        m.step(1) if call == "step" else m.result() if call == "result" else m.write(str(tmp_path / "w"))
        return None

    mission = msbench.Mission(scenario, goals=chooser)
    holder["mission"] = mission
    with pytest.raises(msbench.MethodError, match="called while the mission is stepping"):
        mission.run(progress=False)
    assert mission.status == "error" and not (tmp_path / "w").exists()
