// The Python module `msbench._msbench` (docs/python.md): the loop library and the configuration
// layer the command line uses, bound with pybind11 — no second loop, no second configuration
// path. Scenario.load is loadScenario; Mission is the tools/loop Mission; write() writes the files
// `msbench run` writes (tools/results). The GIL is released while C++ steps the loop; Ctrl-C is
// checked between simulated seconds.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "core/baseline/grid_explorer.h"
#include "core/common/config_check.h"
#include "core/common/rng.h"
#include "core/explorer/explorer.h"
#include "core/geometry/world_truth.h"
#include "core/planning/monospheres_explorer.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/world_registry.h"
#include "tools/loop/mission.h"
#include "tools/results/mission_outputs.h"
#include "tools/results/output_files.h"
#include "tools/results/provenance.h"

namespace py = pybind11;

namespace msb {
namespace {

// ---- conversions ----------------------------------------------------------------------------

// A YAML scalar as the Python value it reads as: null, bool, int, float, else str.
py::object scalarToPython(const YAML::Node& n) {
  const std::string& s = n.Scalar();
  if (n.Tag() == "!") return py::str(s);  // quoted: a string whatever it looks like
  if (s == "~" || s == "null" || s.empty()) return py::none();
  if (s == "true") return py::bool_(true);
  if (s == "false") return py::bool_(false);
  size_t used = 0;
  try {
    const long long i = std::stoll(s, &used);
    if (used == s.size()) return py::int_(i);
  } catch (const std::exception&) {
  }
  try {
    const double d = std::stod(s, &used);
    if (used == s.size()) return py::float_(d);
  } catch (const std::exception&) {
  }
  return py::str(s);
}

// A YAML tree as nested dicts and lists.
py::object yamlToPython(const YAML::Node& n) {
  if (n.IsMap()) {
    py::dict d;
    for (const auto& kv : n) d[py::str(kv.first.Scalar())] = yamlToPython(kv.second);
    return d;
  }
  if (n.IsSequence()) {
    py::list l;
    for (const auto& e : n) l.append(yamlToPython(e));
    return l;
  }
  if (n.IsScalar()) return scalarToPython(n);
  return py::none();
}

// A JSON value as the Python value the json module would give.
py::object jsonToPython(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

// A pose as a 4×4 row-major array (a copy).
py::array_t<double> poseArray(const Pose& p) {
  py::array_t<double> a({4, 4});
  auto m = a.mutable_unchecked<2>();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = p.matrix()(r, c);
  return a;
}

py::array_t<double> vec3Array(const Vec3& v) {
  py::array_t<double> a(3);
  for (int i = 0; i < 3; ++i) a.mutable_at(i) = v[i];
  return a;
}

// Marks an array read-only.
template <class A>
A readOnly(A a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

// The frame as a read-only H×W uint8 view, no copy: a capsule owning a reference to the frame
// is the array's base, so the view stays valid after the loop moves on (the loop renders the
// next frame into a new buffer while this one is held) and frees it with the last view.
py::array frameView(std::shared_ptr<const CameraFrame> frame) {
  auto* owner = new std::shared_ptr<const CameraFrame>(std::move(frame));
  py::capsule base(owner, [](void* p) { delete static_cast<std::shared_ptr<const CameraFrame>*>(p); });
  const CameraFrame& f = **owner;
  return readOnly(py::array_t<uint8_t>({f.height, f.width}, {f.width, 1}, f.pixels.data(), base));
}

// ---- Scenario -------------------------------------------------------------------------------

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
    s.effective_yaml = effectiveScenarioYaml(s.spec);
    return s;
  }
  py::object effective() const { return yamlToPython(YAML::Load(effective_yaml)); }
};

// ---- TickRecord -----------------------------------------------------------------------------

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

// The SLAM points of a frame as arrays (copies: a point is a struct, not a row).
void fillPoints(PyTick& t, const SlamPointsFrame& f) {
  const py::ssize_t n = py::ssize_t(f.points.size());
  py::array_t<double> p({n, py::ssize_t(3)}), c({n, py::ssize_t(3), py::ssize_t(3)});
  py::array_t<uint64_t> ids(n);
  auto pm = p.mutable_unchecked<2>();
  auto cm = c.mutable_unchecked<3>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const SlamPoint& s = f.points[size_t(i)];
    ids.mutable_at(i) = s.track_id;
    for (int a = 0; a < 3; ++a) {
      pm(i, a) = s.p_W[a];
      for (int b = 0; b < 3; ++b) cm(i, a, b) = s.cov_W(a, b);
    }
  }
  t.points = readOnly(p);
  t.point_covariances = readOnly(c);
  t.track_ids = readOnly(ids);
}

// ---- Python methods -------------------------------------------------------------------------

/// A Python exception as text with its traceback (for the run's error record).
std::string pythonErrorText(py::error_already_set& e) {
  try {
    py::list lines = py::module_::import("traceback").attr("format_exception")(e.type(), e.value(), e.trace());
    std::string text;
    for (const auto& l : lines) text += py::str(l).cast<std::string>();
    return text;
  } catch (const std::exception&) {
    return e.what();
  }
}

/// A method error: the Python method raised (its traceback is the message).
class MethodError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An interrupt is never a method error: a KeyboardInterrupt raised inside a Python method's or
/// goal chooser's call (Ctrl-C, or the runner's SIGTERM/SIGHUP/SIGQUIT handlers) propagates as
/// it is, and the mission ends as interrupted (nothing recorded).
void rethrowIfInterrupt(py::error_already_set& e) {
  if (e.matches(PyExc_KeyboardInterrupt)) throw;
}

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

// A waypoint from Python: (x, y, z) or (x, y, z, heading_rad); heading None = face travel.
Waypoint waypointFrom(const py::handle& h) {
  const py::sequence seq = py::reinterpret_borrow<py::sequence>(h);
  if (seq.size() != 3 && seq.size() != 4) throw std::runtime_error("a waypoint is (x, y, z) or (x, y, z, heading_rad)");
  Waypoint w;
  w.position_m = Vec3(seq[0].cast<double>(), seq[1].cast<double>(), seq[2].cast<double>());
  if (seq.size() == 4 && !seq[3].is_none()) w.heading_rad = seq[3].cast<double>();
  return w;
}

/// The Explorer interface over a Python object with observe(frame), plan(vehicle) -> None or a
/// list of waypoints, free_space() -> [(id, x, y, z, radius[, "disk" | "square"])], counters() ->
/// {name: number}. Each call holds the GIL; a Python exception becomes a MethodError.
class PyExplorer final : public Explorer {
 public:
  explicit PyExplorer(py::object method) : method_(std::move(method)) {}
  ~PyExplorer() override {
    py::gil_scoped_acquire gil;
    method_ = py::object();
  }

