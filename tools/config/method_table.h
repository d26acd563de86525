// The method table: one entry per exploration method — its `method.type` name (written only
// there), a one-line summary, the reader and writer of its keys under `method:` (one keys
// function serves both; strict: keys of another method are unknown keys), the factory (through
// methodChoice<Explorer>() of tools/loop/methods.h) and the Table I rows it answers to. How a
// method's free space is drawn and scored comes from its free-space geometry, not its name.
// Every method registers itself from its own folder (core/explorer/method_registry.h;
// docs/architecture.md, "How to add an exploration method"); only `python`, the door for methods
// written in Python, is listed here.
#pragma once

#include <any>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/explorer/method_registry.h"
#include "tools/config/yaml_reader.h"
#include "tools/config/yaml_writer.h"
#include "tools/loop/methods.h"

namespace msb {

struct SphereMapConfig;  // MonoSpheres' mapper settings (core/methods/monospheres/map/sphere_map.h)

/// One registered method.
struct MethodEntry {
  const char* type;                                     ///< `method.type`
  const char* summary;                                  ///< for help texts and errors
  std::function<MethodChoice(MapReader& method)> read;  ///< reads the keys under `method:` (except `type`) and finishes
  std::function<void(const std::any& config, MapWriter& method)> write;  ///< writes every key of its config
  std::vector<PaperRow> paper_rows;            ///< the Table I rows it answers to (none: not in the paper)
  std::vector<std::string> progress_counters;  ///< the counters the progress line shows, in order
  /// Gives `explorer` (one this entry made) the chooser of `choosers` that fits it; null: the
  /// method takes no outside goal chooser.
  std::function<void(Explorer& explorer, const GoalChoosers& choosers)> attach_goal_chooser;
};

/// All methods, in the order they are listed.
const std::vector<MethodEntry>& methodTable();

/// The method table's entry of `type`, or null.
const MethodEntry* findMethod(const std::string& type);

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
