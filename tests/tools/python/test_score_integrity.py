"""A score no method can inflate, and run records that name what flew: verified coverage against a
method that claims what it never saw, in-process factories and goal choosers in metrics.json and
config.yaml, interrupts inside a method's call, and out-of-range free space."""
import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

import msbench
from conftest import FAST, MSBENCH_BIN, SCENARIO, SOURCE_DIR, fast_sets

sys.path.insert(0, os.path.join(SOURCE_DIR, "examples/python"))
import hover_turn  # noqa: E402

HOVER = os.path.join(SOURCE_DIR, "examples/hover_turn.yaml")


class Claim:
    """Never takes off; claims one free-space disk of `radius` around its start."""

    radius = 60.0

    def __init__(self, context):
        self.p = context.start_position

    def observe(self, frame):
        pass

    def plan(self, vehicle):
        return None

    def free_space(self):
        return [(1, self.p[0], self.p[1], self.p[2], self.radius)]


def test_a_claimed_60_m_disk_earns_no_more_than_the_camera_saw_from_take_off():
    m = msbench.Mission(msbench.Scenario.load(SCENARIO, set=fast_sets(duration_s=5)), method=Claim)
    m.run(progress=False)
    cov = m.result()["coverage"]
    print(f"claimed A = {cov['area_m2']:.0f} m², seen from take-off = {cov['seen_area_m2']:.0f} m², "
          f"verified A = {cov['verified_area_m2']:.0f} m²")
    assert cov["area_m2"] > 10000  # the paper's metric takes the claim
    assert 0 < cov["verified_area_m2"] <= cov["seen_area_m2"]
    assert cov["verified_area_m2"] < 0.15 * cov["area_m2"]
    assert cov["verified_box_share"] < 0.2 < cov["box_share"]
    acc = m.result()["map_accuracy"]
    assert acc["falsely_free_volume_share"] > 0.4  # half of the ball is underground
    assert acc["falsely_free_element_share"] == 1.0


def test_a_claimed_60_m_disk_earns_less_than_nothing():
    # The earned score (docs/metrics.md): the disk buys the free space the camera crossed within
    # 10 m of take-off and pays for everything behind what it saw; declaring nothing earns 0.
    m = msbench.Mission(msbench.Scenario.load(SCENARIO, set=fast_sets(duration_s=5)), method=Claim)
    m.run(progress=False)
    score = m.result()["score"]
    print(score)
    assert score["unit"] == "m3"
    assert score["credited_m3"] > 0
    assert score["unseen_m3"] > score["credited_m3"]
    assert score["earned"] < 0


def test_the_verified_area_is_over_time_in_coverage_csv(tmp_path):
    m = msbench.Mission(msbench.Scenario.load(SCENARIO, set=fast_sets(duration_s=4)), method=Claim)
    m.run(progress=False)
    out = m.write(str(tmp_path / "run"))
    lines = open(os.path.join(out, "coverage.csv")).read().splitlines()
    assert lines[0].split(",")[-2:] == ["area_verified_m2", "score_earned_m3"]
    assert float(lines[-1].split(",")[-2]) == m.result()["coverage"]["verified_area_m2"]
    assert float(lines[-1].split(",")[-1]) == round(m.result()["score"]["before_forfeit"], 3)


def run_config(config_dir, tmp_path, name):
    return subprocess.run([MSBENCH_BIN, "run", os.path.join(config_dir, "config.yaml"), "--quiet", "--out",
                           str(tmp_path / name)], capture_output=True, text=True)


def test_an_importable_in_process_factory_is_recorded_and_its_config_replays_the_run(tmp_path):
    m = msbench.Mission(msbench.Scenario.load(HOVER, set=FAST), method=hover_turn.factory)
    m.run(progress=False)
    out = m.write(str(tmp_path / "run"))
    metrics = json.load(open(os.path.join(out, "metrics.json")))
    assert metrics["method"] == "python" and metrics["method_entry"] == "hover_turn:factory"
    assert metrics["replayable"] is True and metrics["switches"] == {}
    replay = run_config(out, tmp_path, "replay")
    assert replay.returncode == 0, replay.stderr
    assert f"hash {m.hash}" in replay.stdout


def test_a_lambda_factory_is_recorded_as_not_replayable(tmp_path):
    m = msbench.Mission(msbench.Scenario.load(HOVER, set=FAST), method=lambda c: hover_turn.factory(c))
    m.run(progress=False)
    out = m.write(str(tmp_path / "run"))
    metrics = json.load(open(os.path.join(out, "metrics.json")))
    assert metrics["method"] == "python" and metrics["replayable"] is False
    assert "<lambda>" in metrics["method_entry"]
    config = open(os.path.join(out, "config.yaml")).read()
    assert config.startswith("# NOT REPLAYABLE:") and "type: python" in config
    replay = run_config(out, tmp_path, "replay")
    assert replay.returncode == 2 and "method.entry" in replay.stderr and "not replayable" in replay.stderr
    assert not (tmp_path / "replay").exists()