  void observe(const SlamPointsFrame& f) override {
    call([&] {
      SlamFrameView frame;
      frame.tick = f.tick;
      frame.t_s = f.t_s;
      frame.pose = readOnly(poseArray(f.T_W_C));
      PyTick t;
      fillPoints(t, f);
      frame.points = t.points;
      frame.covariances = t.point_covariances;
      frame.track_ids = t.track_ids;
      method_.attr("observe")(frame);
    });
  }

  std::optional<PathCommand> plan(const VehicleState& v) override {
    std::optional<PathCommand> out;
    call([&] {
      VehicleView vehicle;
      vehicle.tick = v.tick;
      vehicle.t_s = v.t_s;
      vehicle.yaw_rad = yawOf(v.T_W_B.linear());
      vehicle.path_finished = v.path_finished;
      vehicle.pose = readOnly(poseArray(v.T_W_B));
      vehicle.position = readOnly(vec3Array(v.T_W_B.translation()));
      vehicle.velocity = readOnly(vec3Array(v.velocity_mps));
      const py::object path = method_.attr("plan")(vehicle);
      if (path.is_none()) return;
      PathCommand c;
      c.tick = v.tick;
      for (const auto& w : path) c.waypoints.push_back(waypointFrom(w));
      if (c.waypoints.empty())
        throw std::runtime_error("plan() returned an empty path (return None to keep the current one)");
      out = std::move(c);
    });
    return out;
  }

