"""Observation and action spaces without gymnasium (docs/python.md, "Spaces").

`Box`, `Discrete` and `Dict` carry what an RL library reads from gymnasium's spaces — `shape`,
`dtype`, bounds (`low`, `high`, `n`), `sample()` from a seeded generator and `contains()` — so a
network can be sized and an action drawn on a machine without gymnasium (Debian 12 has none).
When gymnasium is importable, the environments use gymnasium's own spaces instead (`make_box`
and friends below choose).
"""
import numpy as np

try:  # gymnasium is optional
    import gymnasium as _gymnasium
except ImportError:  # pragma: no cover - depends on the machine
    _gymnasium = None


class Space:
    """Base of msbench's spaces: a shape, a dtype and a seeded generator for sample()."""

    def __init__(self, shape, dtype, seed=None):
        self.shape = None if shape is None else tuple(int(s) for s in shape)
        self.dtype = None if dtype is None else np.dtype(dtype)
        self._rng = np.random.default_rng(seed)

    def seed(self, seed=None):
        """Re-seeds the generator of sample(); returns [seed] as gymnasium does."""
        self._rng = np.random.default_rng(seed)
        return [seed]

    def __contains__(self, x):
        return self.contains(x)


class Box(Space):
    """An n-dimensional box [low, high] (gymnasium.spaces.Box's fields and behaviour)."""

    def __init__(self, low, high, shape=None, dtype=np.float64, seed=None):
        dtype = np.dtype(dtype)
        if shape is None:
            shape = np.broadcast(np.asarray(low), np.asarray(high)).shape
        super().__init__(shape, dtype, seed)
        self.low = np.broadcast_to(np.asarray(low, dtype=dtype), self.shape).copy()
        self.high = np.broadcast_to(np.asarray(high, dtype=dtype), self.shape).copy()
        if np.any(self.low > self.high):
            raise ValueError("Box: low must not exceed high")

    def sample(self):
        """A point of the box: uniform where bounded, normal / exponential where not."""
        if np.issubdtype(self.dtype, np.integer):
            lo, hi = np.floor(self.low), np.floor(self.high)
            return self._rng.integers(lo, hi, endpoint=True, size=self.shape).astype(self.dtype)
        lo, hi = self.low.astype(np.float64), self.high.astype(np.float64)
        out = np.empty(self.shape, dtype=np.float64)
        both, below, above = np.isfinite(lo) & np.isfinite(hi), np.isfinite(lo) & ~np.isfinite(hi), ~np.isfinite(lo) & np.isfinite(hi)
        none = ~np.isfinite(lo) & ~np.isfinite(hi)
        out[both] = self._rng.uniform(lo[both], hi[both])
        out[below] = lo[below] + self._rng.exponential(size=below.sum())
        out[above] = hi[above] - self._rng.exponential(size=above.sum())
        out[none] = self._rng.normal(size=none.sum())
        return out.astype(self.dtype)

    def contains(self, x):
        """True if x has the box's shape, a castable dtype and lies within the bounds."""
        x = np.asarray(x)
        if x.shape != self.shape or not np.can_cast(x.dtype, self.dtype, casting="same_kind"):
            return False
        return bool(np.all(x >= self.low) and np.all(x <= self.high))

    def __repr__(self):
        return f"Box({self.low.min()}, {self.high.max()}, {self.shape}, {self.dtype})"


class Discrete(Space):
    """The integers start, ..., start + n - 1 (gymnasium.spaces.Discrete)."""

    def __init__(self, n, seed=None, start=0):
        if int(n) <= 0:
            raise ValueError("Discrete: n must be positive")
        super().__init__((), np.int64, seed)
        self.n, self.start = int(n), int(start)

    def sample(self):
        """One of the n integers, uniformly."""
        return np.int64(self.start + self._rng.integers(self.n))

    def contains(self, x):
        """True if x is an integer in range."""
        if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, np.integer)):
            if not (isinstance(x, np.ndarray) and x.shape == () and np.issubdtype(x.dtype, np.integer)):
                return False
        return self.start <= int(x) < self.start + self.n

    def __repr__(self):
        return f"Discrete({self.n}, start={self.start})"


class Dict(Space):
    """Named sub-spaces (gymnasium.spaces.Dict); sample() and contains() work per key."""

    def __init__(self, spaces, seed=None):
        super().__init__(None, None, seed)
        self.spaces = dict(spaces)
        self.seed(seed)

    def seed(self, seed=None):
        """Seeds every sub-space from one generator (deterministic for a given seed)."""
        rng = np.random.default_rng(seed)
        for space in self.spaces.values():
            space.seed(int(rng.integers(2**63)) if seed is not None else None)
        return [seed]

    def sample(self):
        """A dict of one sample per sub-space."""
        return {k: s.sample() for k, s in self.spaces.items()}

    def contains(self, x):
        """True if x has exactly the keys and each value is in its space."""
        return isinstance(x, dict) and x.keys() == self.spaces.keys() and all(
            self.spaces[k].contains(v) for k, v in x.items())

    def __getitem__(self, key):
        return self.spaces[key]

    def keys(self):
        return self.spaces.keys()

    def __repr__(self):
        return "Dict(" + ", ".join(f"{k}: {v!r}" for k, v in self.spaces.items()) + ")"


def make_box(low, high, shape, dtype):
    """gymnasium's Box when gymnasium is importable, else msbench's."""
    if _gymnasium is not None:
        return _gymnasium.spaces.Box(low, high, shape=shape, dtype=dtype)
    return Box(low, high, shape=shape, dtype=dtype)


def make_discrete(n):
    """gymnasium's Discrete when importable, else msbench's."""
    return _gymnasium.spaces.Discrete(n) if _gymnasium is not None else Discrete(n)


def make_dict(spaces):
    """gymnasium's Dict when importable, else msbench's."""
    return _gymnasium.spaces.Dict(spaces) if _gymnasium is not None else Dict(spaces)
