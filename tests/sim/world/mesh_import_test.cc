// Imported meshes (docs/worlds.md, "Imported meshes"), on a small mesh the test writes: a
// terrain with a bump, a box and an L-shaped (concave) block in one OBJ file with a textured
// material. Each node is cut by its rule; the ground truth holds the solid under the terrain, the
// box and the L's walls but not the L's notch; MuJoCo's rays agree with the truth's; a missing
// image, file or unreadable mesh is an error naming the key.
#include "sim/world/mesh_import.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <regex>

#include "core/common/config_check.h"
#include "core/common/png.h"
#include "core/common/rng.h"
#include "sim/physics/mjcf_files.h"
#include "sim/physics/quadrotor_sim.h"
#include "sim/world/world_cache.h"
#include "sim/world/world_generator.h"
#include "sim/world/world_salt.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

// The terrain's height: a tilted plane with a 1.5 m bump at the origin (sampled on the grid).
double terrainZ(double x, double y) { return 0.5 + 0.05 * x + (std::abs(x) < 1 && std::abs(y) < 1 ? 1.5 : 0.0); }

// Writes scene.obj (+ scene.mtl, grass.png) into `dir`: terrain (5 x 5 vertices over ±20 m,
// normals up, texture coordinates), box (half 1 m at (8, 8, 3)), L block (z 0...2 at (-10, -10)).
void writeScene(const fs::path& dir, bool with_image = true) {
  fs::create_directories(dir);
  std::ofstream mtl(dir / "scene.mtl");
  mtl << "newmtl ground\nKd 0.5 0.6 0.4\nmap_Kd grass.png\nnewmtl paint\nKd 0.8 0.8 0.8\n";
  if (with_image) {
    cv::Mat img(64, 64, CV_8UC1);
    cv::randu(img, 0, 255);
    writePng(dir / "grass.png", viewOf(img));
  }
  std::ofstream o(dir / "scene.obj");
  o << "mtllib scene.mtl\no terrain\nusemtl ground\n";
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) {
      const double x = -20 + 10 * i, y = -20 + 10 * j;
      o << "v " << x << " " << y << " " << terrainZ(x, y) << "\nvt " << i / 4.0 << " " << j / 4.0 << "\n";
    }
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int a = 1 + j * 5 + i, b = a + 1, c = a + 5, d = c + 1;
      o << "f " << a << "/" << a << " " << b << "/" << b << " " << d << "/" << d << "\n";
      o << "f " << a << "/" << a << " " << d << "/" << d << " " << c << "/" << c << "\n";
    }
  o << "o box\nusemtl paint\n";
  for (int k = 0; k < 8; ++k)
    o << "v " << 8 + (k & 1 ? 1 : -1) << " " << 8 + (k & 2 ? 1 : -1) << " " << 3 + (k & 4 ? 1 : -1) << "\n";
  const int box[12][3] = {{1, 3, 4}, {1, 4, 2}, {5, 6, 8}, {5, 8, 7}, {1, 2, 6}, {1, 6, 5},
                          {3, 7, 8}, {3, 8, 4}, {1, 5, 7}, {1, 7, 3}, {2, 4, 8}, {2, 8, 6}};
  for (const auto& t : box) o << "f " << 25 + t[0] << " " << 25 + t[1] << " " << 25 + t[2] << "\n";
  // The L: polygon (0,0) (3,0) (3,1) (1,1) (1,3) (0,3) at z 0 and 2, placed at (-10, -10).
  o << "o ell\nusemtl paint\n";
  const double L[6][2] = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  for (double z : {0.0, 2.0})
    for (const auto& p : L) o << "v " << -10 + p[0] << " " << -10 + p[1] << " " << z << "\n";
  const int base = 34;  // 1-based index of the L's first vertex (after 25 + 8)
  const int caps[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  for (const auto& t : caps) {
    o << "f " << base + t[0] << " " << base + t[2] << " " << base + t[1] << "\n";              // bottom, down
    o << "f " << base + 6 + t[0] << " " << base + 6 + t[1] << " " << base + 6 + t[2] << "\n";  // top, up
  }
  for (int k = 0; k < 6; ++k) {
    const int a = base + k, b = base + (k + 1) % 6;
    o << "f " << a << " " << b << " " << b + 6 << "\nf " << a << " " << b + 6 << " " << a + 6 << "\n";
  }
}

fs::path tempDir(const std::string& tag) {
  const fs::path d = fs::path(::testing::TempDir()) / ("msb_mesh_" + tag);
  fs::remove_all(d);
  return d;
}

// A world of the scene alone (no ground plane: the terrain is the ground).
WorldSpec sceneWorld(const fs::path& source) {
  WorldSpec w;
  w.name = "mesh_fixture";
  w.ground_enabled = false;
  w.ground_size_m = Vec2(60, 60);
  w.start_position_m = Vec3(-15, 15, terrainZ(-15, 15));
  w.exploration_box.min = Vec3(-20, -20, 0);
  w.exploration_box.max = Vec3(20, 20, 8);
  w.start_clearance_m = 1;
  w.source = SourceSpec{"test/fixture", "0000000"};
  MeshSpec m;
  m.file = "meshes/scene.obj";
  m.name = "scene";
  w.meshes.push_back(m);
  w.source_dir = source.string();
  return w;
}

