"""Shared settings of the Python module's tests: the source tree, the msbench binary, and a fast
scenario (no GL: the blank renderer and the oracle front end) on a generated world."""
import os

import pytest

SOURCE_DIR = os.environ.get("MSB_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "../../..")))
MSBENCH_BIN = os.environ.get("MSBENCH_BIN", os.path.join(SOURCE_DIR, "build/bin/msbench"))
SCENARIO = os.path.join(SOURCE_DIR, "scenarios/missions/urban_short.yaml")
FAST = ["camera_stream.renderer=blank", "perception.source=oracle"]


def fast_sets(duration_s=6, seed=1):
    """--set overrides of a short, fast, GL-free mission."""
    return FAST + [f"duration_s={duration_s}", f"seed={seed}"]


@pytest.fixture
def fast_scenario():
    import msbench
    return msbench.Scenario.load(SCENARIO, set=fast_sets())
