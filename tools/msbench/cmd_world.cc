// msbench world list | build | show: the benchmark worlds, their cache and previews.
#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "core/common/png.h"
#include "core/common/rng.h"
#include "core/common/strict_number.h"
#include "core/common/wall_time.h"
#include "core/geometry/shape_mesh.h"
#include "sim/physics/mjcf_files.h"
#include "sim/physics/quadrotor_sim.h"
#include "sim/render/fisheye_renderer.h"
#include "tools/config/world_registry.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/interrupt.h"
#include "tools/results/input_files.h"
#include "tools/results/output_files.h"
#include "tools/results/ply_files.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

std::optional<uint64_t> seedArg(const ArgParser& args) {
  if (!args.given("seed")) return std::nullopt;
  uint64_t s;
  std::string why;
  if (!parseUnsigned(args.get("seed"), &s, &why)) throw UsageError("--seed: " + why);
  return s;
}

const BuiltWorld& requireGenerated(const ResolvedWorld& w, const std::string& name) {
  if (!w.built) throw UsageError("world '" + name + "' is a hand-written MJCF world, not generated");
  return *w.built;
}

// BGR colour of an obstacle kind in the top-down map.
cv::Vec3b kindColour(ObstacleKind k) {
  switch (k) {
    case ObstacleKind::kTextured:
      return {90, 150, 60};  // green-ish: textured
    case ObstacleKind::kTextureless:
      return {40, 40, 220};  // red: textureless
    case ObstacleKind::kThin:
      return {220, 40, 220};  // magenta: thin
    case ObstacleKind::kGround:
      return {120, 120, 120};  // grey: cave rock/ceiling
  }
  return {0, 0, 0};
}

// Top-down map: a downward ray per pixel from the top of the exploration box; obstacles coloured
// by kind and shaded by height; exploration box, 2.5 m grid and start pose on top.
// The area the top-down map shows: the exploration box and every object, 5 m around.
std::pair<Vec2, Vec2> topDownExtent(const GeneratedWorld& g) {
  Vec2 lo = g.exploration_box.min.head<2>(), hi = g.exploration_box.max.head<2>();
  for (const auto& s : g.shapes) {
    if (s.type == ShapeType::kHalfSpace) continue;
    const auto [mn, mx] = s.bounds();
    lo = lo.cwiseMin(mn.head<2>()), hi = hi.cwiseMax(mx.head<2>());
  }
  lo.array() -= 5, hi.array() += 5;
  return {lo, hi};
}

