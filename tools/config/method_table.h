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

/// A row of the paper's Table I that a method answers to (mean and max A over its runs, m²).
struct PaperRow {
  const char* world;           ///< urban, cave, rooftops, sparse
  const char* switched_off;    ///< "" for the full method, else the one switch an ablation turns off
  double mean_area_m2, max_area_m2;
};

/// One registered method.
struct MethodEntry {
  const char* type;      ///< `method.type`
  const char* summary;   ///< for help texts and errors
  MethodChoice (*read)(MapReader& method);  ///< reads the keys under `method:` (except `type`) and finishes
  std::vector<PaperRow> paper_rows;         ///< the Table I rows it answers to (none: not in the paper)
};

/// All methods, in the order they are listed.
const std::vector<MethodEntry>& methodTable();

/// The method table's entry of `type`, or null.
const MethodEntry* findMethod(const std::string& type);

/// Reads `method:` (type and the type's keys); an unknown type names the known ones.
MethodChoice readMethod(MapReader method);

/// The MonoSpheres mapper keys (shared with map-replay's --set map.KEY=VALUE); the caller
/// finishes the reader.
void readSphereMapKeys(MapReader& r, SphereMapConfig& c);

}  // namespace msb
