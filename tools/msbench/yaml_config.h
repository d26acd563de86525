// The only place where YAML meets configuration structs. Unknown keys, wrong types, missing
// files and invalid values all throw FileConfigError, whose message names the file, the key
// and the reason; nothing is written before a file has loaded completely.
#pragma once

#include <filesystem>
#include <string>

#include "tools/loop/flight_spec.h"
#include "tools/msbench/yaml_reader.h"

namespace msb {

/// Loads and validates a flight file for `msbench fly`. Relative paths inside resolve
/// against the file's directory.
FlightSpec loadFlightSpec(const std::string& path);

/// Reads the keys of a flight (world, seed, duration_s, start, trajectory, sensors, ...) from
/// `r` without rejecting the others; `dir` resolves a relative MJCF world path.
void readFlightKeys(MapReader& r, const std::filesystem::path& dir, FlightSpec& s);

}  // namespace msb
