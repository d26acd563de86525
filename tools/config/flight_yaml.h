// Flight files for `msbench fly` and `vio-eval` (tools/config is the only place where YAML meets
// configuration structs). Unknown keys, wrong types, missing
// files and invalid values all throw FileConfigError, whose message names the file, the key
// and the reason; nothing is written before a file has loaded completely.
#pragma once

#include <filesystem>
#include <string>

#include "tools/engine/flight_spec.h"

namespace msb {

/// Loads and validates a flight file for `msbench fly`. Relative paths inside resolve
/// against the file's directory.
FlightSpec loadFlightSpec(const std::string& path);

}  // namespace msb
