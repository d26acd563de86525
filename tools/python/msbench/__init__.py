"""msbench from Python (docs/python.md).

    import msbench
    s = msbench.Scenario.load("scenarios/missions/urban_short.yaml", set=["seed=2"])
    m = msbench.Mission(s)
    t = m.step(100)          # TickRecord: frame (H×W uint8 view), points (N×3), poses ...
    m.run()                  # to the end; Ctrl-C raises KeyboardInterrupt
    m.write("out/run1")      # the files `msbench run` writes, the same hash
    df = msbench.results.load_coverage("out/run1")

The loop and the configuration are the command line's own (the C++ extension `_msbench`); the
result loaders (`msbench.results`) are plain Python over the files every run writes.
"""
from ._msbench import (ConfigError, Context, GoalRequest, MethodError, MethodExited, MethodProtocolError, MethodTimeout, Mission, RngStream, Scenario, SlamFrame,
                       TickRecord, Vehicle, ViewpointRequest, __version__)
from . import gym, results, spaces, vector

__all__ = ["ConfigError", "Context", "GoalRequest", "MethodError", "MethodExited", "MethodProtocolError", "MethodTimeout", "Mission", "RngStream", "Scenario", "SlamFrame", "TickRecord",
           "Vehicle", "ViewpointRequest", "gym", "results", "__version__"]