  ExplorerSnapshot snapshot() const override {
    ExplorerSnapshot snap;
    call([&] {
      for (const auto& e : method_.attr("free_space")()) {
        if (snap.free_space.size() == kMaxFreeSpaceElements)
          throw MethodOutputError("free_space() returned more than " + std::to_string(kMaxFreeSpaceElements) +
                                  " elements (the limit, docs/metrics.md)");
        const py::sequence q = py::reinterpret_borrow<py::sequence>(e);
        if (q.size() != 5 && q.size() != 6)
          throw std::runtime_error("a free-space element is (id, x, y, z, radius[, kind])");
        FreeSpaceElement el;
        el.id = q[0].cast<uint64_t>();
        el.centre = Vec3(q[1].cast<double>(), q[2].cast<double>(), q[3].cast<double>());
        el.radius = q[4].cast<double>();
        if (q.size() == 6) {
          const std::string kind = q[5].cast<std::string>();
          if (kind != "disk" && kind != "square") throw std::runtime_error("a free-space kind is 'disk' or 'square'");
          el.footprint = kind == "disk" ? FreeSpaceElement::Footprint::kDisk : FreeSpaceElement::Footprint::kSquare;
        }
        snap.free_space.push_back(el);
      }
    });
    return snap;
  }

  std::map<std::string, double> counters() const override {
    std::map<std::string, double> c;
    call([&] {
      if (!py::hasattr(method_, "counters")) return;
      for (const auto& kv : method_.attr("counters")().cast<py::dict>())
        c[kv.first.cast<std::string>()] = kv.second.cast<double>();
    });
    return c;
  }

 private:
  // Runs `f` with the GIL held; a Python exception becomes a MethodError with its traceback.
  template <class F>
  void call(F&& f) const {
    py::gil_scoped_acquire gil;
    try {
      f();
    } catch (py::error_already_set& e) {
      rethrowIfInterrupt(e);
      throw MethodError("the Python method raised:\n" + pythonErrorText(e));
    } catch (const py::cast_error& e) {
      throw MethodError(std::string("the Python method returned a value of the wrong type: ") + e.what());
    }
  }

  py::object method_;
};

// ---- The goal-only helper -------------------------------------------------------------------

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

// A chooser's answer: None (keep), one point (x, y, z), or a list of points (a path; empty: hover).
std::optional<std::vector<Vec3>> goalChoiceFrom(const py::object& r) {
  if (r.is_none()) return std::nullopt;
  const py::object list = py::module_::import("builtins").attr("list");
  const py::list items = list(r);
  auto isScalar = [](const py::handle& h) { return !py::hasattr(h, "__len__"); };
  auto point = [&](const py::list& q) {
    if (q.size() != 3 || !isScalar(q[0]) || !isScalar(q[1]) || !isScalar(q[2]))
      throw std::runtime_error("goals() must return None, (x, y, z) or a list of (x, y, z)");
    return Vec3(q[0].cast<double>(), q[1].cast<double>(), q[2].cast<double>());
  };
  if (items.size() == 3 && isScalar(items[0])) return std::vector<Vec3>{point(items)};
  std::vector<Vec3> out;
  for (const auto& e : items) {
    if (isScalar(e)) throw std::runtime_error("goals() must return None, (x, y, z) or a list of (x, y, z)");
    out.push_back(point(list(e)));
  }
  return out;
}

/// What a viewpoint chooser sees when MonoSpheres takes a new goal: the time, the vehicle and the
/// reachable viewpoints by path cost (arrays, read-only).
struct ViewpointRequestView {
  double t_s = 0.0;
  py::object position, ids, positions, yaws, path_costs, values;
};

ViewpointRequestView viewpointRequestView(const ViewpointRequest& q) {
  const py::ssize_t n = py::ssize_t(q.candidates.size());
  py::array_t<uint64_t> ids(n);
  py::array_t<double> pos({n, py::ssize_t(3)}), yaw(n), cost(n);
  py::array_t<int64_t> value(n);
  auto pm = pos.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const ViewpointCandidate& c = q.candidates[size_t(i)];
    ids.mutable_at(i) = c.id;
    for (int k = 0; k < 3; ++k) pm(i, k) = c.position[k];
    yaw.mutable_at(i) = c.yaw_rad;
    cost.mutable_at(i) = c.path_cost_m;
    value.mutable_at(i) = c.value;
  }
  ViewpointRequestView v;
  v.t_s = q.t_s;
  v.position = readOnly(vec3Array(q.position));
  v.ids = readOnly(ids);
  v.positions = readOnly(pos);
  v.yaws = readOnly(yaw);
  v.path_costs = readOnly(cost);
  v.values = readOnly(value);
  return v;
}

// Runs a goal chooser's call `f` with the GIL held; a Python exception, a wrong type or an answer
// `f` refuses (runtime_error) becomes a MethodError.
template <class F>
auto callChooser(F&& f) -> decltype(f()) {
  py::gil_scoped_acquire gil;
  try {
    return f();
  } catch (py::error_already_set& e) {
    rethrowIfInterrupt(e);
    throw MethodError("the Python goal chooser raised:\n" + pythonErrorText(e));
  } catch (const py::cast_error& e) {
    throw MethodError(std::string("the Python goal chooser returned a value of the wrong type: ") + e.what());
  } catch (const std::runtime_error& e) {
    throw MethodError(std::string("the Python goal chooser: ") + e.what());
  }
}