def test_a_cpp_method_and_a_scenario_python_method_replay_from_their_config(tmp_path):
    for scenario in (HOVER, os.path.join(SOURCE_DIR, "examples/hover_turn_python.yaml")):
        m = msbench.Mission(msbench.Scenario.load(scenario, set=FAST))
        m.run(progress=False)
        out = m.write(str(tmp_path / os.path.basename(scenario)))
        assert json.load(open(os.path.join(out, "metrics.json")))["replayable"] is True
        replay = run_config(out, tmp_path, "replay_" + os.path.basename(scenario))
        assert replay.returncode == 0, replay.stderr
        assert f"hash {m.hash}" in replay.stdout


def test_a_goal_chooser_is_named_and_the_run_is_not_replayable(tmp_path):
    s = msbench.Scenario.load(os.path.join(SOURCE_DIR, "scenarios/missions/urban_grid.yaml"),
                              set=fast_sets(duration_s=4))
    m = msbench.Mission(s, goals=lambda request: None)
    m.run(progress=False)
    out = m.write(str(tmp_path / "run"))
    metrics = json.load(open(os.path.join(out, "metrics.json")))
    assert metrics["method"] == "grid_random" and "<lambda>" in metrics["goal_chooser"]
    assert metrics["replayable"] is False
    assert open(os.path.join(out, "config.yaml")).read().startswith("# NOT REPLAYABLE: the goals came from")


class SignalsItself(hover_turn.HoverTurn):
    """Sends `sig` to its own process once, inside plan() after 2 s (as one Ctrl-C would)."""

    sig = signal.SIGINT

    def plan(self, vehicle):
        if vehicle.t_s > 2.0 and not getattr(self, "_sent", False):
            self._sent = True
            os.kill(os.getpid(), self.sig)
        return super().plan(vehicle)


def test_ctrl_c_inside_a_method_call_is_an_interrupt_not_a_method_error(tmp_path):
    m = msbench.Mission(msbench.Scenario.load(HOVER, set=FAST), method=SignalsItself)
    with pytest.raises(KeyboardInterrupt):
        m.run(progress=False)
    assert m.status == "interrupted" and not m.running
    with pytest.raises(RuntimeError, match="interrupted"):
        m.write(str(tmp_path / "run"))
    assert not (tmp_path / "run").exists()


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT])
def test_a_signal_during_a_method_call_ends_msbench_run_as_interrupted(tmp_path, sig):
    # A scenario's method runs in its own process (it cannot signal msbench): the signal comes
    # from outside, as Ctrl-C or a scheduler's SIGTERM does, while msbench waits for plan().
    (tmp_path / "m").mkdir()
    (tmp_path / "m" / "slow.py").write_text(textwrap.dedent("""
        import time

        class Method:
            def __init__(self, context):
                pass
            def observe(self, frame):
                pass
            def plan(self, vehicle):
                if vehicle.t_s > 1.0:
                    time.sleep(3600)
            def free_space(self):
                return []
        """))
    (tmp_path / "s.yaml").write_text(f"base: {HOVER}\nmethod: {{type: python, entry: 'slow:Method', "
                                     f"path: {tmp_path / 'm'}, params: {{}}}}\n")
    sets = sum([["--set", s] for s in FAST], [])
    p = subprocess.Popen([MSBENCH_BIN, "run", str(tmp_path / "s.yaml"), "--quiet", "--out", str(tmp_path / "out")] +
                         sets, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(6)
    p.send_signal(sig)
    _, err = p.communicate(timeout=30)
    assert p.returncode == 128 + int(sig), err
    assert "interrupted; nothing written" in err and "Traceback" not in err
    assert not (tmp_path / "out").exists() and not (tmp_path / "out.partial").exists()


@pytest.mark.parametrize("element,why", [
    ((1, float("nan"), 0.0, 1.0, 2.0), "not a finite point"),
    ((1, 0.0, 0.0, 1.0, 1e9), "radius"),
    ((1, 0.0, 0.0, 1.0, -1.0), "radius"),
    ((1, 1e300, 0.0, 1.0, 1.0), "outside the exploration box"),
    ((1, 0.0, 0.0, 1.0, 1e5, "square"), "radius"),
])
def test_out_of_range_free_space_ends_the_run_with_an_error_naming_the_element(element, why):
    class Bad(Claim):
        def free_space(self):
            return [element]

    m = msbench.Mission(msbench.Scenario.load(SCENARIO, set=fast_sets(duration_s=3)), method=Bad)
    with pytest.raises(msbench.MethodError, match=why):
        m.run(progress=False)
    assert m.status == "error"


def test_nan_or_far_waypoints_end_the_run_with_an_error():
    for waypoint in [(float("nan"), 0.0, 2.0), (1e9, 0.0, 2.0)]:
        class Wild(Claim):
            def plan(self, vehicle, w=waypoint):
                return [w]

        m = msbench.Mission(msbench.Scenario.load(SCENARIO, set=fast_sets(duration_s=3)), method=Wild)
        with pytest.raises(msbench.MethodError, match="waypoint 0"):
            m.run(progress=False)
        assert m.status == "error"


def test_a_billion_free_space_elements_end_the_run_at_the_limit_without_exhausting_memory():
    class Flood(Claim):
        def free_space(self):
            return ((1, 0.0, 0.0, 1.0, 1.0) for _ in range(10**9))

    m = msbench.Mission(msbench.Scenario.load(SCENARIO, set=fast_sets(duration_s=2)), method=Flood)
    with pytest.raises(msbench.MethodError, match="more than 5000000 elements"):
        m.run(progress=False)
    assert m.status == "error"