cv::Mat renderTopDown(const BuiltWorld& w, double m_per_px) {
  const auto& g = w.generated;
  const WorldTruth truth(g.shapes);
  const auto [lo, hi] = topDownExtent(g);
  const int W = int((hi.x() - lo.x()) / m_per_px), H = int((hi.y() - lo.y()) / m_per_px);
  cv::Mat img(H, W, CV_8UC3, cv::Scalar(235, 235, 235));
  const double z_top = g.exploration_box.max.z() - 0.01;
  auto px = [&](const Vec2& p) {
    return cv::Point(int((p.x() - lo.x()) / m_per_px), int((hi.y() - p.y()) / m_per_px));
  };
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const Vec3 o(lo.x() + (u + 0.5) * m_per_px, hi.y() - (v + 0.5) * m_per_px, z_top);
      // Down to 1 m below the box (its floor is the ground, or an imported terrain's low point).
      const double z_low = g.exploration_box.min.z();
      const auto hit = truth.raycast(o, Vec3(0, 0, -1), z_top - z_low + 1.0);
      if (!hit || g.shapes[hit->shape].type == ShapeType::kHalfSpace) continue;  // open ground
      const double height = z_top - hit->distance_m - z_low;
      const double shade = 0.55 + 0.45 * std::clamp(height / (z_top - z_low), 0.0, 1.0);
      const cv::Vec3b c = kindColour(g.shapes[hit->shape].kind);
      img.at<cv::Vec3b>(v, u) = cv::Vec3b(uchar(c[0] * shade), uchar(c[1] * shade), uchar(c[2] * shade));
    }
  // 2.5 m grid and exploration box.
  const Aabb& box = g.exploration_box;
  for (double x = box.min.x(); x <= box.max.x() + 1e-9; x += 2.5)
    cv::line(img, px({x, box.min.y()}), px({x, box.max.y()}), cv::Scalar(200, 200, 200), 1);
  for (double y = box.min.y(); y <= box.max.y() + 1e-9; y += 2.5)
    cv::line(img, px({box.min.x(), y}), px({box.max.x(), y}), cv::Scalar(200, 200, 200), 1);
  cv::rectangle(img, px(box.min.head<2>()), px(box.max.head<2>()), cv::Scalar(200, 120, 0), 2);
  // Thin obstacles are narrower than a pixel: mark each with a small disc.
  for (const auto& sh : g.shapes)
    if (sh.kind == ObstacleKind::kThin) {
      const cv::Vec3b c = kindColour(ObstacleKind::kThin);
      cv::circle(img, px(sh.pose.translation().head<2>()), 3, cv::Scalar(c[0], c[1], c[2]), -1);
    }
  // Start pose.
  const Vec2 s = g.start.translation().head<2>();
  const Vec2 f = s + 4.0 * g.start.linear().col(0).head<2>().normalized();
  cv::circle(img, px(s), int(1.0 / m_per_px) + 2, cv::Scalar(0, 140, 255), -1);
  cv::arrowedLine(img, px(s), px(f), cv::Scalar(0, 140, 255), 2);
  // Legend.
  const char* labels[] = {"textured", "textureless", "thin", "rock/ceiling"};
  const ObstacleKind kinds[] = {ObstacleKind::kTextured, ObstacleKind::kTextureless, ObstacleKind::kThin,
                                ObstacleKind::kGround};
  for (int i = 0; i < 4; ++i) {
    const cv::Vec3b c = kindColour(kinds[i]);
    cv::rectangle(img, cv::Rect(8, 8 + 18 * i, 14, 14), cv::Scalar(c[0], c[1], c[2]), -1);
    cv::putText(img, labels[i], cv::Point(28, 20 + 18 * i), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(30, 30, 30), 1);
  }
  cv::putText(img, g.name + "  (orange: start, blue: exploration box, grid 2.5 m)", cv::Point(8, H - 10),
              cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(30, 30, 30), 1);
  return img;
}

// Fisheye views from 1.5 m above the start at four headings, in a 2x2 mosaic.
cv::Mat startViews(const BuiltWorld& w) {
  const Pose start = w.generated.start * poseFromXyzYaw(Vec3(0, 0, 1.5), 0.0);
  QuadrotorSim sim(PhysicsConfig{}, w.world_xml, start);
  sim.beginTick();
  const FisheyeCamera cam{FisheyeCameraConfig{}};
  FisheyeRenderer renderer(FisheyeRendererConfig{}, cam, sim.model());
  cv::Mat mosaic(2 * cam.height(), 2 * cam.width(), CV_8UC1);
  for (int k = 0; k < 4; ++k) {
    throwIfInterrupted();  // between views: the staging directory goes with the exception
    CameraFrame f;
    renderer.render(sim.data(), start * poseFromXyzYaw(Vec3::Zero(), k * M_PI / 2) * cam.T_B_C(), &f);
    cv::Mat(f.height, f.width, CV_8UC1, f.pixels.data())
        .copyTo(mosaic(cv::Rect((k % 2) * cam.width(), (k / 2) * cam.height(), cam.width(), cam.height())));
  }
  return mosaic;
}

// msbench world list.
int worldList(int argc, char** argv) {
  ArgParser args("msbench world list", "List the worlds.");
  if (!args.parse(argc - 1, argv + 1)) return kExitOk;
  for (const auto& w : listWorlds())
    std::printf("%-10s %-9s %s\n", w.name.c_str(), w.generated ? "generated" : "mjcf", w.description.c_str());
  return kExitOk;
}

// What each imported mesh of a world became: nodes and their pieces, images, stand-ins.
void printMeshReports(const std::vector<MeshBuildReport>& meshes) {
  for (const MeshBuildReport& m : meshes) {
    std::printf("  mesh %s: %zu triangles\n", m.file.c_str(), m.triangles);
    for (const auto& [node, what] : m.nodes) std::printf("    %-24s %s\n", node.c_str(), what.c_str());
    for (const std::string& i : m.images) std::printf("    image %s\n", i.c_str());
    for (const std::string& i : m.stand_ins)
      std::printf("    image %s: absent from the imported source, drawn as the spec's missing_texture\n", i.c_str());
  }
}