TEST(MeshImport, EachNodeIsCutByItsRule) {
  const fs::path dir = tempDir("rules");
  writeScene(dir);
  const ImportedMesh m = importMesh((dir / "scene.obj").string(), Vec3::Ones(), Pose::Identity(), 0.3);
  ASSERT_EQ(m.nodes.size(), 3u);
  std::map<std::string, const ImportedNode*> by;
  for (const auto& n : m.nodes) by[n.node] = &n;
  ASSERT_TRUE(by.count("terrain") && by.count("box") && by.count("ell"));
  EXPECT_EQ(by["terrain"]->rule, PieceRule::kVertical);
  EXPECT_TRUE(by["terrain"]->terrain);
  EXPECT_EQ(by["terrain"]->pieces.size(), 32u);
  EXPECT_EQ(by["box"]->rule, PieceRule::kConvex);
  EXPECT_EQ(by["box"]->pieces.size(), 1u);
  EXPECT_EQ(by["ell"]->rule, PieceRule::kVertical);  // closed and concave: cut vertically
  EXPECT_FALSE(by["ell"]->terrain);
  EXPECT_EQ(by["ell"]->pieces.size(), 20u);
  EXPECT_EQ(m.triangles, 32u + 12u + 20u);
  // The terrain's surface keeps its image and texture coordinates.
  bool textured = false;
  for (const auto& s : m.surfaces) textured |= s.node == "terrain" && s.texture_file == "grass.png" && !s.uv.empty();
  EXPECT_TRUE(textured);
}

TEST(MeshImport, TheTruthHoldsTheTerrainsSolidTheBoxAndTheWallsButNotTheNotch) {
  const fs::path dir = tempDir("truth");
  writeScene(dir / "meshes");
  const GeneratedWorld g = generateWorld(sceneWorld(dir));
  const WorldTruth truth(g.shapes);
  // Under and over the terrain, on and off the grid's vertices.
  for (double x : {-17.0, -5.0, 3.0, 12.0})
    for (double y : {-13.0, 4.0, 16.0}) {
      EXPECT_TRUE(truth.inside(Vec3(x, y, terrainZ(x, y) - 0.4 - 0.05 * 10))) << x << ", " << y;
      EXPECT_FALSE(truth.inside(Vec3(x, y, 4.5))) << x << ", " << y;
    }
  EXPECT_TRUE(truth.inside(Vec3(8, 8, 3)));  // the box's centre
  EXPECT_FALSE(truth.inside(Vec3(8, 8, 4.2)));
  EXPECT_TRUE(truth.inside(Vec3(-9.9, -8.0, 1.0)));               // 0.1 m inside the L's outer wall
  EXPECT_TRUE(truth.inside(Vec3(-9.5, -7.5, 1.0)));               // the L's core, beyond any slab
  EXPECT_FALSE(truth.inside(Vec3(-8.0, -8.0, 1.5)));              // the notch
  EXPECT_NEAR(truth.distance(Vec3(-8.0, -8.0, 1.5)), 1.0, 1e-6);  // to the notch walls
  // Terrain pieces are ground; the others the spec's kind.
  int ground = 0, textured = 0;
  for (const Shape& s : g.shapes) (s.kind == ObstacleKind::kGround ? ground : textured) += s.type == ShapeType::kConvex;
  EXPECT_EQ(ground, 32);
  EXPECT_EQ(textured, 21);
  ASSERT_EQ(g.image_textures.size(), 1u);
}

TEST(MeshImport, MuJoCoRaysAgreeWithTheTruthWithin1cmAndTheStartRestsOnTheTerrain) {
  const fs::path dir = tempDir("rays");
  writeScene(dir / "meshes");
  const BuiltWorld w = buildWorld(sceneWorld(dir), (dir / "cache").string());
  const WorldTruth truth(w.generated.shapes);
  // The vehicle starts on the terrain: resting on it before take-off is no collision.
  QuadrotorSim sim(PhysicsConfig{}, w.world_xml, w.generated.start);
  for (int i = 0; i < 50; ++i) {
    EXPECT_FALSE(sim.beginTick());
    sim.endTick(Vec4::Zero());
  }
  const int vehicle = mj_name2id(sim.model(), mjOBJ_BODY, mjcf_names::kVehicleBody);
  const mjtByte collision_groups[mjNGROUP] = {1, 0, 0, 0, 1, 0};
  RngStream rng(5, "mesh_rays");
  int compared = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 o(rng.uniform(-19, 19), rng.uniform(-19, 19), rng.uniform(2.5, 8));
    if (truth.distance(o) < 0.2) continue;
    const Vec3 d = Vec3(rng.normal(), rng.normal(), rng.normal()).normalized();
    const auto hit = truth.raycast(o, d, 100.0);
    int geom = -1;
    double t = mj_ray(sim.model(), sim.data(), o.data(), d.data(), collision_groups, 1, vehicle, &geom);
    const char* name = geom >= 0 ? mj_id2name(sim.model(), mjOBJ_GEOM, geom) : nullptr;
    if (name && std::string(name).rfind("sky_", 0) == 0) t = -1.0;
    if (!hit) {
      EXPECT_LT(t, 0.0) << "mj_ray hit " << (name ? name : "?") << " at " << t << " where the truth has none";
      continue;
    }
    ASSERT_GE(t, 0.0) << "truth hit " << w.generated.shapes[hit->shape].name << ", MuJoCo nothing";
    EXPECT_NEAR(t, hit->distance_m, 0.01) << w.generated.shapes[hit->shape].name << " / " << (name ? name : "?");
    ++compared;
  }
  EXPECT_GT(compared, 250);
}