/// Sets a Python viewpoint chooser on a MonoSpheres explorer: goals(request) -> None (MonoSpheres'
/// own choice), 0 (no goal this step) or a candidate's id; an exception becomes a MethodError.
void setPythonViewpointChooser(MonoSpheresExplorer& explorer, py::object goals) {
  auto fn = std::make_shared<py::object>(std::move(goals));
  explorer.setViewpointChooser([fn](const ViewpointRequest& q) {
    return callChooser([&]() -> std::optional<uint64_t> {
      const py::object r = (*fn)(viewpointRequestView(q));
      if (r.is_none()) return std::nullopt;
      if (!py::hasattr(r, "__index__")) throw std::runtime_error("goals() must return None or a viewpoint id");
      const uint64_t id = r.cast<uint64_t>();
      if (id != 0 && std::none_of(q.candidates.begin(), q.candidates.end(),
                                  [&](const ViewpointCandidate& c) { return c.id == id; }))
        throw std::runtime_error("goals() chose viewpoint " + std::to_string(id) + ", not a candidate");
      return id;
    });
  });
}

/// Sets a Python goal chooser on a grid explorer: goals(request) is called at every goal check
/// with the GIL held; an exception becomes a MethodError.
void setPythonGoalChooser(GridExplorer& explorer, py::object goals) {
  const GridExplorer* ex = &explorer;
  auto fn = std::make_shared<py::object>(std::move(goals));
  explorer.setGoalChooser([ex, fn](const GoalRequest& q) {
    return callChooser([&]() -> std::optional<std::vector<Vec3>> {
      GoalRequestView v;
      v.t_s = q.t_s;
      v.needs_goal = q.needs_goal;
      v.position = readOnly(vec3Array(q.position));
      v.map = &ex->map();
      py::object view = py::cast(v);
      // The map is the explorer's: the view forgets it when the call returns or raises.
      struct Forget {
        py::object& view;
        ~Forget() { view.cast<GoalRequestView&>().map = nullptr; }
      } forget{view};
      return goalChoiceFrom((*fn)(view));
    });
  });
}

// ---- Mission --------------------------------------------------------------------------------

/// A mission of a scenario, stepped from Python.
class PyMission {
 public:
  // `method`: None (the scenario's method) or a factory called with a Context, returning an
  // object with the Python method protocol.
  PyMission(const PyScenario& s, py::object method, py::object goals)
      : scenario_(s), world_(std::make_unique<MissionWorld>()) {
    *world_ = prepareMissionWorld(scenario_.file, scenario_.spec);
    const WorldTruth* truth = world_->truth ? &*world_->truth : nullptr;
    if (!goals.is_none()) {
      buildWithGoalChooser(std::move(method), std::move(goals), truth);
      return;
    }
    // A scenario naming a Python method (method.type: python): its factory, from msbench.methods.
    const bool from_scenario = method.is_none();
    if (method.is_none() && scenario_.spec.method.type == kPythonMethodType) {
      const auto& c = std::any_cast<const PythonMethodConfig&>(scenario_.spec.method.config);
      method = py::module_::import("msbench.methods")
                   .attr("factory_of")(c.entry, c.path, yamlToPython(YAML::Load(c.params_yaml)), scenario_.file);
    }
    if (method.is_none()) {
      mission_ = buildNamingFile(scenario_.file,
                                 [&] { return std::make_unique<Mission>(scenario_.spec, world_->box, truth); });
      return;
    }
    if (!from_scenario) recordInProcess(s, method, /*goal_chooser=*/false);
    const ExplorerContext ctx = explorerContext(scenario_.spec, world_->box);
    MethodContext pc;
    pc.box_min = {ctx.exploration_box.min.x(), ctx.exploration_box.min.y(), ctx.exploration_box.min.z()};
    pc.box_max = {ctx.exploration_box.max.x(), ctx.exploration_box.max.y(), ctx.exploration_box.max.z()};
    pc.start_position = {ctx.start.translation().x(), ctx.start.translation().y(), ctx.start.translation().z()};
    pc.start_yaw_rad = yawOf(ctx.start.linear());
    pc.seed = ctx.seed;
    pc.start_pose = readOnly(poseArray(ctx.start));
    auto explorer = std::make_unique<PyExplorer>(method(pc));
    mission_ = buildNamingFile(scenario_.file, [&] {
      return std::make_unique<Mission>(scenario_.spec, world_->box, truth, std::move(explorer));
    });
  }

