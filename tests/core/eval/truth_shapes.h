// Hand-built truth for the metric's tests: the ground and axis-aligned blocks.
#pragma once

#include "core/geometry/world_truth.h"

namespace msb::test {

/// The ground: the half-space below z = 0.
inline Shape ground() {
  Shape s;
  s.type = ShapeType::kHalfSpace;
  return s;
}

/// A box of half sizes `half` about `centre`, not turned.
inline Shape block(const Vec3& centre, const Vec3& half) {
  Shape s;
  s.type = ShapeType::kBox;
  s.pose = poseFromXyzYaw(centre, 0.0);
  s.size = half;
  return s;
}

}  // namespace msb::test