// The spec of a generated world named `name` (a usage error otherwise).
WorldSpec generatedWorldSpec(const std::string& name) {
  for (const auto& w : listWorlds())
    if (w.name == name) {
      if (!w.generated) throw UsageError("world '" + name + "' is a hand-written MJCF world: it imports nothing");
      return loadWorldSpec(w.path);
    }
  throw UsageError("world '" + name + "': no world of that name in " + worldsDir());
}

// A directory `world import` may replace: empty, or an import msbench wrote (its marker; an
// import from before the marker: no marker and an imported.json that is an import's record).
bool isReplaceableImport(const fs::path& dir) {
  if (fs::is_empty(dir) || isMsbenchOutput(dir, OutputKind::kWorldImport)) return true;
  if (fs::exists(fs::symlink_status(dir / ".msbench-output"))) return false;
  try {
    const nlohmann::json j = readJsonFile(dir / "imported.json", InputLimits{size_t(1) << 20});
    return j.is_object() && j.contains("repository") && j.contains("files") && j["files"].is_array();
  } catch (const InputFileError&) {
    return false;
  }
}

// The checkout's file `rel` (a path inside it) as a regular file that resolves inside the
// checkout (`root`, canonical): a link out of it, a link to nothing, a FIFO, device or directory
// is bad input naming the file and why. Nothing at the path: false.
bool checkoutFileOk(const fs::path& root, const std::string& rel) {
  const fs::path p = root / rel;
  if (!fs::exists(fs::symlink_status(p))) return false;
  std::error_code ec;
  const fs::path real = fs::canonical(p, ec);
  if (ec) throw UsageError("--from: " + p.string() + ": a link to nothing (" + ec.message() + ")");
  const fs::path inside = real.lexically_relative(root);
  if (inside.empty() || *inside.begin() == "..")
    throw UsageError("--from: " + p.string() + ": resolves to " + real.string() +
                     ", outside the checkout; only the checkout's own files are imported");
  const fs::file_status st = fs::status(real);
  if (!fs::is_regular_file(st))
    throw UsageError("--from: " + p.string() + ": is " +
                     (fs::is_directory(st)                                 ? "a directory"
                      : fs::is_fifo(st)                                    ? "a FIFO"
                      : fs::is_character_file(st) || fs::is_block_file(st) ? "a device"
                                                                           : "not a regular file") +
                     ", not a regular file");
  return true;
}

// The files to import: the spec's meshes (each checked before assimp reads it), then the images
// they name (checked; one that is absent is listed in `missing`).
std::vector<std::string> checkedSourceFiles(const WorldSpec& spec, const fs::path& root,
                                            std::vector<std::string>& missing) {
  for (size_t i = 0; i < spec.meshes.size(); ++i)
    if (!checkoutFileOk(root, spec.meshes[i].file))
      throw UsageError("--from " + root.string() + ": meshes[" + std::to_string(i) + "].file " + spec.meshes[i].file +
                       " is not in the checkout (a partial clone, or another repository?)");
  const std::vector<std::string> files = meshSourceFiles(spec, root.string(), missing);
  for (const std::string& f : files) checkoutFileOk(root, f);
  for (const std::string& f : missing) checkoutFileOk(root, f);  // something there that is no image
  return files;
}

// Removes what a killed import of `name` left in `parent` (its staging and replaced copies, each
// with msbench's marker); called with the import's lock held, so none is in use.
void clearStaleImports(const fs::path& parent, const std::string& name) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(parent, ec)) {
    const std::string f = e.path().filename().string();
    const bool ours = f.rfind(".tmp-" + name + "-", 0) == 0 || f.rfind(name + ".replaced-", 0) == 0;
    if (ours && e.is_directory() && isMsbenchOutput(e.path(), OutputKind::kWorldImport)) fs::remove_all(e.path(), ec);
  }
}

