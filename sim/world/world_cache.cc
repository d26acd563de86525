#include "sim/world/world_cache.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/common/png.h"
#include "core/common/wall_time.h"

#include "core/common/rng.h"
#include "sim/world/procedural_textures.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

// Writes a file of the world being built, checked through close (a full disk shows at close).
void writeBytes(const fs::path& p, const std::string& bytes) {
  errno = 0;
  std::ofstream out(p, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out)
    throw std::runtime_error(p.string() + ": write failed" + (errno ? std::string(": ") + std::strerror(errno) : ""));
}

std::string shapesCsv(const std::vector<Shape>& shapes) {
  std::string s = "name,object,kind,type,x,y,z,qw,qx,qy,qz,sx,sy,sz\n";
  char line[512];
  for (const auto& sh : shapes) {
    const Quat q(sh.pose.linear());
    const char* type = sh.type == ShapeType::kBox        ? "box"
                       : sh.type == ShapeType::kCylinder ? "cylinder"
                       : sh.type == ShapeType::kSphere   ? "sphere"
                       : sh.type == ShapeType::kConvex   ? "convex"
                                                         : "halfspace";
    std::snprintf(line, sizeof(line), "%s,%s,%s,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                  sh.name.c_str(), sh.object.c_str(), obstacleKindName(sh.kind), type, sh.pose.translation().x(),
                  sh.pose.translation().y(), sh.pose.translation().z(), q.w(), q.x(), q.y(), q.z(), sh.size.x(),
                  sh.size.y(), sh.size.z());
    s += line;
  }
  return s;
}

// Temporary build directories of `name` that a process now gone left behind (killed while it
// built): removed, so the cache does not collect them.
void removeStaleTemporaries(const fs::path& cache_root, const std::string& name) {
  std::error_code ec;
  const std::string prefix = ".tmp-" + name + "-";
  for (const auto& e : fs::directory_iterator(cache_root, ec)) {
    const std::string f = e.path().filename().string();
    if (f.rfind(prefix, 0) != 0) continue;
    const std::string pid_text = f.substr(prefix.size());
    if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(pid_text);
    if (pid != ::getpid() && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH) fs::remove_all(e.path(), ec);
  }
}

// Writes the world's files into `tmp` and renames it to `dir` (another process may have built
// it first). On any failure the temporary directory is removed and the error names the cache.
void writeWorldDirectory(const GeneratedWorld& g, int texture_px, uint64_t texture_seed, const fs::path& tmp,
                         const fs::path& dir) {
  try {
    fs::remove_all(tmp);
    fs::create_directories(tmp / "textures");
    for (const auto& t : g.textures)
      writeBytes(tmp / "textures" / (t + ".png"), encodePng(viewOf(makeTexture(t, texture_px, texture_seed))));
    for (const auto& [name, png] : g.image_textures) writeBytes(tmp / "textures" / (name + ".png"), png);
    writeBytes(tmp / "shapes.csv", shapesCsv(g.shapes));
    writeBytes(tmp / "world.xml", g.mjcf);
  } catch (const std::exception& e) {
    std::error_code ec;
    fs::remove_all(tmp, ec);
    throw std::runtime_error(dir.string() + ": could not write the world cache: " + e.what());
  }
  std::error_code ec;
  fs::rename(tmp, dir, ec);
  if (ec) fs::remove_all(tmp, ec);  // another process built it first
}

}  // namespace

BuiltWorld buildWorld(const WorldSpec& spec, const std::string& cache_root) {
  const auto t0 = WallClock::now();
  BuiltWorld out;
  out.generated = generateWorld(spec);

  // Cache key: generator version, texture size (and seed, when not the world's own) and the
  // generated MJCF text.
  const std::string key_text = std::to_string(kWorldGeneratorVersion) + "|" + std::to_string(spec.texture_px) +
                               (spec.texture_seed ? "|t" + std::to_string(spec.texture_seed) : std::string()) + "|" +
                               out.generated.mjcf;
  char key[17];
  std::snprintf(key, sizeof(key), "%016llx",
                static_cast<unsigned long long>(fnv1a64(key_text.data(), key_text.size())));
  const fs::path dir = fs::path(cache_root) / (spec.name + "-s" + std::to_string(spec.seed) + "-" + key);
  out.directory = dir.string();
  out.world_xml = (dir / "world.xml").string();

  if (!fs::is_regular_file(dir / "world.xml")) {
    removeStaleTemporaries(cache_root, spec.name);
    const fs::path tmp = fs::path(cache_root) / (".tmp-" + spec.name + "-" + std::to_string(::getpid()));
    writeWorldDirectory(out.generated, spec.texture_px, spec.texture_seed, tmp, dir);
    if (!fs::is_regular_file(dir / "world.xml"))
      throw std::runtime_error(dir.string() + ": could not write the world cache");
  } else {
    out.reused = true;
  }
  out.build_seconds = secondsSince(t0);
  return out;
}

}  // namespace msb