  bool running() const { return !error_ && !interrupted_ && mission_->running(); }

  /// Physics ticks per simulated second.
  int64_t physicsHz() const { return mission_->physicsHz(); }

  /// The coverage area so far (m², the metric's last evaluation).
  double areaM2() const { return mission_->areaM2(); }

  // Steps up to n ticks (fewer if the run ends), the GIL released.
  PyTick step(int64_t n) {
    if (n < 1) throw py::value_error("step(n): n must be >= 1");
    std::optional<SlamPointsFrame> points;
    bool new_frame = false;
    guarded([&] {
      py::gil_scoped_release release;
      for (int64_t i = 0; i < n && mission_->running(); ++i) {
        const TickRecord& r = mission_->step();
        last_tick_ = r.tick;
        last_t_s_ = r.t_s;
        if (r.frame) new_frame = true;
        if (r.points) points = *r.points;
      }
    });
    return record(new_frame, points);
  }

  // Runs to the end, checking for Ctrl-C between simulated seconds; a progress line on a terminal.
  void run(bool progress) {
    const bool tty = progress && isatty(STDERR_FILENO);
    const int64_t chunk = mission_->physicsHz();
    int64_t next_progress = 10 * chunk;
    while (running()) {
      guarded([&] {
        py::gil_scoped_release release;
        for (int64_t i = 0; i < chunk && mission_->running(); ++i) last_tick_ = mission_->step().tick;
      });
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // KeyboardInterrupt
      if (tty && last_tick_ >= next_progress) {
        next_progress += 10 * chunk;
        std::fprintf(stderr, "\rmsbench %s: t = %.0f / %.0f s, A = %.0f m²   ", scenario_.spec.name.c_str(),
                     double(last_tick_) / double(chunk), scenario_.spec.flight.duration_s, mission_->areaM2());
      }
    }
    if (tty) std::fprintf(stderr, "\n");
  }

  // The metrics (metrics.json's content); finishes the mission on first call.
  py::object result() { return jsonToPython(metrics()); }

  std::string hash() { return hexHash(finished().run_hash); }

  // Writes the files `msbench run` writes into `dir` (staged: whole or not at all); after a
  // method error, config.yaml and the error record.
  std::string write(const std::string& dir, bool overwrite) {
    if (interrupted_) throw std::runtime_error("the mission was interrupted: nothing to write");
    StagedOutputDir out(dir, overwrite);
    writeFileAtomic(out.staging() / "config.yaml",
                    configYamlText(scenario_.file, !scenario_.sets.empty(), scenario_.effective_yaml,
                                   scenario_.spec.method.not_replayable));
    if (error_) {
      nlohmann::json j = errorMetrics(scenario_.spec, *error_);
      j["error_tick"] = last_tick_;
      writeFileAtomic(out.staging() / "metrics.json", j.dump(2) + "\n");
    } else {
      writeMissionOutputs(out.staging(), scenario_.spec, finished(), world_->truth ? &*world_->truth : nullptr);
    }
    out.commit();
    return out.finalDir().string();
  }

  // The run's status word: running, error, or the loop's (completed, collided, ...).
  std::string status() {
    if (interrupted_) return "interrupted";
    if (error_) return runStatusName(RunStatus::kError);
    if (mission_->running()) return "running";
    return runStatusName(finished().flight.status);
  }

 private:
  // Runs `f`; a method error (or any failure of the loop) ends the run with status error.
  template <class F>
  void guarded(F&& f) {
    if (interrupted_) throw std::runtime_error("the mission was interrupted: it cannot go on or be written");
    if (error_) throw std::runtime_error("the mission ended with an error: " + *error_);
    try {
      f();
    } catch (py::error_already_set& e) {
      // Only a KeyboardInterrupt reaches here as a Python error (method errors are MethodError).
      interrupted_ = true;
      throw;
    } catch (const std::exception& e) {
      error_ = e.what();
      throw;
    }
  }