// The import under its lock: the files checked and copied into a staging directory, the world
// built from it, then the staging directory put in the target's place (replaceDirectory).
size_t importLocked(WorldSpec spec, const fs::path& root, const fs::path& target, const std::vector<fs::path>& made) {
  const std::string name = spec.name;
  const OutputLock lock(target, "world import " + name);
  clearStaleImports(target.parent_path(), name);
  const fs::path staging = target.parent_path() / (".tmp-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(staging);
  // Reading the meshes, copying and the check build write only into the staging directory: a
  // signal there ends the import at once (assimp and the mesh cutting have no safe points).
  std::optional<ExitOnInterrupt> watch(std::in_place, std::vector<fs::path>{staging, target.string() + ".lock"},
                                       "world", made);
  std::vector<std::string> missing;
  const std::vector<std::string> files = checkedSourceFiles(spec, root, missing);
  try {
    fs::create_directories(staging);
    writeOutputMarker(staging, OutputKind::kWorldImport);
    nlohmann::json list = nlohmann::json::array();
    for (const std::string& f : files) {
      fs::create_directories((staging / f).parent_path());
      copyInputFile(root / f, staging / f, throwIfInterrupted);
      list.push_back({{"file", f}, {"bytes", fs::file_size(staging / f)}});
    }
    spec.source_dir = staging.string();
    const GeneratedWorld g = generateWorld(spec);
    const nlohmann::json record = {{"repository", spec.source->repository},
                                   {"commit", spec.source->commit},
                                   {"from", root.string()},
                                   {"files", list},
                                   {"absent_images", missing}};
    writeFileAtomic(staging / "imported.json", record.dump(2) + "\n");
    watch.reset();
    throwIfInterrupted();
    replaceDirectory(staging, target);
    printMeshReports(g.meshes);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(staging, ec);
    throw;
  }
  return files.size();
}

// msbench world import NAME --from CHECKOUT: copies the files a world's meshes need (and the
// images they name) from a checkout of its source into the cache's sources/NAME/, after checking
// that the world builds from them. Staged beside the target and put in its place only when the
// world builds (the old import whole until then, and after any failure); only an import msbench
// wrote is replaced; only the checkout's regular files are copied (docs/worlds.md).
int worldImport(int argc, char** argv) {
  ArgParser args("msbench world import",
                 "Copy a world's meshes and their images from a checkout of its source into the world cache.");
  args.positional("NAME", "world name").option("from", "", "the checkout (a clone of the spec's source)", true);
  if (!args.parse(argc - 1, argv + 1)) return kExitOk;
  const std::string name = args.get("NAME"), checkout = args.get("from");
  WorldSpec spec = generatedWorldSpec(name);
  if (spec.meshes.empty()) throw UsageError("world '" + name + "' imports nothing (its spec has no meshes)");
  if (!fs::is_directory(checkout)) throw UsageError("--from " + checkout + ": not a directory");
  const fs::path root = fs::canonical(checkout);
  // The target: absent, empty or an import msbench wrote; anything else is the user's.
  const fs::path target = worldSourcesDir(name);
  if (fs::exists(fs::symlink_status(target))) {
    if (!fs::is_directory(fs::symlink_status(target)))
      throw UsageError(target.string() + ": exists and is not a directory; refusing to replace it");
    if (!isReplaceableImport(target))
      throw UsageError(target.string() + ": holds files msbench did not import (no import marker or record); " +
                       "refusing to replace it — move it away first");
  }
  // The cache's sources/ made for this import goes again if the import fails.
  const fs::path sources = target.parent_path();
  const bool made = !fs::exists(fs::symlink_status(sources));
  fs::create_directories(sources);
  size_t files = 0;
  try {
    files = importLocked(spec, root, target, made ? std::vector<fs::path>{sources} : std::vector<fs::path>{});
  } catch (...) {
    std::error_code ec;
    if (made) fs::remove(sources, ec);  // only if empty
    throw;
  }
  std::printf("world %s: %zu files imported from %s -> %s\n", name.c_str(), files, checkout.c_str(), target.c_str());
  return kExitOk;
}

// msbench world build NAME: generate (or reuse) and compile once in MuJoCo.
int worldBuild(int argc, char** argv) {
  ArgParser args("msbench world build", "Generate a world (MJCF, textures, shapes) into the cache.");
  args.positional("NAME", "world name").option("seed", "", "placement seed (default: the spec's)");
  if (!args.parse(argc - 1, argv + 1)) return kExitOk;
  const auto t0 = WallClock::now();
  const ResolvedWorld r = resolveWorld(args.get("NAME"), seedArg(args));
  const BuiltWorld& w = requireGenerated(r, args.get("NAME"));
  throwIfInterrupted();  // the cache entry is whole (written and renamed) or absent
  // Compile once in MuJoCo (fails loudly on any MuJoCo error or warning).
  QuadrotorSim sim(PhysicsConfig{}, w.world_xml, w.generated.start);
  throwIfInterrupted();
  const double secs = secondsSince(t0);
  std::printf("world %s: %s (%s) in %.2f s; %d collision + %d visual geoms (MuJoCo model: %d geoms)\n",
              w.generated.name.c_str(), w.directory.c_str(), w.reused ? "cached" : "built", secs,
              w.generated.collision_geoms, w.generated.visual_geoms, sim.geomCount());
  for (const auto& [kind, n] : w.generated.object_counts) std::printf("  %-10s %d\n", kind.c_str(), n);
  printMeshReports(w.generated.meshes);
  // The surface under the start (the spec's start z should lie on it: the vehicle rests there).
  const Vec3 start = w.generated.start.translation();
  const WorldTruth truth(w.generated.shapes);
  if (const auto hit = truth.raycast(start + Vec3(0, 0, 100), Vec3(0, 0, -1), 300.0))
    std::printf("  the surface under the start (%g, %g) is at z = %.3f (the start's z: %g)\n", start.x(), start.y(),
                start.z() + 100 - hit->distance_m, start.z());
  return kExitOk;
}

// The ground truth against MuJoCo: 1000 random rays from free points of the exploration box
// (seeded: the same rays every time), each first hit compared. Rays that leave the world (no hit
// within 150 m in both, or MuJoCo's finite ground plane) are not compared.
struct RayAgreement {
  int compared = 0, disagree = 0;  ///< rays compared; those differing by more than 1 cm
  double max_diff_m = 0.0;
};

RayAgreement truthAgainstMuJoCo(const BuiltWorld& w) {
  const WorldTruth truth(w.generated.shapes);
  QuadrotorSim sim(PhysicsConfig{}, w.world_xml, w.generated.start);
  const int vehicle = mj_name2id(sim.model(), mjOBJ_BODY, mjcf_names::kVehicleBody);
  const mjtByte groups[mjNGROUP] = {1, 0, 0, 0, 1, 0};  // collision geoms: drawn (0) and hidden (4)
  RngStream rng(11, "world_show_rays");
  const Aabb& box = w.generated.exploration_box;
  RayAgreement out;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 o(rng.uniform(box.min.x(), box.max.x()), rng.uniform(box.min.y(), box.max.y()),
                 rng.uniform(box.min.z() + 0.3, box.max.z()));
    const Vec3 d = Vec3(rng.normal(), rng.normal(), rng.normal()).normalized();
    if (truth.distance(o) < 0.2) continue;
    const auto hit = truth.raycast(o, d, 150.0);
    int geom = -1;
    double t = mj_ray(sim.model(), sim.data(), o.data(), d.data(), groups, 1, vehicle, &geom);
    const char* name = geom >= 0 ? mj_id2name(sim.model(), mjOBJ_GEOM, geom) : nullptr;
    if ((name && std::string(name).rfind("sky_", 0) == 0) || t > 150.0) t = -1.0;
    if (hit && w.generated.shapes[hit->shape].type == ShapeType::kHalfSpace) continue;  // MuJoCo's plane is finite
    if (!hit && t < 0) continue;
    const double diff = hit && t >= 0 ? std::abs(t - hit->distance_m) : 1e9;
    ++out.compared;
    out.disagree += diff > 0.01;
    out.max_diff_m = std::max(out.max_diff_m, std::min(diff, 1e9));
  }
  return out;
}

