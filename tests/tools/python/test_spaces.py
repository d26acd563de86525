"""msbench's own spaces (msbench.spaces), used when gymnasium is not importable."""
import math

import numpy as np
import pytest

from msbench import spaces


def test_box_samples_within_bounds_with_its_dtype_and_seed():
    box = spaces.Box(0, 255, shape=(4, 5), dtype="uint8", seed=3)
    a = box.sample()
    assert a.shape == (4, 5) and a.dtype == np.uint8 and box.contains(a)
    assert np.array_equal(a, spaces.Box(0, 255, shape=(4, 5), dtype="uint8", seed=3).sample())
    unbounded = spaces.Box(-math.inf, math.inf, shape=(3,), dtype=float, seed=1)
    x = unbounded.sample()
    assert x.dtype == np.float64 and np.all(np.isfinite(x)) and x in unbounded
    half = spaces.Box(np.array([0.0, -math.inf]), np.array([math.inf, 1.0]), seed=2)
    for _ in range(50):
        s = half.sample()
        assert s[0] >= 0.0 and s[1] <= 1.0


def test_box_contains_checks_shape_dtype_and_bounds():
    box = spaces.Box(-1.0, 1.0, shape=(2,))
    assert box.contains(np.array([0.5, -0.5]))
    assert not box.contains(np.array([1.5, 0.0]))
    assert not box.contains(np.array([0.0, 0.0, 0.0]))
    assert not spaces.Box(0, 10, shape=(2,), dtype="uint8").contains(np.array([1.5, 2.0]))
    with pytest.raises(ValueError):
        spaces.Box(1.0, 0.0, shape=(1,))


def test_discrete_and_dict():
    d = spaces.Discrete(5, seed=0)
    draws = {int(d.sample()) for _ in range(200)}
    assert draws == set(range(5))
    assert d.contains(4) and not d.contains(5) and not d.contains(1.0) and not d.contains(True)
    obs = spaces.Dict({"a": spaces.Box(0, 1, shape=(2,)), "b": spaces.Discrete(3)}, seed=7)
    x = obs.sample()
    assert obs.contains(x) and set(x) == {"a", "b"}
    again = spaces.Dict({"a": spaces.Box(0, 1, shape=(2,)), "b": spaces.Discrete(3)}, seed=7).sample()
    assert np.array_equal(x["a"], again["a"]) and x["b"] == again["b"]
    assert not obs.contains({"a": x["a"]})