  // The scenario's grid explorer with its goals from `goals` (the goal-only helper).
  void buildWithGoalChooser(py::object method, py::object goals, const WorldTruth* truth) {
    if (!method.is_none()) throw py::value_error("Mission: give a method or goals, not both");
    recordInProcess(scenario_, goals, /*goal_chooser=*/true);
    std::unique_ptr<Explorer> explorer = scenario_.spec.method.make(FisheyeCamera(scenario_.spec.flight.camera),
                                                                    explorerContext(scenario_.spec, world_->box));
    if (auto* grid = dynamic_cast<GridExplorer*>(explorer.get()))
      setPythonGoalChooser(*grid, std::move(goals));
    else if (auto* spheres = dynamic_cast<MonoSpheresExplorer*>(explorer.get()))
      setPythonViewpointChooser(*spheres, std::move(goals));
    else
      throw py::value_error(scenario_.file +
                            ": goals= needs a scenario whose method.type is grid_random or "
                            "monospheres (got '" +
                            scenario_.spec.method.type + "')");
    mission_ = buildNamingFile(scenario_.file, [&] {
      return std::make_unique<Mission>(scenario_.spec, world_->box, truth, std::move(explorer));
    });
  }

  // Records what flies instead of the scenario's method: an in-process factory becomes a Python
  // method named by its module and name (config.yaml replays it when that name imports back to
  // it); a goal chooser is named beside the scenario's method, and such a run is never
  // replayable (a scenario cannot name a chooser). The effective YAML is rebuilt from the
  // scenario as loaded (`original`: before the world filled in the start).
  void recordInProcess(const PyScenario& original, const py::object& obj, bool goal_chooser) {
    const py::tuple rec = py::module_::import("msbench.methods").attr("record_of")(obj);
    const std::string entry = rec[0].cast<std::string>(), why = rec[2].cast<std::string>();
    ScenarioSpec spec = original.spec;
    if (goal_chooser) {
      spec.method.goal_chooser = entry;
      spec.method.not_replayable = "the goals came from the in-process goal chooser " + entry;
    } else {
      PythonMethodConfig c;
      c.entry = entry;
      c.path = rec[1].cast<std::string>();
      spec.method.type = kPythonMethodType;
      spec.method.config = c;
      spec.method.switches.clear();
      spec.method.not_replayable = why;
    }
    scenario_.effective_yaml = effectiveScenarioYaml(spec);
    scenario_.spec.method.type = spec.method.type;
    scenario_.spec.method.config = spec.method.config;
    scenario_.spec.method.switches = spec.method.switches;
    scenario_.spec.method.not_replayable = spec.method.not_replayable;
    scenario_.spec.method.goal_chooser = spec.method.goal_chooser;
  }

  const MissionResult& finished() {
    if (error_) throw std::runtime_error("the mission ended with an error (write() records it): " + *error_);
    if (!result_) {
      if (mission_->running())
        throw std::runtime_error("the mission is still running: step() or run() it to its end first");
      result_ = mission_->finish();
    }
    return *result_;
  }

  nlohmann::json metrics() {
    const MissionResult& r = finished();
    return missionMetrics(scenario_.spec, r, world_->truth ? &*world_->truth : nullptr);
  }

  PyTick record(bool new_frame, const std::optional<SlamPointsFrame>& points) const {
    PyTick t;
    t.tick = last_tick_;
    t.t_s = last_t_s_;
    t.running = mission_->running();
    const ClosedLoop& loop = mission_->loop();
    if (new_frame) {
      const std::shared_ptr<const CameraFrame> f = loop.sharedFrame();
      t.frame = frameView(f);
      t.frame_pose = readOnly(poseArray(f->T_W_C));
      t.frame_tick = py::int_(f->tick);
    }
    if (points) fillPoints(t, *points);
    t.true_pose = readOnly(poseArray(loop.groundTruth().T_W_B));
    t.est_pose = readOnly(poseArray(loop.estimate().T_W_B));
    t.true_velocity = readOnly(vec3Array(loop.groundTruth().v_W_mps));
    t.est_velocity = readOnly(vec3Array(loop.estimate().v_W_mps));
    return t;
  }

  PyScenario scenario_;
  std::unique_ptr<MissionWorld> world_;  // the truth the mission points into: never moves
  std::unique_ptr<Mission> mission_;
  std::optional<MissionResult> result_;
  std::optional<std::string> error_;  // the run ended with an error (a Python method raised)
  bool interrupted_ = false;          // a KeyboardInterrupt ended it: nothing to write
  int64_t last_tick_ = 0;
  double last_t_s_ = 0.0;
};

