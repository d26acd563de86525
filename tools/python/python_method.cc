// Methods written in Python: the Explorer over a Python object, its errors and the types it sees.
#include "tools/python/binding.h"

#include <time.h>

#include <atomic>
#include <cmath>

#include "core/common/rng.h"
#include "core/explorer/output_limits.h"

namespace msb {
namespace binding {

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

/// An interrupt is never a method error: a KeyboardInterrupt raised inside a Python method's or
/// goal chooser's call (Ctrl-C, or the runner's SIGTERM/SIGHUP/SIGQUIT handlers) propagates as
/// it is, and the mission ends as interrupted (nothing recorded).
void rethrowIfInterrupt(py::error_already_set& e) {
  if (e.matches(PyExc_KeyboardInterrupt)) throw;
}

namespace {
std::atomic<unsigned long> method_call_thread{0};  // the thread inside a method's call (0: none)
}  // namespace

MethodCallNote::MethodCallNote() { method_call_thread = PyThread_get_thread_ident(); }
MethodCallNote::~MethodCallNote() { method_call_thread = 0; }

void interruptMethodCall() {
  const unsigned long t = method_call_thread;
  if (t != 0 && t != PyThread_get_thread_ident()) PyThreadState_SetAsyncExc(t, PyExc_KeyboardInterrupt);
}

void addOwnProcessClock(Explorer& explorer, const py::object& proxy) {
  if (!py::hasattr(proxy, "msbench_process_id")) return;
  const pid_t pid = proxy.attr("msbench_process_id").cast<pid_t>();
  clockid_t clock;
  if (clock_getcpuclockid(pid, &clock) != 0) return;
  explorer.addHelperClock([clock] {
    timespec ts{};
    return clock_gettime(clock, &ts) == 0 ? double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec) : 0.0;
  });
}

namespace {
py::handle method_timeout_type, method_exited_type, method_protocol_type;  // set by bindErrors
}  // namespace

void rethrowIfProcessError(py::error_already_set& e) {
  if (method_timeout_type && e.matches(method_timeout_type))
    throw MethodProcessError(RunStatus::kMethodTimeout, py::str(e.value()).cast<std::string>());
  if (method_exited_type && e.matches(method_exited_type))
    throw MethodProcessError(RunStatus::kMethodExited, py::str(e.value()).cast<std::string>());
  if (method_protocol_type && e.matches(method_protocol_type))
    throw MethodProcessError(RunStatus::kMethodProtocolError, py::str(e.value()).cast<std::string>());
}

namespace {

// A waypoint from Python: (x, y, z) or (x, y, z, heading_rad); heading None = face travel.
Waypoint waypointFrom(const py::handle& h) {
  const py::sequence seq = py::reinterpret_borrow<py::sequence>(h);
  if (seq.size() != 3 && seq.size() != 4) throw std::runtime_error("a waypoint is (x, y, z) or (x, y, z, heading_rad)");
  Waypoint w;
  w.position_m = Vec3(seq[0].cast<double>(), seq[1].cast<double>(), seq[2].cast<double>());
  if (seq.size() == 4 && !seq[3].is_none()) w.heading_rad = seq[3].cast<double>();
  return w;
}

// The optional pictures of a Python method: snapshot() -> {"obstacles": N×3, "frontiers": N×3,
// "viewpoints": [(x, y, z, yaw)], "goal": (x, y, z, yaw), "path": N×3}, every key optional.
std::vector<Vec3> pointsFrom(const py::handle& h, const char* key) {
  std::vector<Vec3> out;
  for (const auto& e : py::reinterpret_borrow<py::sequence>(h)) {
    if (out.size() == kMaxFreeSpaceElements)
      throw std::runtime_error(std::string("snapshot()['") + key + "'] has more than " +
                               std::to_string(kMaxFreeSpaceElements) + " points");
    const py::sequence q = py::reinterpret_borrow<py::sequence>(e);
    if (q.size() != 3) throw std::runtime_error(std::string("snapshot()['") + key + "']: a point is (x, y, z)");
    const Vec3 p(q[0].cast<double>(), q[1].cast<double>(), q[2].cast<double>());
    if (!p.allFinite()) throw std::runtime_error(std::string("snapshot()['") + key + "']: a point is not finite");
    out.push_back(p);
  }
  return out;
}

ExplorerSnapshot::Pose2 poseFrom(const py::handle& h, const char* key) {
  const py::sequence q = py::reinterpret_borrow<py::sequence>(h);
  if (q.size() != 4) throw std::runtime_error(std::string("snapshot()['") + key + "']: a pose is (x, y, z, yaw)");
  ExplorerSnapshot::Pose2 p{Vec3(q[0].cast<double>(), q[1].cast<double>(), q[2].cast<double>()), q[3].cast<double>()};
  if (!p.position.allFinite() || !std::isfinite(p.yaw_rad))
    throw std::runtime_error(std::string("snapshot()['") + key + "']: a pose is not finite");
  return p;
}

void addPictures(const py::dict& d, ExplorerSnapshot& snap) {
  for (const auto& kv : d) {
    const std::string key = kv.first.cast<std::string>();
    if (key == "obstacles") {
      snap.obstacles = pointsFrom(kv.second, "obstacles");
    } else if (key == "frontiers") {
      snap.frontiers = pointsFrom(kv.second, "frontiers");
    } else if (key == "path") {
      snap.path = pointsFrom(kv.second, "path");
    } else if (key == "viewpoints") {
      for (const auto& v : py::reinterpret_borrow<py::sequence>(kv.second))
        snap.viewpoints.push_back(poseFrom(v, "viewpoints"));
    } else if (key == "goal") {
      if (!kv.second.is_none()) snap.goal = poseFrom(kv.second, "goal");
    } else {
      throw std::runtime_error("snapshot() returned the unknown key '" + key +
                               "' (obstacles, frontiers, viewpoints, goal, path)");
    }
  }
}

/// The Explorer interface over a Python object with observe(frame), plan(vehicle) -> None or a
/// list of waypoints, free_space() -> [(id, x, y, z, radius[, "disk" | "square"])], counters() ->
/// {name: number}. Each call holds the GIL; a Python exception becomes a MethodError.
class PyExplorer final : public Explorer {
 public:
  explicit PyExplorer(py::object method) : method_(std::move(method)) {
    // A method in its own process: that process's CPU clock (compute charged, docs/compute.md).
    addOwnProcessClock(*this, method_);
  }
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
      // What the pictures draw besides the free space, if the method says (snapshot(), optional).
      if (py::hasattr(method_, "snapshot")) {
        const py::object extra = method_.attr("snapshot")();
        if (!extra.is_none()) {
          if (!py::isinstance<py::dict>(extra)) throw std::runtime_error("snapshot() must return a dict or None");
          addPictures(extra.cast<py::dict>(), snap);
        }
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
    const MethodCallNote note;
    try {
      f();
    } catch (py::error_already_set& e) {
      rethrowIfInterrupt(e);
      rethrowIfProcessError(e);
      throw MethodError("the Python method raised:\n" + pythonErrorText(e));
    } catch (const py::cast_error& e) {
      throw MethodError(std::string("the Python method returned a value of the wrong type: ") + e.what());
    } catch (const MethodOutputError&) {
      throw;  // a limit of the metric, named as such
    } catch (const std::runtime_error& e) {
      throw MethodError(std::string("the Python method: ") + e.what());  // an answer of the wrong shape
    }
  }

  py::object method_;
};

}  // namespace

std::unique_ptr<Explorer> makePythonExplorer(py::object method) {
  return std::make_unique<PyExplorer>(std::move(method));
}

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
  // A method in its own process that stopped answering, or whose process ended (msbench.confined).
  static py::exception<MethodProcessError> timeout(m, "MethodTimeout", method_error.ptr());
  static py::exception<MethodProcessError> exited(m, "MethodExited", method_error.ptr());
  method_timeout_type = timeout;
  method_exited_type = exited;
  // A message the method's process sent that msbench does not answer (msbench.confined).
  static py::exception<MethodProcessError> protocol(m, "MethodProtocolError", method_error.ptr());
  method_protocol_type = protocol;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const MethodProcessError& e) {
      (e.status == RunStatus::kMethodTimeout         ? timeout
       : e.status == RunStatus::kMethodProtocolError ? protocol
                                                     : exited)(e.what());
    } catch (const MethodError& e) {
      method_error(e.what());
    } catch (const MethodCallError& e) {  // a C++ method's call that threw, named by the loop
      method_error(e.what());
    } catch (const MethodOutputError& e) {
      method_error(e.what());
    }
  });
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

}  // namespace binding
}  // namespace msb
