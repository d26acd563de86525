// The keys of a flight, read into a FlightSpec or written from one (inside tools/config: flight
// files and scenarios share them).
#pragma once

#include <filesystem>

#include "tools/config/yaml_reader.h"
#include "tools/config/yaml_writer.h"
#include "tools/engine/flight_spec.h"

namespace msb {

/// Reads the keys of a flight (world, seed, duration_s, start, trajectory, sensors, ...) from
/// `r` without rejecting the others; `dir` resolves a relative MJCF world path.
void readFlightKeys(MapReader& r, const std::filesystem::path& dir, FlightSpec& s);

/// Writes every key of a flight, defaults included (the start pose only if `with_start`), so
/// that reading them back gives the same FlightSpec.
void writeFlightKeys(MapWriter& w, const FlightSpec& s, bool with_start);

}  // namespace msb
