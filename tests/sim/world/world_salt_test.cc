// Held-out worlds (sim/world/world_salt.h): a salt draws the same world every time, another salt
// another world of the same task, and a truth carried in advance no longer fits it.
#include "sim/world/world_salt.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/geometry/world_truth.h"
#include "sim/world/world_generator.h"
#include "tools/config/world_registry.h"

namespace msb {
namespace {

const std::vector<std::string> kWorlds = {"urban", "cave", "rooftops", "sparse", "urban_town", "suburb3", "sparse1"};
const std::string kSaltA = "salt-a-0123456789abcdef", kSaltB = "salt-b-0123456789abcdef";

WorldSpec spec(const std::string& name) {
  return loadWorldSpec(std::string(MSB_SOURCE_DIR) + "/worlds/" + name + "/spec.yaml");
}

// A salt of `name` that mirrors it (or does not), found by counting: the same one every time.
std::string saltThat(const std::string& name, bool mirrors) {
  for (int i = 0; i < 64; ++i) {
    const std::string salt = "search-salt-" + std::to_string(i) + "-0123456789";
    WorldSalting h;
    saltWorldSpec(spec(name), salt, &h);
    if (h.mirrored == mirrors) return salt;
  }
  ADD_FAILURE() << name << ": no salt in 64 " << (mirrors ? "mirrors" : "keeps") << " it";
  return "";
}

// Over the box's 0.5 m lattice: the points the first truth holds inside an obstacle, and those
// whose occupancy differs between the two.
struct Lattice {
  int occupied = 0, differ = 0;
};
Lattice compare(const GeneratedWorld& a, const GeneratedWorld& b) {
  const WorldTruth ta(a.shapes), tb(b.shapes);
  const Aabb& box = a.exploration_box;
  Lattice out;
  for (double x = box.min.x() + 0.25; x < box.max.x(); x += 0.5)
    for (double y = box.min.y() + 0.25; y < box.max.y(); y += 0.5)
      for (double z = box.min.z() + 0.25; z < box.max.z(); z += 0.5) {
        const bool in_a = ta.inside(Vec3(x, y, z));
        out.occupied += in_a;
        out.differ += in_a != tb.inside(Vec3(x, y, z));
      }
  return out;
}

TEST(WorldSalt, TheSameSaltGivesTheSameWorldAndAnotherSaltAnother) {
  for (const auto& name : kWorlds) {
    const GeneratedWorld a1 = generateWorld(saltWorldSpec(spec(name), kSaltA));
    const GeneratedWorld a2 = generateWorld(saltWorldSpec(spec(name), kSaltA));
    const GeneratedWorld b = generateWorld(saltWorldSpec(spec(name), kSaltB));
    const GeneratedWorld plain = generateWorld(spec(name));
    EXPECT_EQ(a1.mjcf, a2.mjcf) << name;
    EXPECT_NE(a1.mjcf, b.mjcf) << name;
    EXPECT_NE(a1.mjcf, plain.mjcf) << name;
    // The same task: the kinds and counts of objects, the start, the box's size.
    auto objects = [](std::map<std::string, int> counts) {
      counts.erase("cave_box");  // the cave's carving, not an object: its boxes merge by orientation
      return counts;
    };
    EXPECT_EQ(objects(a1.object_counts), objects(plain.object_counts)) << name;
    EXPECT_TRUE(a1.start.translation().isApprox(plain.start.translation(), 1e-9)) << name;
    EXPECT_NEAR(yawOf(a1.start.linear()), yawOf(plain.start.linear()), 1e-9) << name;
    EXPECT_TRUE((a1.exploration_box.max - a1.exploration_box.min)
                    .isApprox(plain.exploration_box.max - plain.exploration_box.min, 1e-9))
        << name;
    EXPECT_NE(saltWorldSpec(spec(name), kSaltA).texture_seed, 0u);
  }
}

TEST(WorldSalt, ASaltedWorldKeepsItsStartClearAndItsStartInItsBox) {
  for (const auto& name : kWorlds)
    for (const std::string& salt : {kSaltA, kSaltB, saltThat(name, true), saltThat(name, false)}) {
      const WorldSpec ws = saltWorldSpec(spec(name), salt);
      GeneratedWorld g;
      try {
        g = generateWorld(ws);  // throws when a fixed object reaches the start's clearance
      } catch (const std::exception& e) {
        FAIL() << name << " salted " << salt << ": " << e.what();
      }
      std::vector<Shape> obstacles;
      for (const auto& s : g.shapes)
        if (s.type != ShapeType::kHalfSpace) obstacles.push_back(s);
      const WorldTruth truth(obstacles);
      for (double z = 0.3; z <= 3.0; z += 0.1)
        EXPECT_GE(truth.distance(g.start.translation() + Vec3(0, 0, z), 100.0), ws.start_clearance_m) << name;
      EXPECT_TRUE(g.exploration_box.contains(g.start.translation() + Vec3(0, 0, 1))) << name;
    }
}

TEST(WorldSalt, AMirrorMovesTheBoxAndEveryObjectWithTheWorld) {
  const WorldSpec plain = spec("urban");
  WorldSalting h;
  const WorldSpec mirrored = saltWorldSpec(plain, saltThat("urban", true), &h);
  ASSERT_TRUE(h.mirrored);
  // urban starts at (0, 2) heading +y: the mirror is x -> -x.
  EXPECT_TRUE(h.point(Vec2(3, 5)).isApprox(Vec2(-3, 5)));
  EXPECT_NEAR(std::abs(h.yaw(0.0)), 3.14159265358979323846, 1e-12);
  EXPECT_TRUE(mirrored.exploration_box.min.isApprox(Vec3(-45, -48, 0)));
  EXPECT_TRUE(mirrored.exploration_box.max.isApprox(Vec3(20, 14, 7)));
  // The fire station (fixed, by the start: never jittered) stands mirrored, turned to match.
  EXPECT_TRUE(mirrored.objects[0].at->isApprox(Vec2(4.24, 16.54)));
  EXPECT_NEAR(*mirrored.objects[0].yaw_deg, 0.4, 1e-9);
  // The sun too, so that every face is lit as its mirror image was (before, it was not: the
  // textureless buses' sides then faced the light differently in a mirrored urban).
  EXPECT_TRUE(mirrored.sun_direction.isApprox(Vec3(-0.62, 0.47, -0.63)));
  EXPECT_NE(generateWorld(mirrored).mjcf.find("dir=\"-0.62 0.47 -0.63\""), std::string::npos);
  EXPECT_NE(generateWorld(plain).mjcf.find("dir=\"0.62 0.47 -0.63\""), std::string::npos);
}

// What a method carrying the world's truth from the repository meets on a held-out world: where
// its truth says "obstacle", the salted world is often free, and the other way round. Measured,
// lattice points that differ per point the obstacles hold, mirrored / not: urban 1.53 / 0.13,
// sparse1 1.52 / 0.62, suburb3 1.17 / 0.34 — a mirror moves everything; without one, urban keeps
// the large buildings within kSaltKeepM of its start, and a building moved 1.5 m changes only its
// edges. Asserted: above 1 mirrored, above 0.1 not.
TEST(WorldSalt, ATruthCarriedInAdvanceNoLongerFitsTheWorld) {
  for (const auto& name : {"urban", "sparse1", "suburb3"}) {
    const GeneratedWorld plain = generateWorld(spec(name));
    for (bool mirrors : {true, false}) {
      WorldSalting h;
      const GeneratedWorld salted = generateWorld(saltWorldSpec(spec(name), saltThat(name, mirrors), &h));
      EXPECT_GT(h.swapped + h.jittered, 5) << name;
      const Lattice l = compare(plain, salted);
      const double ratio = double(l.differ) / double(l.occupied);
      std::printf("%s %s: %d of the box's lattice points differ, %d are occupied (%.2f)\n", name,
                  mirrors ? "mirrored" : "not mirrored", l.differ, l.occupied, ratio);
      EXPECT_GT(ratio, mirrors ? 1.0 : 0.1) << name << (mirrors ? " mirrored" : " not mirrored");
    }
  }
}

TEST(WorldSalt, TheRecordCarriesACommitmentNotTheSalt) {
  EXPECT_EQ(worldSaltCommitment(kSaltA), worldSaltCommitment(kSaltA));
  EXPECT_NE(worldSaltCommitment(kSaltA), worldSaltCommitment(kSaltB));
  EXPECT_EQ(worldSaltCommitment(kSaltA).find(kSaltA), std::string::npos);
  EXPECT_EQ(worldSaltCommitment(kSaltA).rfind("fnv1a64:", 0), 0u);
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// Half the salts mirror a world whose start heads along an axis (the mirror is a coin, not a
// constant a method could carry the answer to).
TEST(WorldSalt, AboutHalfTheSaltsMirror) {
  const WorldSpec urban = spec("urban");
  int mirrored = 0;
  for (int i = 0; i < 200; ++i) {
    WorldSalting h;
    saltWorldSpec(urban, "coin-" + std::to_string(i) + "-0123456789abcdef", &h);
    mirrored += h.mirrored;
  }
  EXPECT_GT(mirrored, 70);
  EXPECT_LT(mirrored, 130);
  std::printf("%d of 200 salts mirror urban\n", mirrored);
}

}  // namespace
}  // namespace msb
