// The method table of the YAML layer: one entry per exploration method — its `method.type`
// name, a one-line summary and the reader of its keys under `method:` (strict: keys of another
// method are unknown keys). Each reader converts and validates the method's config and returns
// the MethodChoice of tools/loop/methods.h. Adding a method: its folder under core/, one
// function in tools/loop/methods.cc, one reader and one line here.
#pragma once

#include <string>
#include <vector>

#include "tools/loop/methods.h"
#include "tools/config/yaml_reader.h"

namespace msb {

/// One registered method.
struct MethodEntry {
  const char* type;      ///< `method.type`
  const char* summary;   ///< for help texts and errors
  MethodChoice (*read)(MapReader& method);  ///< reads the keys under `method:` (except `type`) and finishes
};

/// All methods, in the order they are listed.
const std::vector<MethodEntry>& methodTable();

/// Reads `method:` (type and the type's keys); an unknown type names the known ones.
MethodChoice readMethod(MapReader method);

/// The MonoSpheres mapper keys (shared with map-replay's --set map.KEY=VALUE); the caller
/// finishes the reader.
void readSphereMapKeys(MapReader& r, SphereMapConfig& c);

}  // namespace msb
