// The Python module's shared parts (docs/python.md): conversions to NumPy and Python objects, the
// scenario and tick records, what a Python method and a goal chooser see, and the functions that
// bind each area (one file each: convert.cc, python_method.cc, goal_choosers.cc,
// mission_binding.cc; module.cc assembles them).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/messages.h"
#include "core/explorer/explorer.h"
#include "core/grid/grid_map.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/yaml_json.h"
#include "tools/engine/closed_loop.h"
#include "tools/engine/records.h"
#include "tools/engine/scenario_spec.h"
#include "tools/results/compute_log.h"

namespace py = pybind11;

namespace msb {
// Hidden from other shared objects, as pybind11's own types are (their fields are pybind11 types).
#pragma GCC visibility push(hidden)
namespace binding {

// ---- conversions ----------------------------------------------------------------------------

/// A YAML scalar as the Python value it reads as (bool, int, float, None or str).
/// A YAML text as nested Python dicts, lists and scalars (each scalar as yamlAsJson reads it,
/// tools/config/yaml_json.h).
py::object yamlToPython(const std::string& yaml_text);
/// A JSON value as the Python object json.loads makes of it.
py::object jsonToPython(const nlohmann::json& j);
/// A pose as a 4×4 array.
py::array_t<double> poseArray(const Pose& p);
/// A vector as a length-3 array.
py::array_t<double> vec3Array(const Vec3& v);

// Marks an array read-only.
template <class A>
A readOnly(A a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

/// A frame as a read-only H×W uint8 view that keeps the frame alive (no copy).
py::array frameView(std::shared_ptr<const CameraFrame> frame);

// ---- Scenario and TickRecord ----------------------------------------------------------------

/// A loaded, validated scenario (the CLI's loadScenario; its errors become msbench.ConfigError).
struct PyScenario {
  std::string file;
  std::vector<std::string> sets;
  ScenarioSpec spec;
  std::string effective_yaml;

  static PyScenario load(const std::string& path, const std::vector<std::string>& sets) {
    PyScenario s;
    s.file = path;
    s.sets = sets;
    s.spec = loadScenario(path, sets);
    loadComputeReplay(s.spec, path);
    s.effective_yaml = effectiveScenarioYaml(runOwnComputeLog(s.spec));
    return s;
  }
  py::object effective() const { return yamlToPython(effective_yaml); }
};

/// A path argument: str or os.PathLike, as a string.
std::string pathOf(const py::handle& path);

/// `set=` as KEY=VALUE strings: a list or tuple of such strings, or a dict {key: value} (True and
/// False as true/false, lists and dicts as JSON flow, the rest as str()). TypeError otherwise.
std::vector<std::string> setsOf(const py::handle& sets);

/// A scenario argument: a loaded Scenario, or a path loaded without overrides.
PyScenario scenarioOf(const py::handle& scenario);

/// What a step produced: the tick, the newest frame and SLAM points of the ticks stepped (None
/// when none was rendered in them), the vehicle's true and estimated state. Arrays read-only.
struct PyTick {
  int64_t tick = 0;
  double t_s = 0.0;
  bool running = true;
  py::object frame = py::none(), frame_pose = py::none(), frame_tick = py::none();
  py::object points = py::none(), point_covariances = py::none(), track_ids = py::none();
  py::object true_pose, est_pose, true_velocity, est_velocity;
};

/// The SLAM points of a frame into `t` as arrays.
void fillPoints(PyTick& t, const SlamPointsFrame& f);

// ---- Python methods -------------------------------------------------------------------------

/// A Python exception as text with its traceback (for the run's error record).
std::string pythonErrorText(py::error_already_set& e);

/// A method error: the Python method raised (its traceback, which names the call, is the message).
class MethodError : public MethodCallError {
 public:
  using MethodCallError::MethodCallError;
};

/// A method in its own process that stopped answering (`kMethodTimeout`) or whose process ended
/// (`kMethodExited`): the run ends with that status (msbench.MethodTimeout, msbench.MethodExited).
class MethodProcessError : public MethodError {
 public:
  MethodProcessError(RunStatus s, const std::string& what) : MethodError(what), status(s) {}
  RunStatus status;
};

/// An interrupt is never a method error: a KeyboardInterrupt raised inside a Python method's or
/// goal chooser's call (Ctrl-C, or the runner's SIGTERM/SIGHUP/SIGQUIT handlers) propagates as
/// it is, and the mission ends as interrupted (nothing recorded).
void rethrowIfInterrupt(py::error_already_set& e);

/// Charges the CPU time of a method's or goal chooser's own process (a msbench.confined proxy:
/// `msbench_process_id`) to `explorer` (timing.compute: charged); nothing for an in-process one.
void addOwnProcessClock(Explorer& explorer, const py::object& proxy);

/// The errors of a method's or goal chooser's own process (msbench.confined: MethodTimeout,
/// MethodExited, MethodProtocolError) as a MethodProcessError with the run's status.
void rethrowIfProcessError(py::error_already_set& e);

/// While it lives (the GIL held), a Python method's or goal chooser's call runs on this thread:
/// an interrupt the waiting loop thread sees is raised here too (interruptMethodCall).
struct MethodCallNote {
  MethodCallNote();
  ~MethodCallNote();
  MethodCallNote(const MethodCallNote&) = delete;
  MethodCallNote& operator=(const MethodCallNote&) = delete;
};

/// Raises KeyboardInterrupt in the method call running on another thread, if any (the GIL
/// held): a busy loop stops at its next bytecode; a call blocked in C stops when it returns.
void interruptMethodCall();

/// The SLAM-points frame a Python method observes (arrays read-only).
struct SlamFrameView {
  int64_t tick = 0;
  double t_s = 0.0;
  py::object pose, points, covariances, track_ids;
};

/// The vehicle a Python method plans for (estimate frame).
struct VehicleView {
  int64_t tick = 0;
  double t_s = 0.0;
  double yaw_rad = 0.0;
  bool path_finished = true;
  py::object pose, position, velocity;
};

/// What a Python method's factory receives: the box, the start, the seed, and named RNG streams
/// seeded like every C++ stream (scenario seed + name).
struct MethodContext {
  std::vector<double> box_min, box_max, start_position;
  double start_yaw_rad = 0.0;
  uint64_t seed = 1;
  py::object start_pose;
};

/// The Explorer over a Python method object (observe, plan, free_space, counters).
std::unique_ptr<Explorer> makePythonExplorer(py::object method);

// ---- Goal choosers --------------------------------------------------------------------------

/// What a goal chooser sees at a goal check: the time, the vehicle, whether the baseline would
/// need a new goal, and msbench's OctoMap (its leaves, computed when asked; valid during the call).
struct GoalRequestView {
  double t_s = 0.0;
  bool needs_goal = true;
  py::object position;
  const GridMap* map = nullptr;

  const GridMap& liveMap() const {
    if (!map) throw std::runtime_error("a GoalRequest's map is valid only during the goals() call");
    return *map;
  }
  // Leaves as an N×4 array: centre x, y, z and edge length.
  py::array_t<double> leafArray(bool occupied) const {
    const std::vector<GridLeaf> leaves = liveMap().leaves(occupied);
    py::array_t<double> a({py::ssize_t(leaves.size()), py::ssize_t(4)});
    auto m = a.mutable_unchecked<2>();
    for (size_t i = 0; i < leaves.size(); ++i) {
      for (int k = 0; k < 3; ++k) m(py::ssize_t(i), k) = leaves[i].centre[k];
      m(py::ssize_t(i), 3) = leaves[i].size_m;
    }
    return readOnly(a);
  }
};

/// What a viewpoint chooser sees when MonoSpheres takes a new goal: the time, the vehicle and the
/// reachable viewpoints by path cost (arrays, read-only).
struct ViewpointRequestView {
  double t_s = 0.0;
  py::object position, ids, positions, yaws, path_costs, values;
};

/// Gives the scenario's explorer its goals from `goals` (the goal-only helper), through the
/// method registration's goal-chooser hooks; throws py::value_error when the method takes none.
void attachGoalChooser(Explorer& explorer, const std::string& method_type, py::object goals,
                       const std::string& scenario_file);

// ---- the module's parts ---------------------------------------------------------------------

/// msbench.ConfigError (every configuration error of the CLI) and msbench.MethodError.
void bindErrors(py::module_& m);
/// Scenario and TickRecord.
void bindScenarioAndTicks(py::module_& m);
/// What a Python method and a goal chooser see: RngStream, Context, SlamFrame, Vehicle,
/// GoalRequest, ViewpointRequest.
void bindMethodTypes(py::module_& m);
/// Mission.
void bindMission(py::module_& m);

}  // namespace binding
#pragma GCC visibility pop
}  // namespace msb
