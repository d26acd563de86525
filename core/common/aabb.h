// Axis-aligned boxes (exploration boxes, bounds): a plain type shared by every module, so that
// exploration methods need not include the ground-truth geometry to know their box.
#pragma once

#include "core/common/types.h"

namespace msb {

/// Axis-aligned box [min, max] in the world frame.
struct Aabb {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  /// True if p lies inside or on the box.
  bool contains(const Vec3& p) const { return (p.array() >= min.array()).all() && (p.array() <= max.array()).all(); }
};

}  // namespace msb