// ---- the module's parts ------------------------------------------------------------------------

// msbench.ConfigError (every configuration error of the CLI) and msbench.MethodError.
void bindErrors(py::module_& m) {
  // Every configuration error of the CLI (file, key, reason) is one Python exception type.
  static py::exception<FileConfigError> config_error(m, "ConfigError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const FileConfigError& e) {
      config_error(e.what());
    } catch (const UsageError& e) {
      config_error(e.what());
    } catch (const ConfigError& e) {
      config_error(e.what());
    }
  });

  static py::exception<MethodError> method_error(m, "MethodError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const MethodError& e) {
      method_error(e.what());
    } catch (const MethodOutputError& e) {
      method_error(e.what());
    }
  });
}

// Scenario and TickRecord.
void bindScenarioAndTicks(py::module_& m) {
  py::class_<PyScenario>(m, "Scenario", "A validated scenario file, as `msbench run` loads it.")
      .def_static("load", &PyScenario::load, py::arg("path"), py::arg("set") = std::vector<std::string>{},
                  "Loads a scenario with KEY=VALUE overrides (as --set); raises msbench.ConfigError.")
      .def("effective", &PyScenario::effective, "The full effective configuration as a dict.")
      .def(
          "effective_yaml", [](const PyScenario& s) { return s.effective_yaml; }, "config.yaml's text.")
      .def_property_readonly("file", [](const PyScenario& s) { return s.file; })
      .def_property_readonly("name", [](const PyScenario& s) { return s.spec.name; })
      .def_property_readonly("seed", [](const PyScenario& s) { return s.spec.flight.seed; })
      .def_property_readonly("method", [](const PyScenario& s) { return s.spec.method.type; })
      .def_property_readonly("duration_s", [](const PyScenario& s) { return s.spec.flight.duration_s; });

  py::class_<PyTick>(m, "TickRecord", "What a step produced (arrays are read-only).")
      .def_readonly("tick", &PyTick::tick)
      .def_readonly("t_s", &PyTick::t_s)
      .def_readonly("running", &PyTick::running)
      .def_readonly("frame", &PyTick::frame, "H×W uint8 fisheye image (a view, no copy), or None")
      .def_readonly("frame_pose", &PyTick::frame_pose, "true camera pose of the frame, 4×4")
      .def_readonly("frame_tick", &PyTick::frame_tick)
      .def_readonly("points", &PyTick::points, "SLAM points N×3 (VIO frame), or None")
      .def_readonly("point_covariances", &PyTick::point_covariances, "N×3×3 (m²)")
      .def_readonly("track_ids", &PyTick::track_ids, "N uint64")
      .def_readonly("true_pose", &PyTick::true_pose, "4×4 body pose, ground truth")
      .def_readonly("est_pose", &PyTick::est_pose, "4×4 body pose, VIO estimate")
      .def_readonly("true_velocity", &PyTick::true_velocity)
      .def_readonly("est_velocity", &PyTick::est_velocity);
}

