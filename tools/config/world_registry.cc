#include "tools/config/world_registry.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "core/common/config_check.h"
#include "tools/config/flight_yaml.h"
#include "tools/config/yaml_reader.h"

namespace msb {

namespace fs = std::filesystem;

std::string worldsDir() {
  const char* env = std::getenv("MSBENCH_WORLDS_DIR");
  return env && *env ? env : MSB_WORLDS_DIR;
}

std::string worldCacheDir() {
  const char* env = std::getenv("MSBENCH_CACHE_DIR");
  return env && *env ? std::string(env) : (fs::path(worldsDir()) / ".cache").string();
}

namespace {

void readObject(MapReader& r, ObjectGroupSpec& o) {
  r.read("kind", o.kind);
  r.read("count", o.count);
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
  if (r.read("size", size)) o.size_min = o.size_max = size;
  r.read("size_min", o.size_min);
  r.read("size_max", o.size_max);
  r.read("variant", o.variant);
  r.read("texture", o.texture);
  r.read("tilt_max_deg", o.tilt_max_deg);
  r.read("burned_fraction", o.burned_fraction);
  r.read("burned_texture", o.burned_texture);
  r.read("base_z_m", o.base_z_m);
  r.read("near", o.near);
  r.finish();
}

void readCave(MapReader r, CaveSpec& c) {
  readVec2(r, "min", c.min);
  readVec2(r, "max", c.max);
  r.read("rock_top_m", c.rock_top_m);
  r.read("cell_m", c.cell_m);
  r.read("texture", c.texture);
  if (r.has("chambers"))
    r.forEachInList("chambers", [&](MapReader& m) {
      CaveChamberSpec ch;
      readVec2(m, "min", ch.min);
      readVec2(m, "max", ch.max);
      m.read("ceiling_m", ch.ceiling_m);
      m.finish();
      c.chambers.push_back(ch);
    });
  if (r.has("tunnels"))
    r.forEachInList("tunnels", [&](MapReader& m) {
      CaveTunnelSpec t;
      readVec2(m, "from", t.from);
      readVec2(m, "to", t.to);
      m.read("width_m", t.width_m);
      m.read("ceiling_m", t.ceiling_m);
      m.finish();
      c.tunnels.push_back(t);
    });
  r.finish();
}

void readWorld(MapReader& r, WorldSpec& s) {
  r.read("name", s.name);
  r.read("description", s.description);
  r.read("seed", s.seed);
  if (r.has("ground")) {
    MapReader g = r.sub("ground");
    if (g.has("size_m")) readVec2(g, "size_m", s.ground_size_m);
    g.read("texture", s.ground_texture);
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
  r.read("start_clearance_m", s.start_clearance_m);
  r.read("start_corridor_m", s.start_corridor_m);
  r.read("start_corridor_half_width_m", s.start_corridor_half_width_m);
  r.read("texture_px", s.texture_px);
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

ResolvedWorld resolveWorld(const std::string& arg, std::optional<uint64_t> seed) {
  ResolvedWorld out;
  if (fs::is_regular_file(arg) && fs::path(arg).extension() == ".xml") {
    out.world_xml = fs::absolute(arg).string();
    return out;
  }
  const std::vector<WorldEntry> worlds = listWorlds();
  for (const auto& w : worlds) {
    if (w.name != arg && w.path != arg) continue;
    if (!w.generated) {
      out.world_xml = w.path;
      return out;
    }
    WorldSpec spec = loadWorldSpec(w.path);
    if (seed) spec.seed = *seed;
    try {
      out.built = buildWorld(spec, worldCacheDir());
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
  if (spec.world_name.empty()) return std::nullopt;
  try {
    ResolvedWorld w = resolveWorld(spec.world_name);
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
  if (std::optional<BuiltWorld> built = resolveFlightWorld(file, spec.flight)) {
    if (spec.start_from_world) {
      spec.flight.start_position_m = built->generated.start.translation();
      spec.flight.start_yaw_rad = yawOf(built->generated.start.linear());
    }
    w.box = built->generated.exploration_box;
    w.truth.emplace(built->generated.shapes);
  }
  if (spec.exploration_box) w.box = *spec.exploration_box;
  return w;
}

}  // namespace msb
