// The only place where YAML meets configuration structs. Unknown keys, wrong types, missing
// files and invalid values all throw FileConfigError, whose message names the file, the key
// and the reason; nothing is written before a file has loaded completely.
#pragma once

#include <stdexcept>
#include <string>

#include "tools/msbench/flight_spec.h"

namespace msb {

/// A configuration problem in a named file (message: "FILE: key 'k': reason").
class FileConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Loads and validates a flight file for `msbench fly`. Relative paths inside resolve
/// against the file's directory.
FlightSpec loadFlightSpec(const std::string& path);

}  // namespace msb
