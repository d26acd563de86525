// The keys of a flight, read into a FlightSpec (inside tools/config: flight files and scenarios
// share them).
#pragma once

#include <filesystem>

#include "tools/config/yaml_reader.h"
#include "tools/loop/flight_spec.h"

namespace msb {

/// Reads the keys of a flight (world, seed, duration_s, start, trajectory, sensors, ...) from
/// `r` without rejecting the others; `dir` resolves a relative MJCF world path.
void readFlightKeys(MapReader& r, const std::filesystem::path& dir, FlightSpec& s);

}  // namespace msb
