// Conversions between msbench's records and Python objects, and the Scenario/TickRecord types.
#include "tools/python/binding.h"

#include <utility>

namespace msb {
namespace binding {

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

}  // namespace binding
}  // namespace msb
