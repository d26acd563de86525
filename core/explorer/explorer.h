// The interface every exploration method implements (docs/architecture.md, "Adding a method"): it
// observes each frame of SLAM points (its own map update), plans at the planning rate and emits
// path commands for the trajectory tracker, and exposes the free space it has mapped as geometry,
// which the coverage metric (core/eval) scores. This layer depends on core/common alone: a method
// links msb::explorer, never the metric or another method. Methods are chosen by `method.type` in
// a scenario; a new method lives in its own folder behind this interface and registers itself
// there (core/explorer/method_registry.h). The loop times observe() and plan() itself (wall
// time is recorded, never used).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/common/aabb.h"
#include "core/common/messages.h"
#include "core/explorer/snapshot.h"

namespace msb {

/// What every method knows about its mission.
struct ExplorerContext {
  Aabb exploration_box;           ///< goals outside are ignored (estimate frame = world frame at start)
  Pose start = Pose::Identity();  ///< body pose at start
  uint64_t seed = 1;              ///< scenario seed (for the method's RNG streams)
};

/// The vehicle as the planner sees it (estimate frame), once per planning step.
struct VehicleState {
  int64_t tick = 0;
  double t_s = 0.0;
  Pose T_W_B = Pose::Identity();     ///< VIO estimate
  Vec3 velocity_mps = Vec3::Zero();  ///< VIO estimate
  TrajectoryReference reference;     ///< the tracker's current reference
  /// The method's last command is done (at rest, heading reached): false while a path it sent
  /// has not yet taken effect (compute in the loop, docs/compute.md).
  bool path_finished = true;
};

/// A method's output broke the interface's contract (free space or waypoints not finite, out of
/// range, too many): the run ends with status error naming the element and the tick.
class MethodOutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What a method's observe() or plan() threw, named by the call and its tick (the loop wraps
/// any error a call throws that does not say so itself: docs/architecture.md).
class MethodCallError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An exploration method.
class Explorer {
 public:
  Explorer() = default;
  /// Not copyable: a method's parts may refer to its own map (a copy would point into the
  /// original); a new explorer from the method registry is the reset (docs/architecture.md §3).
  Explorer(const Explorer&) = delete;
  Explorer& operator=(const Explorer&) = delete;
  virtual ~Explorer() = default;
  /// Integrates one frame of SLAM points (called at the map-update rate).
  virtual void observe(const SlamPointsFrame& frame) = 0;
  /// One planning step; returns a new path to follow, or none to keep the current one.
  virtual std::optional<PathCommand> plan(const VehicleState& vehicle) = 0;
  /// Map contents for pictures and the determinism hash.
  virtual ExplorerSnapshot snapshot() const = 0;
  /// The free space the method has mapped, as geometry (spheres' disks, free cells' squares).
  /// The coverage metric (core/eval) turns it into columns every metric period: a method never
  /// scores itself. By default taken from snapshot().
  virtual std::vector<FreeSpaceElement> freeSpace() const { return snapshot().free_space; }
  /// Counters for metrics.json and the progress line (e.g. spheres, goals reached).
  virtual std::map<std::string, double> counters() const = 0;
  /// The counters a cost model charges its calls by (`timing.compute: modelled`, docs/compute.md),
  /// read after every call: the size of what the method works on (points, frontiers, ...). By
  /// default counters(); a method whose counters() is costly gives the cheap ones here.
  virtual std::map<std::string, double> workCounters() const { return counters(); }
  /// CPU seconds, so far, of the processes the method computes in besides the thread that calls
  /// it (a Python method's or goal chooser's own process; `timing.compute: charged`): by default
  /// the sum of the clocks added with addHelperClock (0 for a method wholly in-process).
  virtual double helperCpuSeconds() const {
    double s = 0.0;
    for (const auto& clock : helper_clocks_) s += clock();
    return s;
  }
  /// Adds a process the method computes in (a goal chooser's own process) to helperCpuSeconds().
  void addHelperClock(std::function<double()> clock) { helper_clocks_.push_back(std::move(clock)); }

 private:
  std::vector<std::function<double()>> helper_clocks_;  // CPU seconds of helper processes
};

/// A path command sent at this planning step: `last_path` becomes the vehicle's reference followed
/// by the waypoints (for pictures and checks along it), and `paths_sent` counts it.
PathCommand sendPath(const VehicleState& vehicle, std::vector<Waypoint> waypoints, std::vector<Vec3>& last_path,
                     double& paths_sent);

}  // namespace msb
