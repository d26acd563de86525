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
  /// axis only, while the free-space polyhedron spans the fisheye's ±90°. (The same pinhole K in
  /// DBOF's triangulation test, OVDE and viewpoint visibility is not modelled yet.)
  bool pinhole_rays = false;
  /// The 300 viewpoint samples take sphere number k of the whole map for k drawn below the count
  /// of reachable spheres: the oldest spheres, reachable or not, whatever the search radius.
  bool viewpoints_anywhere = false;

  /// Every switch on: the published code as far as msbench models it.
  static ReferenceCodeConfig published() {
    ReferenceCodeConfig c;
    for (const auto& [name, member] : switches()) c.*member = true;
    return c;
  }
  /// The switches by name with their member, in documentation order.
  static const std::array<std::pair<const char*, bool ReferenceCodeConfig::*>, 5>& switches() {
    static const std::array<std::pair<const char*, bool ReferenceCodeConfig::*>, 5> kSwitches = {{
        {"path_resend_8s", &ReferenceCodeConfig::path_resend_8s},
        {"safety_cost_inverted", &ReferenceCodeConfig::safety_cost_inverted},
        {"heading_check_signed", &ReferenceCodeConfig::heading_check_signed},
        {"pinhole_rays", &ReferenceCodeConfig::pinhole_rays},
        {"viewpoints_anywhere", &ReferenceCodeConfig::viewpoints_anywhere},
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
