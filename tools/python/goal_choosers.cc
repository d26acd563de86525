// The goal-only helper: a Python goal chooser for the scenario's grid or MonoSpheres explorer.
#include "tools/python/binding.h"

#include <algorithm>

#include "core/methods/grid_random/grid_explorer.h"
#include "core/methods/monospheres/planner/goal_choice.h"
#include "tools/config/method_table.h"

namespace msb {
namespace binding {

namespace {

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
  const MethodCallNote note;
  try {
    return f();
  } catch (py::error_already_set& e) {
    rethrowIfInterrupt(e);
    rethrowIfProcessError(e);
    throw MethodError("the Python goal chooser raised:\n" + pythonErrorText(e));
  } catch (const py::cast_error& e) {
    throw MethodError(std::string("the Python goal chooser returned a value of the wrong type: ") + e.what());
  } catch (const std::runtime_error& e) {
    throw MethodError(std::string("the Python goal chooser: ") + e.what());
  }
}

/// A Python viewpoint chooser for MonoSpheres: goals(request) -> None (MonoSpheres' own choice),
/// 0 (no goal this step) or a candidate's id; an exception becomes a MethodError.
ViewpointChooser pythonViewpointChooser(std::shared_ptr<py::object> fn) {
  return [fn](const ViewpointRequest& q) {
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
  };
}

/// A Python goal chooser for the grid: goals(request) is called at every goal check with the GIL
/// held; an exception becomes a MethodError (its own process's end: that run status).
GoalChooser pythonGoalChooser(std::shared_ptr<py::object> fn) {
  return [fn](const GoalRequest& q) {
    return callChooser([&]() -> std::optional<std::vector<Vec3>> {
      GoalRequestView v;
      v.t_s = q.t_s;
      v.needs_goal = q.needs_goal;
      v.position = readOnly(vec3Array(q.position));
      v.map = q.map;
      py::object view = py::cast(v);
      // The map is the explorer's: the view forgets it when the call returns or raises.
      struct Forget {
        py::object& view;
        ~Forget() { view.cast<GoalRequestView&>().map = nullptr; }
      } forget{view};
      return goalChoiceFrom((*fn)(view));
    });
  };
}

}  // namespace

void attachGoalChooser(Explorer& explorer, const std::string& method_type, py::object goals,
                       const std::string& scenario_file) {
  // The method's registration says which goal-chooser hooks it offers (no method is named here).
  const MethodRegistration* reg = findRegistration(method_type);
  const ExplorerHook* goal_hook = reg ? reg->info.hook("goal_chooser") : nullptr;
  const ExplorerHook* viewpoint_hook = reg ? reg->info.hook("viewpoint_chooser") : nullptr;
  if (!goal_hook && !viewpoint_hook) {
    std::string takers;
    for (const MethodRegistration& r : methodRegistrations())
      if (takesGoalChooser(registeredMethodChoice(r, r.default_config())))
        takers += (takers.empty() ? "" : ", ") + r.info.type;
    throw py::value_error(scenario_file + ": goals= needs a scenario whose method.type takes a goal chooser (" +
                          takers + "; got '" + method_type + "')");
  }
  // A chooser in its own process (a scenario's `goals`): its CPU time is charged like the method's.
  addOwnProcessClock(explorer, goals);
  auto fn = std::make_shared<py::object>(std::move(goals));
  if (goal_hook) (*goal_hook)(explorer, std::any(pythonGoalChooser(fn)));
  if (viewpoint_hook) (*viewpoint_hook)(explorer, std::any(pythonViewpointChooser(fn)));
}

}  // namespace binding
}  // namespace msb