TEST(MeshImport, AMissingImageFileOrMeshIsAnErrorNamingTheKey) {
  const fs::path dir = tempDir("errors");
  writeScene(dir / "meshes", /*with_image=*/false);
  auto expectError = [](const WorldSpec& w, const std::string& part) {
    try {
      generateWorld(w);
      ADD_FAILURE() << "no error; expected one with '" << part << "'";
    } catch (const ConfigError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("meshes[0].file"), std::string::npos) << what;
      EXPECT_NE(what.find(part), std::string::npos) << what;
    }
  };
  // The image is absent: an error, unless the spec names a stand-in texture.
  WorldSpec w = sceneWorld(dir);
  expectError(w, "grass.png");
  w.meshes[0].missing_texture = "grass";
  const GeneratedWorld g = generateWorld(w);
  ASSERT_EQ(g.meshes.size(), 1u);
  EXPECT_EQ(g.meshes[0].stand_ins, std::vector<std::string>{"meshes/grass.png"});
  // An image named outside the checkout ('..' past its root) is looked for beside the mesh only:
  // never read or copied from outside (here absent: the stand-in again).
  std::ofstream(dir / "outside.png") << "not read";
  std::string mtl;
  {
    std::ifstream in(dir / "meshes" / "scene.mtl");
    mtl.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::ofstream(dir / "meshes" / "scene.mtl") << std::regex_replace(mtl, std::regex("grass.png"), "../../outside.png");
  std::vector<std::string> absent;
  const auto files = meshSourceFiles(w, dir.string(), absent);
  // The mesh and the material library it reads (an import copies both); the image is absent.
  EXPECT_EQ(files, (std::vector<std::string>{"meshes/scene.obj", "meshes/scene.mtl"}));
  EXPECT_EQ(absent, std::vector<std::string>{"meshes/outside.png"});
  EXPECT_EQ(generateWorld(w).meshes[0].stand_ins, std::vector<std::string>{"meshes/outside.png"});
  // Not imported: says how to import it.
  w.source_dir = (dir / "nowhere").string();
  expectError(w, "msbench world import mesh_fixture --from");
  // Not a mesh.
  std::ofstream(dir / "meshes" / "junk.obj") << "this is not a mesh\n\x01\x02";
  w.source_dir = dir.string();
  w.meshes[0].file = "meshes/junk.obj";
  expectError(w, "junk.obj");
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// A held-out world's mirror (sim/world/world_salt.h) mirrors an imported mesh too: its solids are
// where the unmirrored ones are, seen in the mirror (the fixture starts at (-15, 15) heading +x:
// the mirror is y -> 30 - y), and its faces stay wound outwards.
TEST(MeshImport, AMirroredMeshHoldsItsSolidsInTheMirror) {
  const fs::path dir = tempDir("mirror");
  writeScene(dir / "meshes");
  const WorldSpec plain = sceneWorld(dir);
  WorldSpec mirrored;
  WorldSalting h;
  for (int i = 0; i < 64 && !h.mirrored; ++i)
    mirrored = saltWorldSpec(plain, "mirror-salt-" + std::to_string(i) + "-0123456", &h);
  ASSERT_TRUE(h.mirrored);
  ASSERT_TRUE(mirrored.meshes[0].mirrored);
  const WorldTruth a(generateWorld(plain).shapes), b(generateWorld(mirrored).shapes);
  int checked = 0;
  for (double x = -19.5; x < 20; x += 1.5)
    for (double y = 10.25; y < 20; y += 1.5)
      for (double z = -1.0; z < 5; z += 0.7) {
        const Vec2 m = h.point(Vec2(x, y));
        EXPECT_EQ(a.inside(Vec3(x, y, z)), b.inside(Vec3(m.x(), m.y(), z))) << x << ", " << y << ", " << z;
        ++checked;
      }
  EXPECT_GT(checked, 500);
}

}  // namespace
}  // namespace msb