// What a Python method sees: RngStream, Context, SlamFrame, Vehicle.
void bindMethodTypes(py::module_& m) {
  py::class_<RngStream>(m, "RngStream", "A named random stream, seeded like msbench's own (scenario seed + name).")
      .def(py::init<uint64_t, std::string>(), py::arg("seed"), py::arg("name"))
      .def("uniform", py::overload_cast<>(&RngStream::uniform), "uniform in [0, 1)")
      .def("uniform_range", [](RngStream& r, double lo, double hi) { return r.uniform(lo, hi); })
      .def("uniform_int", &RngStream::uniformInt, "uniform integer in [0, n)")
      .def("normal", py::overload_cast<>(&RngStream::normal), "standard normal");

  py::class_<MethodContext>(m, "Context", "What a Python method's factory receives.")
      .def_readonly("box_min", &MethodContext::box_min)
      .def_readonly("box_max", &MethodContext::box_max)
      .def_readonly("start_position", &MethodContext::start_position)
      .def_readonly("start_yaw_rad", &MethodContext::start_yaw_rad)
      .def_readonly("start_pose", &MethodContext::start_pose)
      .def_readonly("seed", &MethodContext::seed)
      .def(
          "rng", [](const MethodContext& c, const std::string& name) { return RngStream(c.seed, name); },
          py::arg("name"), "The method's RNG stream `name`, seeded from the scenario seed.");

  py::class_<SlamFrameView>(m, "SlamFrame", "A frame of SLAM points as a method observes it (estimate frame).")
      .def_readonly("tick", &SlamFrameView::tick)
      .def_readonly("t_s", &SlamFrameView::t_s)
      .def_readonly("pose", &SlamFrameView::pose, "estimated camera pose, 4×4")
      .def_readonly("points", &SlamFrameView::points, "N×3")
      .def_readonly("covariances", &SlamFrameView::covariances, "N×3×3")
      .def_readonly("track_ids", &SlamFrameView::track_ids, "N uint64");

  py::class_<GoalRequestView>(m, "GoalRequest", "What a goal chooser sees (estimate frame).")
      .def_readonly("t_s", &GoalRequestView::t_s)
      .def_readonly("needs_goal", &GoalRequestView::needs_goal,
                    "the baseline would draw a new goal now (none yet, reached, idle or timed out)")
      .def_readonly("position", &GoalRequestView::position)
      .def(
          "occupied", [](const GoalRequestView& v) { return v.leafArray(true); },
          "the OctoMap's occupied leaves, N×4 (x, y, z, edge m)")
      .def(
          "free", [](const GoalRequestView& v) { return v.leafArray(false); }, "its free leaves, N×4");

  py::class_<ViewpointRequestView>(m, "ViewpointRequest",
                                   "What a goal chooser sees when MonoSpheres takes a new goal (estimate frame).")
      .def_readonly("t_s", &ViewpointRequestView::t_s)
      .def_readonly("position", &ViewpointRequestView::position)
      .def_readonly("ids", &ViewpointRequestView::ids, "the reachable viewpoints' ids, N uint64, by path cost")
      .def_readonly("positions", &ViewpointRequestView::positions, "N×3")
      .def_readonly("yaws", &ViewpointRequestView::yaws, "N, rad")
      .def_readonly("path_costs", &ViewpointRequestView::path_costs, "N, m along the sphere graph")
      .def_readonly("values", &ViewpointRequestView::values, "N: frontiers each sees");

  py::class_<VehicleView>(m, "Vehicle", "The vehicle as a method plans for it (estimate frame).")
      .def_readonly("tick", &VehicleView::tick)
      .def_readonly("t_s", &VehicleView::t_s)
      .def_readonly("yaw_rad", &VehicleView::yaw_rad)
      .def_readonly("path_finished", &VehicleView::path_finished)
      .def_readonly("pose", &VehicleView::pose)
      .def_readonly("position", &VehicleView::position)
      .def_readonly("velocity", &VehicleView::velocity);
}

void bindMission(py::module_& m) {
  py::class_<PyMission>(m, "Mission", "A mission of a scenario, stepped or run from Python.")
      .def(py::init<const PyScenario&, py::object, py::object>(), py::arg("scenario"), py::arg("method") = py::none(),
           py::arg("goals") = py::none(),
           "method: None (the scenario's) or a factory(Context) returning a Python method; goals: a "
           "goal chooser for the scenario's method (the goal-only helper): grid_random: "
           "goals(GoalRequest) -> None | (x, y, z) | [(x, y, z), ...]; monospheres: "
           "goals(ViewpointRequest) -> None | 0 | viewpoint id")
      .def("area_m2", &PyMission::areaM2, "The coverage area so far (m²).")
      .def_property_readonly("physics_hz", &PyMission::physicsHz, "physics ticks per simulated second")
      .def_property_readonly("status", &PyMission::status)
      .def_property_readonly("running", &PyMission::running)
      .def("step", &PyMission::step, py::arg("n") = 1, "Steps up to n physics ticks; returns a TickRecord.")
      .def("run", &PyMission::run, py::arg("progress") = true, "Runs to the end (Ctrl-C raises KeyboardInterrupt).")
      .def("result", &PyMission::result, "metrics.json's content as a dict (the run must have ended).")
      .def("hash", &PyMission::hash, "The determinism hash (as msbench run prints it).")
      .def("write", &PyMission::write, py::arg("dir"), py::arg("overwrite") = false,
           "Writes the files msbench run writes into dir; returns its path.");
}

}  // namespace
}  // namespace msb

PYBIND11_MODULE(_msbench, m) {
  m.doc() = "msbench: deterministic closed-loop benchmark for monocular UAV exploration (docs/python.md)";
  msb::bindErrors(m);
  msb::bindScenarioAndTicks(m);
  msb::bindMethodTypes(m);
  msb::bindMission(m);
  m.attr("__version__") = MSB_VERSION;
}
