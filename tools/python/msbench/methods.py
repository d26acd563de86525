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


def _import_entry(entry, path, scenario_file, key):
    """The callable `entry` ("module:name") names, `path` first on sys.path; ConfigError naming
    `key`.entry or `key`.path otherwise."""
    if path:
        full = path if os.path.isabs(path) else os.path.join(os.path.dirname(os.path.abspath(scenario_file)), path)
        if not os.path.isdir(full):
            raise ConfigError(f"{scenario_file}: key '{key}.path': not a directory: {full}")
        if full not in sys.path:
            sys.path.insert(0, full)
    check_importable(entry, scenario_file, key)
    module_name, _, attr = entry.partition(":")
    try:
        module = importlib.import_module(module_name)
    except ImportError as e:
        raise ConfigError(f"{scenario_file}: key '{key}.entry': cannot import '{module_name}': {e}") from e
    found = getattr(module, attr, None)
    if not callable(found):
        raise ConfigError(f"{scenario_file}: key '{key}.entry': '{module_name}' has no callable '{attr}'")
    return found


def source_file(obj):
    """The file a function, class, instance or module was defined in, or None (built-ins, code
    typed at a prompt): an input that msbench's outputs may not overlap."""
    import inspect
    for candidate in (obj, type(obj)):
        try:
            return os.path.abspath(inspect.getsourcefile(candidate) or inspect.getfile(candidate))
        except (TypeError, OSError):
            continue
    return None


def chooser_of(entry, path, params, scenario_file):
    """The goal chooser a scenario's `goals` section names, in its own confined process
    (msbench.confined): `entry` itself, or — with `params` — what `entry(**params)` returns (a
    factory of choosers), imported there and nowhere else. ConfigError naming the key."""
    from . import confined
    full = method_dir(path, scenario_file, "goals")
    check_importable(entry, scenario_file, "goals")
    return confined.chooser(entry, full, dict(params or {}), 60.0, scenario_file)


def factory_of(entry, path, params, scenario_file, call_budget_s=60.0, memory_limit_mib=4096):
    """The factory(context) of a scenario's Python method, its params bound: the method runs in
    its own confined process (msbench.confined), imported there and nowhere else. A bad path or
    entry raises ConfigError naming the key."""
    from . import confined
    full = method_dir(path, scenario_file, "method")
    check_importable(entry, scenario_file, "method")
    return confined.factory(entry, full, dict(params or {}), call_budget_s, scenario_file, memory_limit_mib)


def method_dir(path, scenario_file, key):
    """A scenario's `key`.path as an absolute, real directory ("" when not given)."""
    if not path:
        return ""
    full = path if os.path.isabs(path) else os.path.join(os.path.dirname(os.path.abspath(scenario_file)), path)
    if not os.path.isdir(full):
        raise ConfigError(f"{scenario_file}: key '{key}.path': not a directory: {full}")
    return os.path.realpath(full)


def module_file(entry, path):
    """The file of the module `entry` names, found without importing it (nothing of the method
    runs in msbench's process), or None."""
    from importlib.machinery import PathFinder
    search = [path] if path else None
    spec = None
    for part in entry.partition(":")[0].split("."):
        spec = PathFinder.find_spec(part, search)
        if spec is None:
            return None
        search = list(spec.submodule_search_locations or [])
    return os.path.abspath(spec.origin) if spec and spec.origin else None


def record_of(factory):
    """How a run records an in-process factory or goal chooser: (entry, path, why_not_replayable).
    `entry` is "module:qualname"; `path` the directory that makes the module importable; the
    reason is "" when importing `entry` from `path` gives back this very object (a scenario can
    then name it, and config.yaml replays the run), else why it cannot (a lambda, a closure, a
    bound parameter, a script run as __main__)."""
    module_name = getattr(factory, "__module__", None) or "?"
    qualname = getattr(factory, "__qualname__", None) or type(factory).__qualname__
    entry = f"{module_name}:{qualname}"
    if module_name == "__main__":
        return entry, "", f"the method is the in-process factory {entry}, defined in a script run as __main__"
    if "<" in qualname or "." in qualname:
        return entry, "", f"the method is the in-process factory {entry}, which has no importable name"
    module = sys.modules.get(module_name)
    if module is None or getattr(module, qualname, None) is not factory:
        return entry, "", f"the method is the in-process object {entry}, not a module-level factory"
    file = getattr(module, "__file__", None)
    if not file:
        return entry, "", f"the method's module {module_name} has no file"
    # The directory that makes `module_name` importable: up one level per package part.
    root = os.path.dirname(os.path.abspath(file))
    parts = module_name.split(".")
    if os.path.basename(file) == "__init__.py":
        root = os.path.dirname(root)
    for _ in parts[:-1]:
        root = os.path.dirname(root)
    return entry, root, ""


def check_importable(entry, scenario_file, key="method"):
    """A scenario's entry that names an in-process factory (recorded, not importable) is refused."""
    module_name, _, attr = entry.partition(":")
    if module_name == "__main__" or "<" in attr:
        raise ConfigError(f"{scenario_file}: key '{key}.entry': '{entry}' names an in-process factory that "
                          "cannot be imported: the run it records was not replayable (its config.yaml says so)")
