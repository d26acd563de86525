// The `method:` section of a scenario, read and written through the one registry of methods
// (core/explorer/method_registry.h): the type, then the keys of the type's registration (strict:
// keys of another method are unknown keys), validated with their `method.` names; the run's
// choice is made from the registration (registeredMethodChoice, tools/engine/methods.h). Every
// method registers itself from its own folder (docs/architecture.md, "How to add an exploration
// method"), `python` (methods written in Python) included; nothing here names a method.
#pragma once

#include <memory>
#include <string>

#include "core/explorer/method_registry.h"
#include "tools/config/yaml_reader.h"
#include "tools/config/yaml_writer.h"
#include "tools/engine/methods.h"

namespace msb {

struct SphereMapConfig;  // MonoSpheres' mapper settings (core/methods/monospheres/map/sphere_map.h)

/// Reads `method:` (type and the type's keys); an unknown type names the known ones.
MethodChoice readMethod(MapReader method);

/// Writes `method.type` and every key of the method's config (defaults included).
void writeMethod(MapWriter& w, const MethodChoice& method);

/// Every key of method `type` with its default, as the YAML of a scenario's `method:` section
/// (`msbench methods`). Throws ConfigError for an unknown type (naming the known ones).
/// With `log`, each key's accepted values are also recorded there (paths "method.KEY").
std::string methodDefaultsYaml(const std::string& type, std::shared_ptr<MapWriter::KeyLog> log = nullptr);

/// The MonoSpheres mapper keys (shared with map-replay's --set map.KEY=VALUE); the caller
/// finishes the reader.
void readSphereMapKeys(MapReader& r, SphereMapConfig& c);

}  // namespace msb
