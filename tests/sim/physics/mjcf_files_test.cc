// A world's included MJCF files (sim/physics/mjcf_files.h): found recursively and loaded from
// memory; a FIFO, a missing file and a cycle are configuration errors naming the file, raised
// without blocking; commented-out includes are not files.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "sim/physics/mjcf_files.h"
#include "sim/physics/quadrotor_sim.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("msb_mjcf_files_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d / "parts");
  return d;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

const char* kWorld = R"(<mujoco model="w">
  <!-- <include file="parts/missing.xml"/> is commented out -->
  <include file="parts/a.xml"/>
  <worldbody><geom name="ground" type="plane" size="50 50 1"/></worldbody>
</mujoco>
)";

TEST(MjcfFiles, IncludesAreFoundRecursivelyAndTheWorldLoadsFromThem) {
  const fs::path d = scratch("ok");
  write(d / "world.xml", kWorld);
  write(d / "parts/a.xml", R"(<mujoco><include file='parts/b.xml'/>
    <worldbody><geom name="box_a" type="box" size="1 1 1" pos="10 0 1"/></worldbody></mujoco>)");
  write(d / "parts/b.xml", R"(<mujoco><worldbody><geom name="box_b" type="box" size="1 1 1" pos="-10 0 1"/>
    </worldbody></mujoco>)");
  const auto files = mjcfInputFiles((d / "world.xml").string());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[1], (d / "parts/a.xml").string());
  EXPECT_EQ(files[2], (d / "parts/b.xml").string());
  const QuadrotorSim sim(PhysicsConfig{}, (d / "world.xml").string(), poseFromXyzYaw(Vec3(0, 0, 0.05), 0.0));
  EXPECT_GE(mj_name2id(sim.model(), mjOBJ_GEOM, "box_b"), 0);
}

TEST(MjcfFiles, AnIncludedFifoIsRefusedWithoutBlocking) {
  const fs::path d = scratch("fifo");
  write(d / "world.xml", kWorld);
  ASSERT_EQ(mkfifo((d / "parts/a.xml").c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  try {
    mjcfInputFiles((d / "world.xml").string());
    FAIL() << "a FIFO was read";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find((d / "parts/a.xml").string() + ": not a regular file"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(QuadrotorSim(PhysicsConfig{}, (d / "world.xml").string(), poseFromXyzYaw(Vec3(0, 0, 0.05), 0.0)),
               ConfigError);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST(MjcfFiles, AMissingIncludeAndACycleNameTheFile) {
  const fs::path d = scratch("bad");
  write(d / "world.xml", kWorld);
  try {
    mjcfInputFiles((d / "world.xml").string());
    FAIL() << "a missing include was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("parts/a.xml: included file (of"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
  }
  write(d / "parts/a.xml", R"(<mujoco><include file="parts/a.xml"/></mujoco>)");
  try {
    mjcfInputFiles((d / "world.xml").string());
    FAIL() << "a cycle was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("already included"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace msb