// One line per object: id, source name, position and heading.
void printPlacedObjects(const std::vector<PlacedObject>& objects) {
  std::printf("%-14s %-34s %9s %9s %8s\n", "object", "name", "x (m)", "y (m)", "yaw (°)");
  for (const PlacedObject& o : objects)
    std::printf("%-14s %-34s %9.3f %9.3f %8.2f\n", o.id.c_str(), o.name.empty() ? "-" : o.name.c_str(), o.xy.x(),
                o.xy.y(), o.yaw_deg);
}

// msbench world show NAME --out DIR: top-down map, start views, explorable columns.
int worldShow(int argc, char** argv) {
  ArgParser args("msbench world show", "Write a top-down map and fisheye views of a world.");
  args.positional("NAME", "world name")
      .option("out", "", "output directory", true)
      .option("seed", "", "placement seed (default: the spec's)")
      .option("m-per-px", "0.2", "top-down map resolution")
      .flag("overwrite", "replace an existing output directory");
  if (!args.parse(argc - 1, argv + 1)) return kExitOk;
  const ResolvedWorld r = resolveWorld(args.get("NAME"), seedArg(args));
  const BuiltWorld& w = requireGenerated(r, args.get("NAME"));
  // The map's size follows from the resolution: 1 to 16384 pixels a side.
  const double m_per_px = args.getDoubleIn("m-per-px", 1e-3, 1e3);
  const auto [lo, hi] = topDownExtent(w.generated);
  const double longest_px = (hi - lo).maxCoeff() / m_per_px;
  if (longest_px > 16384 || (hi - lo).minCoeff() / m_per_px < 1)
    throw UsageError("--m-per-px " + args.get("m-per-px") + ": the top-down map of " + w.generated.name + " (" +
                     std::to_string(int(hi.x() - lo.x())) + " x " + std::to_string(int(hi.y() - lo.y())) +
                     " m) would be " + std::to_string(long(longest_px)) +
                     " pixels long; choose a resolution that gives 1 to 16384 pixels a side");
  StagedOutputDir out(args.get("out"), args.has("overwrite"), OutputKind::kWorldShow);
  writePng(out.staging() / "topdown.png", viewOf(renderTopDown(w, m_per_px)));

  writePng(out.staging() / "views.png", viewOf(startViews(w)));

  const WorldTruth truth(w.generated.shapes);
  const auto columns = truth.explorableColumns(w.generated.exploration_box);
  const Aabb& b = w.generated.exploration_box;
  const int total =
      int(std::floor((b.max.x() - b.min.x()) / 2.5 + 1e-9)) * int(std::floor((b.max.y() - b.min.y()) / 2.5 + 1e-9));
  nlohmann::json j = {{"world", w.generated.name},
                      {"directory", w.directory},
                      {"collision_geoms", w.generated.collision_geoms},
                      {"visual_geoms", w.generated.visual_geoms},
                      {"objects", w.generated.object_counts},
                      {"box_columns", total},
                      {"explorable_columns", columns.size()},
                      {"explorable_area_m2", 6.25 * columns.size()}};
  // Every object with its source's name and pose (the authors' model names in their worlds).
  nlohmann::json placed = nlohmann::json::array();
  for (const PlacedObject& o : w.generated.objects)
    placed.push_back(
        {{"id", o.id}, {"kind", o.kind}, {"name", o.name}, {"x", o.xy.x()}, {"y", o.xy.y()}, {"yaw_deg", o.yaw_deg}});
  j["placed"] = placed;
  const RayAgreement rays = truthAgainstMuJoCo(w);
  j["truth_vs_mujoco"] = {
      {"rays_compared", rays.compared}, {"beyond_1cm", rays.disagree}, {"max_diff_m", rays.max_diff_m}};
  writeFileAtomic(out.staging() / "summary.json", j.dump(2) + "\n");
  out.commit();
  printPlacedObjects(w.generated.objects);
  printMeshReports(w.generated.meshes);
  std::printf("world %s: ground truth against MuJoCo: %d rays compared, %d differ by more than 1 cm (largest %.4f m)\n",
              w.generated.name.c_str(), rays.compared, rays.disagree, rays.max_diff_m);
  std::printf("world %s: %zu of %d columns of the exploration box explorable (%.0f m2) -> %s\n",
              w.generated.name.c_str(), columns.size(), total, 6.25 * columns.size(), out.finalDir().c_str());
  return kExitOk;
}

