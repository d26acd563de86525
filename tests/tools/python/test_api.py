"""One rule for the Python API (docs/python.md, "API"): facts are properties, actions methods;
paths or Scenarios wherever a scenario is taken; `set=` as a dict or a list."""
import pathlib

import pytest

import msbench
from conftest import SCENARIO, fast_sets


def test_facts_are_properties_and_format_in_f_strings(fast_scenario):
    m = msbench.Mission(fast_scenario)
    m.step(500)
    assert isinstance(m.area_m2, float) and isinstance(m.running, bool) and m.status == "running"
    m.run(progress=False)
    line = f"{m.status}: A = {m.area_m2:.0f} m², hash {m.hash}"  # failed when area_m2 was a method
    assert len(m.hash) == 16 and m.hash in line


def test_set_takes_a_dict_or_a_list_and_refuses_other_types():
    as_list = msbench.Scenario.load(SCENARIO, set=fast_sets(duration_s=3, seed=2))
    as_dict = msbench.Scenario.load(SCENARIO, set={"camera_stream.renderer": "blank",
                                                   "perception.source": "oracle", "duration_s": 3, "seed": 2})
    assert as_list.effective() == as_dict.effective()
    assert msbench.Scenario.load(SCENARIO, set={"method.switches.dbof": False}).effective()["method"]["switches"][
        "dbof"] is False
    with pytest.raises(TypeError, match="dict"):
        msbench.Scenario.load(SCENARIO, set="seed=2")
    with pytest.raises(TypeError, match="KEY=VALUE"):
        msbench.Scenario.load(SCENARIO, set=[("seed", 2)])


def test_a_mission_takes_a_path_or_a_scenario():
    a = msbench.Mission(pathlib.Path(SCENARIO))  # os.PathLike
    b = msbench.Mission(msbench.Scenario.load(SCENARIO))
    assert a.physics_hz == b.physics_hz
    assert msbench.Scenario.load(pathlib.Path(SCENARIO), set={"seed": 3}).sets == ["seed=3"]


def test_the_env_has_spaces_and_takes_a_scenario():
    grid = str(pathlib.Path(SCENARIO).with_name("grid_random.yaml"))
    env = msbench.gym.ExplorationEnv(msbench.Scenario.load(grid, set={"world": "urban"}), set={"duration_s": 4})
    assert env.action_space is not None and env.action_space.shape == (3,)
    assert env.observation_space["frame"].shape == env.frame_shape
    assert env.observation_space["frame"].contains(env.observation_space["frame"].sample())


def test_public_names_have_docstrings():
    for name in ("Mission", "Scenario", "TickRecord"):
        cls = getattr(msbench, name)
        assert cls.__doc__
        for attr in dir(cls):
            if not attr.startswith("_"):
                assert getattr(cls, attr).__doc__, f"{name}.{attr} has no docstring"
