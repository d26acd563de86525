// Road vehicles built like vehicles (issue 12): car, SUV, bus, fire truck and ambulance as
// compositions of primitives — body panels in flat paint (textureless), dark windows, tyres with
// light rims, bumpers and lights — each part a collision geom, so the collision shape follows
// the vehicle. The paint is textureless as in the reference's Gazebo models; the structure
// (window edges, wheel arches, lights) is what a corner detector can find. The parts are drawn
// as one mesh per grey level of each vehicle (MjcfWorldBuilder merge groups).
#pragma once

#include <string>

#include "core/common/rng.h"
#include "core/common/types.h"
#include "sim/world/mjcf_world_builder.h"

namespace msb {

/// True for the kinds buildVehicle() knows: car, suv, bus, fire_truck, ambulance.
bool isVehicleKind(const std::string& kind);

/// Emits the parts of one vehicle of `kind` with overall size `size` (length along the base
/// frame's x, width, height), standing on the base pose. `detail` draws the paint shade.
void buildVehicle(const std::string& kind, const std::string& id, const Pose& base, const Vec3& size, RngStream& detail,
                  MjcfWorldBuilder& b);

}  // namespace msb