// msbench world export NAME: the public world's truth as a mesh and a sampled cloud. A held-out
// world is never exported: no option reaches the evaluator's salt (the world is the spec's).
int worldExport(int argc, char** argv) {
  ArgParser args("msbench world export",
                 "The ground truth of a public world (its spec, never a held-out draw) as a triangle\n"
                 "mesh (truth_mesh.ply) and a point cloud sampled on it (truth_points.ply, coloured\n"
                 "and with a `kind` property by obstacle kind), world frame (ROS map), metres.");
  args.positional("NAME", "world name")
      .option("out", "", "output directory", true)
      .option("seed", "", "placement seed (default: the spec's)")
      .option("density", "4", "cloud points per square metre of surface")
      .flag("overwrite", "replace an existing output directory");
  if (!args.parse(argc - 1, argv + 1)) return kExitOk;
  const double density = args.getDoubleIn("density", 1e-3, 1e3);
  const ResolvedWorld r = resolveWorld(args.get("NAME"), seedArg(args));
  const BuiltWorld& w = requireGenerated(r, args.get("NAME"));
  const GeneratedWorld& g = w.generated;
  // The mesh: every shape, half-spaces over the top-down map's extent.
  const auto [lo, hi] = topDownExtent(g);
  TriangleMesh mesh;
  for (size_t i = 0; i < g.shapes.size(); ++i) appendShapeMesh(g.shapes[i], int(i), lo, hi, mesh);
  RngStream rng(0, "world_export_points");
  std::vector<SurfacePoint> samples = sampleSurface(mesh, density, rng);
  if (samples.size() > 50'000'000)
    throw UsageError("--density " + args.get("density") + ": " + std::to_string(samples.size()) +
                     " points; choose a lower density");
  // The cloud is the world's boundary: a point buried in another solid (a wall's foot in the
  // ground, overlapping parts) is dropped; the mesh keeps every solid whole.
  const WorldTruth truth(g.shapes);
  const size_t sampled = samples.size();
  std::erase_if(samples, [&](const SurfacePoint& p) { return truth.distance(p.position, 1.0) < -0.01; });
  PlyCloud cloud;
  cloud.comments = {"msbench world " + g.name + " ground truth, frame_id map (the world frame), units m",
                    "kind 0 textured, 1 textureless, 2 thin, 3 ground"};
  for (const SurfacePoint& p : samples) {
    const ObstacleKind kind = g.shapes[p.shape].kind;
    cloud.xyz.push_back(p.position);
    cloud.kind.push_back(uint8_t(kind));
    const cv::Vec3b c = kindColour(kind);  // the top-down map's colours (BGR there)
    cloud.rgb.push_back({c[2], c[1], c[0]});
  }
  nlohmann::ordered_json j = {{"world", g.name},
                              {"frame", "map (the world frame), REP-103 axes, metres"},
                              {"shapes", g.shapes.size()},
                              {"triangles", mesh.triangles.size()},
                              {"points", samples.size()},
                              {"points_buried_dropped", sampled - samples.size()},
                              {"points_per_m2", density},
                              {"ground_extent_xy_m", {lo.x(), lo.y(), hi.x(), hi.y()}},
                              {"round_segments", kRoundSegments}};
  StagedOutputDir out(args.get("out"), args.has("overwrite"), OutputKind::kWorldExport);
  writeFileAtomic(out.staging() / "truth_mesh.ply",
                  binaryPlyMesh(mesh.vertices, mesh.triangles, {cloud.comments.front()}));
  writeFileAtomic(out.staging() / "truth_points.ply", binaryPly(cloud));
  writeFileAtomic(out.staging() / "world_export.json", j.dump(2) + "\n");
  out.commit();
  std::printf("world %s: %zu shapes, %zu triangles, %zu points (%g per m2) -> %s\n", g.name.c_str(), g.shapes.size(),
              mesh.triangles.size(), samples.size(), density, out.finalDir().c_str());
  return kExitOk;
}

}  // namespace

int runWorldCommand(int argc, char** argv) {
  const std::string sub = argc > 0 ? argv[0] : "";
  if (sub.empty() || sub == "--help" || sub == "-h") {
    std::printf(
        "usage: msbench world list | build NAME [--seed S] | show NAME --out DIR [--seed S] |\n"
        "       import NAME --from CHECKOUT | export NAME --out DIR [--density D]\n\n"
        "  list    worlds under %s\n  build   generate into the cache (%s)\n"
        "  show    top-down map and fisheye views from the start pose\n"
        "  import  copy a world's meshes from a checkout of its source into the cache\n"
        "  export  the world's truth as a mesh and a point cloud (PLY, world frame)\n",
        worldsDir().c_str(), worldCacheDir().c_str());
    return sub.empty() ? kExitUsage : kExitOk;
  }
  if (sub == "list") return worldList(argc, argv);
  if (sub == "build") return worldBuild(argc, argv);
  if (sub == "show") return worldShow(argc, argv);
  if (sub == "import") return worldImport(argc, argv);
  if (sub == "export") return worldExport(argc, argv);
  throw UsageError("unknown world sub-command '" + sub + "' (list, build, show, import, export)");
}

}  // namespace msb
