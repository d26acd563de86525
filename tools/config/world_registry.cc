#include "tools/config/world_registry.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "core/common/config_check.h"
#include "core/common/input_file.h"
#include "tools/config/field_keys.h"
#include "tools/config/flight_yaml.h"
#include "tools/config/yaml_reader.h"

namespace msb {

namespace fs = std::filesystem;

std::string worldsDir() {
  const char* env = std::getenv("MSBENCH_WORLDS_DIR");
  return env && *env ? env : MSB_WORLDS_DIR;
}

std::string resultsDir() {
  const char* env = std::getenv("MSBENCH_RESULTS_DIR");
  return env && *env ? std::string(env) : (fs::path(MSB_WORLDS_DIR).parent_path() / "results").string();
}

std::string worldCacheDir() {
  const char* env = std::getenv("MSBENCH_CACHE_DIR");
  return env && *env ? std::string(env) : (fs::path(worldsDir()) / ".cache").string();
}

std::string worldSourcesDir(const std::string& name) { return (fs::path(worldCacheDir()) / "sources" / name).string(); }

namespace {

// Throws "is required" for each of `keys` missing from `r` (a key a table reads as optional).
void requireKeys(const MapReader& r, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (!r.has(k)) throw ConfigError(r.keyName(k), "is required");
}

// An object group: its table, then the optional and shorthand keys.
void readObject(MapReader& r, ObjectGroupSpec& o) {
  fieldKeys(r, o);
  if (r.has("at")) {
    Vec2 at;
    readVec2(r, "at", at);
    o.at = at;
  }
  if (r.has("region")) {
    MapReader reg = r.sub("region");
    Vec2 mn, mx;
    readVec2(reg, "min", mn);
    readVec2(reg, "max", mx);
    reg.finish();
    o.region_min = mn, o.region_max = mx;
  }
  double yaw;
  if (r.read("yaw_deg", yaw)) o.yaw_deg = yaw;
  Vec3 size;
  // `size` sets both ends of the range unless size_min / size_max are given.
  if (r.read("size", size)) {
    if (!r.has("size_min")) o.size_min = size;
    if (!r.has("size_max")) o.size_max = size;
  }
  r.finish();
}

// The cave: its table, and its lists of chambers and tunnels, each element by its own table.
void readCave(MapReader r, CaveSpec& c) {
  requireKeys(r, {"min", "max"});
  fieldKeys(r, c);
  if (r.has("chambers"))
    r.forEachInList("chambers", [&](MapReader& m) {
      requireKeys(m, {"min", "max"});
      CaveChamberSpec ch;
      fieldKeys(m, ch);
      m.finish();
      c.chambers.push_back(ch);
    });
  if (r.has("tunnels"))
    r.forEachInList("tunnels", [&](MapReader& m) {
      requireKeys(m, {"from", "to"});
      CaveTunnelSpec t;
      fieldKeys(m, t);
      m.finish();
      c.tunnels.push_back(t);
    });
  r.finish();
}

void readWorld(MapReader& r, WorldSpec& s) {
  fieldKeys(r, s);
  if (r.has("ground")) {
    MapReader g = r.sub("ground");
    if (g.has("size_m")) readVec2(g, "size_m", s.ground_size_m);
    g.read("texture", s.ground_texture);
    g.read("enabled", s.ground_enabled);
    g.finish();
  }
  if (r.has("start")) {
    MapReader st = r.sub("start");
    st.read("position", s.start_position_m);
    st.read("yaw_deg", s.start_yaw_deg);
    st.finish();
  }
  if (r.has("exploration_box")) {
    MapReader b = r.sub("exploration_box");
    b.read("min", s.exploration_box.min);
    b.read("max", s.exploration_box.max);
    b.finish();
  }
  if (r.has("objects"))
    r.forEachInList("objects", [&](MapReader& m) {
      ObjectGroupSpec o;
      readObject(m, o);
      s.objects.push_back(o);
    });
  if (r.has("cave")) {
    CaveSpec c;
    readCave(r.sub("cave"), c);
    s.cave = c;
  }
  // Imported meshes and where they come from, each by its own table.
  if (r.has("source")) {
    MapReader src = r.sub("source");
    SourceSpec so;
    fieldKeys(src, so);
    src.finish();
    s.source = so;
  }
  if (r.has("meshes"))
    r.forEachInList("meshes", [&](MapReader& m) {
      requireKeys(m, {"file"});
      MeshSpec ms;
      fieldKeys(m, ms);
      m.finish();
      s.meshes.push_back(ms);
    });
  r.finish();
}

}  // namespace

WorldSpec loadWorldSpec(const std::string& path) {
  return parseConfigFile<WorldSpec>(path, [](MapReader& r, WorldSpec& s) { readWorld(r, s); });
}

std::vector<WorldEntry> listWorlds() {
  std::vector<WorldEntry> out;
  const fs::path dir = worldsDir();
  if (!fs::is_directory(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_directory()) continue;
    const std::string name = e.path().filename();
    if (fs::is_regular_file(e.path() / "spec.yaml")) {
      std::string desc;
      try {
        desc = loadWorldSpec((e.path() / "spec.yaml").string()).description;
      } catch (const std::exception& ex) {
        desc = std::string("(invalid spec: ") + ex.what() + ")";
      }
      out.push_back({name, desc, (e.path() / "spec.yaml").string(), true});
    } else if (fs::is_regular_file(e.path() / "world.xml")) {
      out.push_back({name, "hand-written MJCF world", (e.path() / "world.xml").string(), false});
    }
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return out;
}

std::string heldOutSalt() {
  const char* text = std::getenv("MSBENCH_WORLD_SALT");
  const char* file = std::getenv("MSBENCH_WORLD_SALT_FILE");
  std::string salt, from = "$MSBENCH_WORLD_SALT";
  if (text && *text) {
    salt = text;
  } else if (file && *file) {
    from = "$MSBENCH_WORLD_SALT_FILE (" + std::string(file) + ")";
    // A regular file of at most kMaxSaltFileBytes, opened without blocking: a FIFO, a device or
    // 1 GiB of zeros is refused at once, before anything is read.
    try {
      salt = readInputFile(file, InputLimits{kMaxSaltFileBytes});
    } catch (const InputFileError& e) {
      throw InputFileError("$MSBENCH_WORLD_SALT_FILE: " + std::string(e.what()));
    }
    salt = salt.substr(0, salt.find('\n'));
  } else {
    throw std::runtime_error(
        "a held-out world needs the evaluator's salt: set $MSBENCH_WORLD_SALT or "
        "$MSBENCH_WORLD_SALT_FILE (at least " +
        std::to_string(kMinSaltChars) + " characters, e.g. `head -c 16 /dev/urandom | xxd -p`)");
  }
  while (!salt.empty() && (salt.back() == '\r' || salt.back() == ' ')) salt.pop_back();
  if (salt.size() < kMinSaltChars)
    throw std::runtime_error(from + " holds " + std::to_string(salt.size()) + " characters; a salt needs at least " +
                             std::to_string(kMinSaltChars));
  return salt;
}

ResolvedWorld resolveWorld(const std::string& arg, std::optional<uint64_t> seed, const std::string& salt) {
  ResolvedWorld out;
  if (fs::is_regular_file(arg) && fs::path(arg).extension() == ".xml") {
    if (!salt.empty())
      throw std::runtime_error("world '" + arg + "' is an MJCF file: only a generated world is held out");
    out.world_xml = fs::absolute(arg).string();
    return out;
  }
  const std::vector<WorldEntry> worlds = listWorlds();
  for (const auto& w : worlds) {
    if (w.name != arg && w.path != arg) continue;
    if (!w.generated) {
      if (!salt.empty())
        throw std::runtime_error("world '" + arg + "' is hand-written MJCF: only a generated world is held out");
      out.world_xml = w.path;
      return out;
    }
    WorldSpec spec = loadWorldSpec(w.path);
    if (seed) spec.seed = *seed;
    spec.source_dir = worldSourcesDir(spec.name);
    WorldSalting salting;
    if (!salt.empty()) spec = saltWorldSpec(spec, salt, &salting);
    try {
      out.built = buildWorld(spec, worldCacheDir());
      out.built->salting = salting;
    } catch (const ConfigError& e) {
      throw FileConfigError(w.path + ": " + e.what());
    }
    out.world_xml = out.built->world_xml;
    return out;
  }
  std::string names;
  for (const auto& w : worlds) names += (names.empty() ? "" : ", ") + w.name;
  throw UsageError("world '" + arg + "': no such file and no world of that name in " + worldsDir() +
                   " (available: " + (names.empty() ? "none" : names) + ")");
}

}  // namespace msb

namespace msb {

std::optional<BuiltWorld> resolveFlightWorld(const std::string& file, FlightSpec& spec) {
  std::string salt;
  if (spec.held_out) {
    try {
      if (spec.world_name.empty()) throw std::runtime_error("an MJCF file is never held out: name a generated world");
      salt = heldOutSalt();
    } catch (const std::runtime_error& e) {
      throw FileConfigError(file + ": key 'held_out': " + e.what());
    }
  }
  if (spec.world_name.empty()) return std::nullopt;
  try {
    ResolvedWorld w = resolveWorld(spec.world_name, std::nullopt, salt);
    spec.world_path = w.world_xml;
    return w.built;
  } catch (const std::runtime_error& e) {
    throw FileConfigError(file + ": key 'world': " + e.what());
  }
}

MissionWorld prepareMissionWorld(const std::string& file, ScenarioSpec& spec) {
  MissionWorld w;
  w.box.min = Vec3::Constant(-1e6);
  w.box.max = Vec3::Constant(1e6);
  const WorldSalting* salting = nullptr;
  std::optional<BuiltWorld> built = resolveFlightWorld(file, spec.flight);
  if (built) {
    salting = &built->salting;
    if (spec.start_from_world) {
      spec.flight.start_position_m = built->generated.start.translation();
      spec.flight.start_yaw_rad = yawOf(built->generated.start.linear());
    } else if (salting->mirrored) {  // the scenario's own start, mirrored with its world
      spec.flight.start_position_m.head<2>() = salting->point(spec.flight.start_position_m.head<2>());
      spec.flight.start_yaw_rad = salting->yaw(spec.flight.start_yaw_rad);
    }
    w.box = built->generated.exploration_box;
    w.truth.emplace(built->generated.shapes);
    spec.paper_world = built->generated.paper_world;
    if (spec.flight.held_out) spec.world_salt_commitment = worldSaltCommitment(heldOutSalt());
  }
  if (spec.exploration_box) w.box = salting ? salting->box(*spec.exploration_box) : *spec.exploration_box;
  return w;
}

}  // namespace msb
