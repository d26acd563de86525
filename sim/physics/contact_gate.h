// Which physics steps can skip MuJoCo's collision detection without changing a bit.
//
// MuJoCo 2.2.2 tests every geom of the world body against every geom of the vehicle on every
// step (its broadphase works on bodies, and the world is one body): 2570 geom pairs in urban,
// about three quarters of a physics step. A contact needs the two shapes within the contact
// margin of each other, so while the vehicle's bounding ball is farther than the margin from
// every world geom's bounding box, detection would find nothing; the step then runs with contacts
// disabled, which MuJoCo treats exactly as a detection that found none (ncon = 0).
//
// The vehicle's ball: its body origin and the farthest point of its geoms' bounding spheres.
// A world geom's box: its own shape's box (box, cylinder, capsule, ellipsoid, sphere; a mesh's
// vertex box), or the cube around its bounding sphere; a plane is the half-space MuJoCo
// collides with. Distances are kept as a free radius around the last position computed, so a
// step usually costs one distance; the ball is re-measured when the vehicle leaves it.
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "core/common/messages.h"

namespace msb {

/// Decides per step whether the vehicle can touch the world (conservatively: never "no" when
/// MuJoCo would find a contact).
class ContactGate {
 public:
  /// Reads the static world geoms' poses from `d` (after mj_forward) and the vehicle's geoms
  /// (those of `vehicle_body`). The gate stays inactive (every step detects) when the model has
  /// explicit contact pairs, a moving body other than the vehicle with collision geoms, or a
  /// non-plane collision geom without a bounding sphere.
  ContactGate(const mjModel* m, const mjData* d, int vehicle_body);

  /// Whether a contact is possible with the vehicle's body origin at `p` (always true when
  /// inactive).
  bool mayTouch(const Vec3& p);
  /// Distance from the vehicle's ball at `p` to the nearest world geom's box or half-space,
  /// less the contact margin and a slack (> 0: no contact possible).
  double clearance(const Vec3& p) const;
  /// Whether the gate can skip steps in this model; if not, why (for bench-sim).
  bool active() const { return why_inactive_.empty(); }
  const std::string& whyInactive() const { return why_inactive_; }
  /// Radius of the vehicle's ball (body origin to its farthest geom point).
  double vehicleRadius() const { return vehicle_radius_; }
  /// World geoms the vehicle can touch (boxes) and planes.
  int boxes() const { return int(boxes_.size()); }
  int planes() const { return int(planes_.size()); }

 private:
  struct Box {
    Vec3 centre;
    Mat3 R;  // box axes in the world (columns)
    Vec3 half;
  };
  struct HalfSpace {
    Vec3 normal;    // pointing out of the solid side
    double offset;  // normal · x on the plane
  };
  void addGeom(const mjModel* m, const mjData* d, int g);

  std::vector<Box> boxes_;
  std::vector<HalfSpace> planes_;
  double vehicle_radius_ = 0.0;
  double reach_ = 0.0;  // vehicle radius + contact margin + slack
  std::string why_inactive_;
  Vec3 anchor_ = Vec3::Zero();  // where the free radius was measured
  double free_radius_ = -1.0;   // no contact within this distance of anchor_ (<= 0: unknown)
};

}  // namespace msb
