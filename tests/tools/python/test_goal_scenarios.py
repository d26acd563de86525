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


def run_fast(scenario, out, extra=()):
    """`msbench run` of a scenario on the fast front end; its metrics.json (the run must succeed)."""
    r = subprocess.run([MSBENCH_BIN, "run", str(scenario), "--quiet", "--out", str(out)] + list(extra) +
                       sum([["--set", s] for s in FAST], []), capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return json.loads((out / "metrics.json").read_text())


def test_a_scenario_named_chooser_runs_confined_and_cannot_forge_its_record(tmp_path):
    # Before: a `goals` chooser ran in msbench's process, read the truth, rewrote metrics.json at
    # exit and re-sealed it (earned 25 000, ranked first). Now it runs in its own confined
    # process: the truth and msbench's outputs are out of its reach, and the record says so.
    (tmp_path / "choosers").mkdir()
    forged = tmp_path / "out" / "metrics.json"
    (tmp_path / "choosers" / "forger.py").write_text(textwrap.dedent(f'''
        import os
        def choose(request):
            for truth in ("{SOURCE_DIR}/worlds/urban/spec.yaml", "{SOURCE_DIR}/worlds/urban"):
                try:
                    os.listdir(truth) if os.path.isdir(truth) else open(truth).read()
                    raise RuntimeError("read the truth at " + truth)
                except PermissionError:
                    pass
            try:
                os.makedirs("{forged.parent}", exist_ok=True)
                open("{forged}", "w").write("{{}}")
                raise RuntimeError("wrote the record")
            except PermissionError:
                pass
            return None
    '''))
    scenario = tmp_path / "forge.yaml"
    scenario.write_text(f"base: {GRID}\nworld: urban\nduration_s: 6\ngoals: {{entry: 'forger:choose', path: choosers}}\n")
    out = tmp_path / "out"
    metrics = run_fast(scenario, out)
    assert metrics["status"] == "completed", metrics.get("error")
    assert metrics["method_confinement"].startswith("goal chooser: own process, Landlock"), metrics["method_confinement"]
    assert metrics["counters"]["goals_chosen"] == 0  # it was asked, and kept the grid's own goals


def test_a_grid_chooser_in_its_own_process_reads_the_map_during_its_call_only(tmp_path):
    (tmp_path / "choosers").mkdir()
    (tmp_path / "choosers" / "mapper.py").write_text(textwrap.dedent('''
        kept = []
        def choose(request):
            free, occupied = request.free(), request.occupied()
            assert free.shape[1] == 4 and occupied.shape[1] == 4 and not free.flags.writeable
            if kept:
                try:
                    kept[0].free()
                    raise AssertionError("an old request's map answered")
                except RuntimeError as e:
                    assert "only during the goals() call" in str(e)
            kept[:] = [request]
            if not request.needs_goal:
                return None
            x, y, z = request.position.tolist()
            return (x + 6.0, y, 2.0)
    '''))
    scenario = tmp_path / "mapper.yaml"
    scenario.write_text(f"base: {GRID}\nworld: urban\nduration_s: 12\ngoals: {{entry: 'mapper:choose', path: choosers}}\n")
    out = tmp_path / "out"
    metrics = run_fast(scenario, out)
    assert metrics["status"] == "completed", metrics.get("error")
    assert metrics["counters"]["goals_chosen"] >= 1


def test_a_viewpoint_chooser_in_its_own_process_flies_the_in_process_run(tmp_path):
    (tmp_path / "ch").mkdir()
    (tmp_path / "ch" / "far.py").write_text("def farthest(request):\n"
                                            "    return int(request.ids[-1]) if len(request.ids) else None\n")
    urban = os.path.join(SOURCE_DIR, "scenarios/missions/urban_short.yaml")
    scenario = tmp_path / "far.yaml"
    scenario.write_text(f"base: {urban}\nduration_s: 20\ngoals: {{entry: 'far:farthest', path: ch}}\n")
    out = tmp_path / "out"
    metrics = run_fast(scenario, out)
    assert metrics["method_confinement"].startswith("goal chooser: own process"), metrics["method_confinement"]
    assert metrics["counters"]["goals_chosen"] >= 1
    import sys
    sys.path.insert(0, str(tmp_path / "ch"))
    import far
    m = msbench.Mission(msbench.Scenario.load(urban, set=FAST + ["duration_s=20"]), goals=far.farthest)
    m.run(progress=False)
    assert m.hash == metrics["determinism_hash"]


def test_a_chooser_in_its_own_process_is_charged_its_cpu_time(tmp_path):
    # timing.compute: charged counts the thread that calls the method; a chooser thinks in its own
    # process, which was free before: 100 ms of its CPU per goal check is now a planning latency.
    (tmp_path / "ch").mkdir()
    (tmp_path / "ch" / "slow.py").write_text(textwrap.dedent('''
        import time
        def slow(request):
            t = time.process_time()
            while time.process_time() - t < 0.1:
                pass
            return None
    '''))
    scenario = tmp_path / "slow.yaml"
    scenario.write_text(f"base: {GRID}\nworld: urban\nduration_s: 14\ngoals: {{entry: 'slow:slow', path: ch}}\n")
    out = tmp_path / "out"
    run_fast(scenario, out, ["--set", "timing.compute=charged"])
    rows = [line.split(",") for line in (out / "compute_latency.csv").read_text().splitlines()[2:]]
    plan_ns = [int(row[4]) for row in rows if len(row) == 6 and row[1] == "plan"]
    assert max(plan_ns) >= 90_000_000, max(plan_ns)
