"""Python methods named by a scenario (method.type: python; docs/python.md).

    method:
      type: python
      entry: "hover_turn:factory"     # module:callable, imported with `path` first on sys.path
      path: ../examples/python        # relative to the scenario file
      params: {turn_step_deg: 30}     # the factory's keyword arguments (it validates them)
"""
import importlib
import os
import sys

from ._msbench import ConfigError


def factory_of(entry, path, params, scenario_file):
    """The factory(context) of a scenario's Python method, its params bound. Import failures and
    a missing callable raise ConfigError naming the key."""
    if path:
        full = path if os.path.isabs(path) else os.path.join(os.path.dirname(os.path.abspath(scenario_file)), path)
        if not os.path.isdir(full):
            raise ConfigError(f"{scenario_file}: key 'method.path': not a directory: {full}")
        if full not in sys.path:
            sys.path.insert(0, full)
    module_name, _, attr = entry.partition(":")
    try:
        module = importlib.import_module(module_name)
    except ImportError as e:
        raise ConfigError(f"{scenario_file}: key 'method.entry': cannot import '{module_name}': {e}") from e
    factory = getattr(module, attr, None)
    if not callable(factory):
        raise ConfigError(f"{scenario_file}: key 'method.entry': '{module_name}' has no callable '{attr}'")
    params = dict(params or {})

    def build(context):
        try:
            return factory(context, **params)
        except TypeError as e:
            raise ConfigError(f"{scenario_file}: key 'method.params': {e}") from e

    return build
