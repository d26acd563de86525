// The published MonoSpheres code's defects as switches (`method.reference_code`,
// docs/deviations.md "The published code as switches"). msbench builds the intended method; each
// switch puts back one behaviour of the authors' code (ctu-mrs/monospheres at 43fca1f) that
// differs from it, so that a run can say what made the paper's Table I. All are off by default;
// `reference_code: published` turns every modelled defect on.
#pragma once

#include <array>
#include <map>
#include <string>
#include <utility>

namespace msb {

/// One switch per modelled defect of the published code (off: the intended method).
struct ReferenceCodeConfig {
  /// A path to the carrot is sent only when none was sent or 8 s have passed since the last one
  /// (the published progress test compares a global position with FCU-frame waypoints and never
  /// fires); a new goal's path waits for the same timer.
  bool path_resend_8s = false;
  /// The A* safety cost rises with the radius ((r − r_min)/(r_safe − r_min))², zero above
  /// r_safe: wide spheres cost up to 1 + w, narrow ones nothing.
  bool safety_cost_inverted = false;
  /// The heading test of "goal reached" lacks abs(): any heading difference below +90° passes,
  /// however far negative.
  bool heading_check_signed = false;
  /// New spheres' sample rays are back-projected with the pinhole K over the whole image, as the
  /// published mapper does (SBM ~569-631, 812-813): they reach ±58.8° × ±46.5° about the optical
  /// axis only, while the free-space polyhedron spans the fisheye's ±90°. The viewpoints' frontier
  /// visibility uses the same K (LNM getViewpointFrontierValue, CS getVisiblePoints): a frontier
  /// counts only inside the pinhole frustum. (DBOF's and OVDE's uses of K are not modelled yet.)
  bool pinhole_rays = false;
  /// The 300 viewpoint samples take sphere number k of the whole map, k drawn over all of them
  /// (LNM 1815-1823: `getReachableNodes` returns a mask over every sphere, so its length is the
  /// map's sphere count): reachable or not, whatever the search radius.
  bool viewpoints_anywhere = false;
  /// A failed path search keeps its goal for another try while the mission has failed at most
  /// three searches in all; the published counter is never reset, so from the fourth failure on
  /// every failed search fails its goal at once (LNM 185-186, 1505-1512).
  bool failure_counter_never_reset = false;
  /// The mapper's pruning test indexes the worked spheres with a stale loop index (SBM 750-756):
  /// when the last worked sphere ends below r_min, the update neither re-links the worked
  /// spheres nor prunes those below r_min or redundant ones; edges stay as they were.
  bool worked_mask_scalar = false;
  /// An update in which no new sphere passes returns early (SBM 800-804, 869-873): the frame's
  /// points are not inserted as obstacle points and no frontier candidates are drawn from it.
  bool early_return_stale = false;
  /// The slow planning (goal choice and path) runs only after at least two map updates since
  /// its last run (OVX planning_loop_iter 317-339); the stop check below runs at every planning
  /// tick all the same.
  bool planning_gate_two_updates = false;
  /// The published stop (LNM quick_replanning_iter 985-1027, stop_following_roadmap_and_stop):
  /// at every planning tick the path ahead (up to 5 m, ignoring its first 1.5 m) is checked for
  /// a point within 1 m of an obstacle point; if so the vehicle is hard-stopped with a one-point
  /// path, which restarts the 8 s re-send timer, and the goal is dropped (not failed, not
  /// blacklisted). msbench's own blocked-route hold is not used.
  bool hardstop_drops_goal = false;
  /// With FFF off (the ablation: `fix_heading_at_path_start: True`), the published heading path
  /// still looks for where to start turning to the goal's heading and gives up on a goal whose
  /// turn does not fit at max_heading_change_per_m (LNM ~310-322, "cant find good index to start
  /// turning"): the turn-feasibility check stays. msbench skips it without FFF.
  bool turn_check_without_fff = false;
  /// DBOF and the protected set use the OVDE-extended free-space polyhedron: the virtual points
  /// are appended before P_f is triangulated (SBM ~560-667), so old points inside the extended
  /// P_f are deleted when seen again from closer, else protected and capping sphere radii — over
  /// open ground too. msbench applies DBOF to the real points' P_f (the paper: virtual free
  /// space "cannot erase existing obstacle points").
  bool dbof_on_ovde_polyhedron = false;
  /// OVDE's activation as published (SBM `ofs_freespace_update`, ~1039-1140): the virtual points
  /// are the pinhole K's rays; visibility in past poses is the pinhole projection; the parallax
  /// angle mixes the current and the old frame; the run of poses that see a point is counted
  /// from the oldest; the flags are recomputed only when a pose is buffered
  /// (OpenAreaDepth::updatePublished).
  bool ovde_parallax_frames = false;
  /// DBOF's "inside the triangulation" test as published (SBM 604-606, 630-637): old points are
  /// projected with the pinhole K, without distortion, and tested against the triangulation of
  /// the frame's points projected *with* the fisheye distortion; a point off the axis lands
  /// farther out than its true image, so DBOF neither deletes nor protects it beyond about 55°
  /// from the axis.
  bool dbof_pinhole_projection = false;
  /// Visited-viewpoint blocking blocks poses, as published (LNM isViewpointBlockedByExplorationGoals,
  /// 1739-1778): a marker blocks every pose within 7 m and 60°. msbench's per-frontier limit
  /// (`planner.viewpoints.frontier_view_limit`) is not used.
  bool plain_pose_blocking = false;
  /// With no goal the published vehicle hovers (LNM exploration_logic 1852-1943: no goal found,
  /// nothing is sent): no bridge out of its part of the graph, no idle turn, no relaxed
  /// viewpoint value. msbench's stall breakers are off.
  bool hover_without_goal = false;
  /// The published graph is the spheres' overlaps only (LNM findPathAstarInSubmap 853-983,
  /// getReachableNodes 750-848 walk `smap.connections`): no gap or trail links between its parts.
  bool graph_without_links = false;
  /// The path sent is the A* route's raw sphere centres from the start sphere's centre, then the
  /// goal (LNM find_headingpath_astar_smap_frame 230-365: `postproc_path` is never called):
  /// no shortcutting, and the vehicle's own position is not the path's first point.
  bool raw_sphere_paths = false;
  /// The route's centre-to-centre segments are not checked against the obstacle points before
  /// the path is sent (the published A* tests radii only, LNM 951-953): no route edge is blocked;
  /// the stop (hardstop_drops_goal) is the only check.
  bool route_edges_unchecked = false;

