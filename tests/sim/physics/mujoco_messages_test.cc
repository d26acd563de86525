// MuJoCo's errors and warnings under msbench's handlers: an error is an exception (never a
// prompt, an exit or a MUJOCO_LOG.TXT), an empty world file is refused before MuJoCo sees it, and
// a warning during a run is counted by MuJoCo's counters.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sim/physics/mujoco_messages.h"
#include "sim/physics/quadrotor_sim.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("msb_mujoco_messages_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(MujocoMessages, AnErrorIsThrownAndNothingIsWritten) {
  installMujocoHandlers();
  const fs::path d = scratch("error");
  const fs::path cwd = fs::current_path();
  fs::current_path(d);
  mjVFS* vfs = new mjVFS;
  mj_defaultVFS(vfs);
  // MuJoCo's own check of a zero file size is a fatal error (mju_error).
  EXPECT_THROW(mj_makeEmptyFileVFS(vfs, "empty.xml", 0), MujocoError);
  mj_deleteVFS(vfs);
  delete vfs;
  fs::current_path(cwd);
  EXPECT_FALSE(fs::exists(d / "MUJOCO_LOG.TXT"));
}

TEST(MujocoMessages, AnEmptyWorldFileIsAConfigurationErrorNamingTheFile) {
  const fs::path d = scratch("empty");
  std::ofstream(d / "empty.xml").close();
  try {
    QuadrotorSim sim(PhysicsConfig{}, (d / "empty.xml").string(), poseFromXyzYaw(Vec3(0, 0, 0.05), 0.0));
    FAIL() << "an empty world loaded";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find((d / "empty.xml").string() + ": the world file is empty"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(QuadrotorSim(PhysicsConfig{}, d.string(), poseFromXyzYaw(Vec3(0, 0, 0.05), 0.0)), ConfigError);
}

TEST(MujocoMessages, AWarningDuringARunIsCounted) {
  // Room for one contact only: the vehicle, dropped from 1 m, lands on its legs and makes more,
  // so MuJoCo warns (contact list full) and counts every step from then on. (At load time the
  // same warning is a configuration error: started on the ground, this world is refused.)
  const fs::path d = scratch("warning");
  std::ofstream(d / "w.xml") << "<mujoco><size nconmax=\"1\"/><worldbody><geom name=\"ground\" type=\"plane\" "
                                "size=\"5 5 1\"/></worldbody></mujoco>\n";
  QuadrotorSim sim(PhysicsConfig{}, (d / "w.xml").string(), poseFromXyzYaw(Vec3(0, 0, 1.0), 0.0));
  EXPECT_TRUE(sim.warningCounts().empty());
  for (int i = 0; i < 1000; ++i) {
    sim.beginTick();
    sim.endTick(Vec4::Zero());
  }
  const auto counts = sim.warningCounts();
  ASSERT_EQ(counts.count("contact_full"), 1u) << "no contact-full warning counted";
  EXPECT_GE(counts.at("contact_full"), 1);
}

}  // namespace
}  // namespace msb
