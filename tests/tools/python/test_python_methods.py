"""Methods written in Python: the C++/Python twin gives the same hash (in-process and through
`msbench run`), an exception ends the run with status error and its traceback, seeded streams."""
import json
import os
import subprocess
import sys

import pytest

import msbench
from conftest import FAST, MSBENCH_BIN, SOURCE_DIR

sys.path.insert(0, os.path.join(SOURCE_DIR, "examples/python"))
import hover_turn  # noqa: E402

CPP = os.path.join(SOURCE_DIR, "examples/hover_turn.yaml")
PY = os.path.join(SOURCE_DIR, "examples/hover_turn_python.yaml")


def test_the_python_twin_gives_the_cpp_methods_hash():
    s = msbench.Scenario.load(CPP, set=FAST)
    cpp = msbench.Mission(s)
    cpp.run(progress=False)
    twin = msbench.Mission(s, method=hover_turn.factory)
    twin.run(progress=False)
    assert twin.hash == cpp.hash
    assert twin.result()["coverage"]["area_m2"] > 0  # the sphere was scored


def test_msbench_run_runs_a_scenario_naming_a_python_method(tmp_path):
    sets = sum([["--set", s] for s in FAST], [])
    cpp = subprocess.run([MSBENCH_BIN, "run", CPP, "--quiet", "--out", str(tmp_path / "cpp")] + sets,
                         capture_output=True, text=True, check=True)
    py = subprocess.run([MSBENCH_BIN, "run", PY, "--quiet", "--out", str(tmp_path / "py")] + sets,
                        capture_output=True, text=True, check=True)
    h = cpp.stdout.split("hash ")[1].split()[0]
    assert f"hash {h}" in py.stdout
    metrics = json.loads((tmp_path / "py" / "metrics.json").read_text())
    assert metrics["method"] == "python" and metrics["determinism_hash"] == h
    bad = subprocess.run([MSBENCH_BIN, "run", PY, "--out", str(tmp_path / "bad"), "--set", "method.params.nope=1"],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "method.params" in bad.stderr and not (tmp_path / "bad").exists()


class Failing(hover_turn.HoverTurn):
    def plan(self, vehicle):
        if vehicle.t_s > 3.0:
            raise ZeroDivisionError("a bug in the method")
        return super().plan(vehicle)


def test_an_exception_in_a_python_method_ends_the_run_with_status_error(tmp_path):
    m = msbench.Mission(msbench.Scenario.load(CPP, set=FAST), method=lambda c: Failing(c))
    with pytest.raises(msbench.MethodError, match="ZeroDivisionError: a bug in the method"):
        m.run(progress=False)
    assert m.status == "error" and not m.running
    out = m.write(str(tmp_path / "run"))
    metrics = json.loads(open(os.path.join(out, "metrics.json")).read())
    assert metrics["status"] == "error"
    assert "in plan" in metrics["error"] and "ZeroDivisionError" in metrics["error"]  # the traceback
    assert 3.0 * 500 <= metrics["error_tick"] < 4.0 * 500
    # What it flew up to the error is written too (before: metrics.json and config.yaml only).
    names = set(os.listdir(out))
    assert {"trajectory.csv", "coverage.csv", "topdown.png", "config.yaml"} <= names, names
    rows = open(os.path.join(out, "trajectory.csv")).read().splitlines()
    assert float(rows[-1].split(",")[0]) == pytest.approx(metrics["sim_time_s"], abs=0.15) and metrics["sim_time_s"] > 3.0


PIPELINED = FAST + ["perception.latency_frames=1"]


def test_a_python_method_on_the_pipelined_loops_second_thread_runs_as_on_one():
    # The method's calls come from the loop's second thread (the GIL taken there): same run.
    one = msbench.Mission(msbench.Scenario.load(CPP, set=PIPELINED))
    one.run(progress=False)
    two = msbench.Mission(msbench.Scenario.load(CPP, set=PIPELINED + ["perception.threads=2"]),
                          method=hover_turn.factory)
    two.run(progress=False)
    assert two.hash == one.hash
    # Stepped tick by tick and dropped half-way with work in flight: no hang.
    m = msbench.Mission(msbench.Scenario.load(CPP, set=PIPELINED + ["perception.threads=2"]),
                        method=hover_turn.factory)
    for _ in range(40):
        m.step(7)
    del m
    # A method raising on the second thread ends the run with status error, as on one thread.
    m = msbench.Mission(msbench.Scenario.load(CPP, set=PIPELINED + ["perception.threads=2"]),
                        method=lambda c: Failing(c))
    with pytest.raises(msbench.MethodError, match="ZeroDivisionError: a bug in the method"):
        m.run(progress=False)
    assert m.status == "error" and not m.running


class WithPictures(hover_turn.HoverTurn):
    """hover_turn handing obstacles, frontiers, a goal and its path to the pictures."""

    def snapshot(self):
        return {"obstacles": [(3.0, 0.0, 1.0), (3.0, 1.0, 1.0)], "frontiers": [(5.0, 5.0, 1.5)],
                "viewpoints": [(5.0, 5.0, 1.5, 0.0)], "goal": (5.0, 5.0, 1.5, 0.0), "path": [(0, 0, 1), (5, 5, 1.5)]}


def test_a_python_methods_snapshot_reaches_map_ply_and_the_pictures(tmp_path):
    plain = msbench.Mission(msbench.Scenario.load(CPP, set=FAST), method=hover_turn.factory)
    plain.run(progress=False)
    drawn = msbench.Mission(msbench.Scenario.load(CPP, set=FAST), method=lambda c: WithPictures(c))
    drawn.run(progress=False)
    a, b = plain.write(str(tmp_path / "plain")), drawn.write(str(tmp_path / "drawn"))
    ply = open(os.path.join(b, "map.ply")).read()
    assert "\n3.0000 0.0000 1.0000 0 1\n" in ply and "\n5.0000 5.0000 1.5000 0 2\n" in ply
    assert open(os.path.join(a, "topdown.png"), "rb").read() != open(os.path.join(b, "topdown.png"), "rb").read()
    # A wrong answer is a method error naming the key.
    class Bad(hover_turn.HoverTurn):
        def snapshot(self):
            return {"obstacle": []}
    m = msbench.Mission(msbench.Scenario.load(CPP, set=FAST), method=lambda c: Bad(c))
    with pytest.raises(msbench.MethodError, match="unknown key 'obstacle'"):
        m.run(progress=False)


class Exits(hover_turn.HoverTurn):
    def plan(self, vehicle):
        if vehicle.t_s > 2.0:
            sys.exit(3)
        return super().plan(vehicle)


def test_sys_exit_inside_a_method_is_a_method_error_not_the_end_of_python():
    m = msbench.Mission(msbench.Scenario.load(CPP, set=FAST), method=lambda c: Exits(c))
    with pytest.raises(msbench.MethodError, match="SystemExit: 3"):
        m.run(progress=False)
    assert m.status == "error"


def test_method_rng_streams_are_seeded_like_msbenchs():
    a, b = msbench.RngStream(7, "goals"), msbench.RngStream(7, "goals")
    assert [a.uniform() for _ in range(5)] == [b.uniform() for _ in range(5)]
    assert msbench.RngStream(8, "goals").uniform() != msbench.RngStream(7, "goals").uniform()
    seen = []
    msbench.Mission(msbench.Scenario.load(CPP, set=FAST), method=lambda c: seen.append(c.rng("x").uniform()) or
                    hover_turn.HoverTurn(c))
    assert seen == [msbench.RngStream(1, "x").uniform()]


def test_a_piped_python_run_prints_the_command_lines_progress_and_summary(tmp_path):
    # Before: no progress when stderr was not a terminal, and a shorter summary than msbench run's.
    sets = sum([["--set", s] for s in FAST + ["duration_s=20"]], [])
    cpp = subprocess.run([MSBENCH_BIN, "run", CPP, "--out", str(tmp_path / "cpp")] + sets,
                         capture_output=True, text=True, check=True)
    py = subprocess.run([MSBENCH_BIN, "run", PY, "--out", str(tmp_path / "py")] + sets,
                        capture_output=True, text=True, check=True)
    assert "t = 10 / 20 s, RTF " in py.stderr and "ETA" in py.stderr
    shape = lambda line: line.split(" after ")[1].split("(")[0] + line.split("); ")[1].split(" m flown")[0]
    cpp_line = next(l for l in cpp.stdout.splitlines() if " after " in l)
    py_line = next(l for l in py.stdout.splitlines() if " after " in l)
    assert "s wall, RTF " in py_line and shape(py_line) == shape(cpp_line)
    # Each names its method beside the run (before: the scenario's name alone).
    assert cpp_line.startswith("run hover_turn (hover_turn): ") and py_line.startswith("run hover_turn_python (python): ")