  /// Every switch on: the published code as far as msbench models it.
  static ReferenceCodeConfig published() {
    ReferenceCodeConfig c;
    for (const auto& [name, member] : switches()) c.*member = true;
    return c;
  }
  /// The switches by name with their member, in documentation order.
  static const std::array<std::pair<const char*, bool ReferenceCodeConfig::*>, 19>& switches() {
    static const std::array<std::pair<const char*, bool ReferenceCodeConfig::*>, 19> kSwitches = {{
        {"path_resend_8s", &ReferenceCodeConfig::path_resend_8s},
        {"safety_cost_inverted", &ReferenceCodeConfig::safety_cost_inverted},
        {"heading_check_signed", &ReferenceCodeConfig::heading_check_signed},
        {"pinhole_rays", &ReferenceCodeConfig::pinhole_rays},
        {"viewpoints_anywhere", &ReferenceCodeConfig::viewpoints_anywhere},
        {"failure_counter_never_reset", &ReferenceCodeConfig::failure_counter_never_reset},
        {"worked_mask_scalar", &ReferenceCodeConfig::worked_mask_scalar},
        {"early_return_stale", &ReferenceCodeConfig::early_return_stale},
        {"planning_gate_two_updates", &ReferenceCodeConfig::planning_gate_two_updates},
        {"hardstop_drops_goal", &ReferenceCodeConfig::hardstop_drops_goal},
        {"turn_check_without_fff", &ReferenceCodeConfig::turn_check_without_fff},
        {"dbof_on_ovde_polyhedron", &ReferenceCodeConfig::dbof_on_ovde_polyhedron},
        {"ovde_parallax_frames", &ReferenceCodeConfig::ovde_parallax_frames},
        {"dbof_pinhole_projection", &ReferenceCodeConfig::dbof_pinhole_projection},
        {"plain_pose_blocking", &ReferenceCodeConfig::plain_pose_blocking},
        {"hover_without_goal", &ReferenceCodeConfig::hover_without_goal},
        {"graph_without_links", &ReferenceCodeConfig::graph_without_links},
        {"raw_sphere_paths", &ReferenceCodeConfig::raw_sphere_paths},
        {"route_edges_unchecked", &ReferenceCodeConfig::route_edges_unchecked},
    }};
    return kSwitches;
  }
  /// Name → value of every switch (metrics.json, report labels).
  std::map<std::string, bool> values() const {
    std::map<std::string, bool> out;
    for (const auto& [name, member] : switches()) out[name] = this->*member;
    return out;
  }
  /// True if any switch is on.
  bool any() const {
    for (const auto& [name, member] : switches())
      if (this->*member) return true;
    return false;
  }
};

}  // namespace msb
