// The reference of every configuration key (`msbench keys`, docs/keys.md): each key of a scenario
// and of each method's `method:` section with its default and the values it accepts, generated
// from the key tables (core/common/config_fields.h) through the YAML writer, so that the
// reference, the reader and the validation cannot disagree.
#pragma once

#include <string>
#include <vector>

namespace msb {

/// One key of the reference.
struct KeyRow {
  std::string section;        ///< "scenario" or "method.type: TYPE"
  std::string key;            ///< dotted path, e.g. "physics.vehicle.mass_kg", "method.map.r_max_m"
  std::string default_value;  ///< as written in config.yaml ("" for keys without a default)
  std::string accepts;        ///< the values it accepts ("" if no rule says: a number without one)
  std::string refused_value;  ///< a YAML value the key refuses ("" if none of its type is)
  bool from_table = true;     ///< false: read outside the key tables (a name, a list, a preset)
};

/// Every key: the scenario's (flight, mission, video), then each registered method's.
std::vector<KeyRow> keyReference();

/// The reference as the Markdown of docs/keys.md.
std::string keyReferenceMarkdown();

}  // namespace msb
