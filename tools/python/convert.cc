// Conversions between msbench's records and Python objects, and the Scenario/TickRecord types.
#include "tools/python/binding.h"

#include <utility>

namespace msb {
namespace binding {

namespace {
// A JSON tree (of yamlAsJson) as nested dicts, lists and scalars, in its key order.
py::object plainToPython(const nlohmann::ordered_json& j) {
  if (j.is_object()) {
    py::dict d;
    for (const auto& [k, v] : j.items()) d[py::str(k)] = plainToPython(v);
    return d;
  }
  if (j.is_array()) {
    py::list l;
    for (const auto& e : j) l.append(plainToPython(e));
    return l;
  }
  if (j.is_boolean()) return py::bool_(j.get<bool>());
  if (j.is_number_integer()) return py::int_(j.get<long long>());
  if (j.is_number_float()) return py::float_(j.get<double>());
  if (j.is_string()) return py::str(j.get<std::string>());
  return py::none();
}
}  // namespace

py::object yamlToPython(const std::string& yaml_text) { return plainToPython(yamlAsJson(yaml_text)); }

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

// The frame as a read-only H×W uint8 view, no copy: a capsule owning a reference to the frame
// is the array's base, so the view stays valid after the loop moves on (the loop renders the
// next frame into a new buffer while this one is held) and frees it with the last view.
py::array frameView(std::shared_ptr<const CameraFrame> frame) {
  auto* owner = new std::shared_ptr<const CameraFrame>(std::move(frame));
  py::capsule base(owner, [](void* p) { delete static_cast<std::shared_ptr<const CameraFrame>*>(p); });
  const CameraFrame& f = **owner;
  return readOnly(py::array_t<uint8_t>({f.height, f.width}, {f.width, 1}, f.pixels.data(), base));
}

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

std::string pathOf(const py::handle& path) {
  if (py::isinstance<py::str>(path)) return path.cast<std::string>();
  if (py::hasattr(path, "__fspath__")) return py::module_::import("os").attr("fspath")(path).cast<std::string>();
  throw py::type_error("expected a path (str or os.PathLike), got " + std::string(py::str(path.get_type())));
}

std::vector<std::string> setsOf(const py::handle& sets) {
  std::vector<std::string> out;
  if (sets.is_none()) return out;
  if (py::isinstance<py::dict>(sets)) {
    const py::module_ json = py::module_::import("json");
    for (const auto& [k, v] : sets.cast<py::dict>()) {
      std::string value;
      if (py::isinstance<py::bool_>(v))
        value = v.cast<bool>() ? "true" : "false";
      else if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v) || py::isinstance<py::dict>(v))
        value = json.attr("dumps")(v).cast<std::string>();
      else
        value = py::str(v).cast<std::string>();
      out.push_back(py::str(k).cast<std::string>() + "=" + value);
    }
    return out;
  }
  if (py::isinstance<py::list>(sets) || py::isinstance<py::tuple>(sets)) {
    for (const auto& item : sets) {
      if (!py::isinstance<py::str>(item))
        throw py::type_error("set: each entry of a list is a 'KEY=VALUE' string, got " +
                             std::string(py::str(item.get_type())));
      out.push_back(item.cast<std::string>());
    }
    return out;
  }
  throw py::type_error("set: expected a dict {key: value} or a list of 'KEY=VALUE' strings, got " +
                       std::string(py::str(sets.get_type())));
}

PyScenario scenarioOf(const py::handle& scenario) {
  if (py::isinstance<PyScenario>(scenario)) return scenario.cast<PyScenario>();
  return PyScenario::load(pathOf(scenario), {});
}

// Scenario and TickRecord.
void bindScenarioAndTicks(py::module_& m) {
  py::class_<PyScenario>(m, "Scenario", "A validated scenario file, as `msbench run` loads it.")
      .def_static(
          "load",
          [](const py::object& path, const py::object& sets) { return PyScenario::load(pathOf(path), setsOf(sets)); },
          py::arg("path"), py::arg("set") = py::none(),
          "Loads a scenario file (a path) with overrides as --set gives them: set= a dict {key: value} or a "
          "list of 'KEY=VALUE' strings. Raises msbench.ConfigError naming the file and key.")
      .def_property_readonly(
          "sets", [](const PyScenario& s) { return s.sets; }, "The KEY=VALUE overrides it was loaded with.")
      .def("effective", &PyScenario::effective, "The full effective configuration as a dict.")
      .def(
          "effective_yaml", [](const PyScenario& s) { return s.effective_yaml; }, "config.yaml's text.")
      .def_property_readonly(
          "file", [](const PyScenario& s) { return s.file; }, "The scenario file's path.")
      .def_property_readonly(
          "name", [](const PyScenario& s) { return s.spec.name; }, "The scenario's name.")
      .def_property_readonly(
          "seed", [](const PyScenario& s) { return s.spec.flight.seed; }, "The run's seed.")
      .def_property_readonly(
          "method", [](const PyScenario& s) { return s.spec.method.type; }, "The method's type (method.type).")
      .def_property_readonly(
          "duration_s", [](const PyScenario& s) { return s.spec.flight.duration_s; }, "Simulated duration (s).");

  py::class_<PyTick>(m, "TickRecord", "What a step produced (arrays are read-only).")
      .def_readonly("tick", &PyTick::tick, "physics tick after the step")
      .def_readonly("t_s", &PyTick::t_s, "simulated time after the step (s)")
      .def_readonly("running", &PyTick::running, "True until the run ends")
      .def_readonly("frame", &PyTick::frame, "H×W uint8 fisheye image (a view, no copy), or None")
      .def_readonly("frame_pose", &PyTick::frame_pose, "true camera pose of the frame, 4×4")
      .def_readonly("frame_tick", &PyTick::frame_tick, "tick of the frame, or None")
      .def_readonly("points", &PyTick::points, "SLAM points N×3 (VIO frame), or None")
      .def_readonly("point_covariances", &PyTick::point_covariances, "N×3×3 (m²)")
      .def_readonly("track_ids", &PyTick::track_ids, "N uint64")
      .def_readonly("true_pose", &PyTick::true_pose, "4×4 body pose, ground truth")
      .def_readonly("est_pose", &PyTick::est_pose, "4×4 body pose, VIO estimate")
      .def_readonly("true_velocity", &PyTick::true_velocity, "body velocity (m/s), ground truth")
      .def_readonly("est_velocity", &PyTick::est_velocity, "body velocity (m/s), VIO estimate");
}

}  // namespace binding
}  // namespace msb
