// The contact gate never says "no contact" where MuJoCo finds one, and says it often enough to
// pay: vehicle poses sampled around every shape it handles, compared with MuJoCo's own detection.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/common/rng.h"
#include "sim/physics/contact_gate.h"
#include "sim/physics/quadrotor_sim.h"

namespace msb {
namespace {

const std::string kWorlds = std::string(MSB_SOURCE_DIR) + "/tests/data/worlds/";

// A vehicle pose set into its own mjData, with MuJoCo's full detection run on it.
class Probe {
 public:
  explicit Probe(QuadrotorSim& sim) : m_(sim.model()), d_(mj_makeData(m_)) {
    body_ = mj_name2id(m_, mjOBJ_BODY, mjcf_names::kVehicleBody);
    qpos_ = m_->jnt_qposadr[m_->body_jntadr[body_]];
    mj_forward(m_, d_);
  }
  ~Probe() { mj_deleteData(d_); }
  Probe(const Probe&) = delete;
  Probe& operator=(const Probe&) = delete;

  // Contacts MuJoCo detects with the vehicle's body at p, turned by the unit quaternion q.
  int contactsAt(const Vec3& p, const Quat& q) {
    for (int k = 0; k < 3; ++k) d_->qpos[qpos_ + k] = p[k];
    d_->qpos[qpos_ + 3] = q.w(), d_->qpos[qpos_ + 4] = q.x(), d_->qpos[qpos_ + 5] = q.y(), d_->qpos[qpos_ + 6] = q.z();
    mj_forward(m_, d_);
    return d_->ncon;
  }
  ContactGate gate() const { return ContactGate(m_, d_, body_); }

 private:
  mjModel* m_;
  mjData* d_;
  int body_ = -1, qpos_ = 0;
};

Quat randomTurn(RngStream& rng) { return Quat(rng.normal(), rng.normal(), rng.normal(), rng.normal()).normalized(); }

TEST(ContactGate, NeverRulesOutAContactMuJoCoFinds) {
  PhysicsConfig cfg;
  cfg.contact_gate = false;  // the sim detects every step; the gate here is the test's own
  QuadrotorSim sim(cfg, kWorlds + "shapes.xml", poseFromXyzYaw(Vec3(0, 0, 2), 0));
  Probe probe(sim);
  const ContactGate gate = probe.gate();
  ASSERT_TRUE(gate.active()) << gate.whyInactive();
  EXPECT_EQ(gate.boxes(), 6);  // box, sphere, cylinder, capsule, ellipsoid, mesh; not the drawn box
  EXPECT_EQ(gate.planes(), 1);
  RngStream rng(1, "contact_gate_test");
  const mjModel* m = sim.model();
  int touching = 0, ruled_out = 0, free_not_ruled_out = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    // Poses in the cube around each world shape's bounding sphere, with room for the vehicle.
    if (m->geom_type[g] == mjGEOM_PLANE || m->geom_bodyid[g] != 0) continue;
    const Vec3 c(sim.data()->geom_xpos[3 * g], sim.data()->geom_xpos[3 * g + 1], sim.data()->geom_xpos[3 * g + 2]);
    const double r = m->geom_rbound[g] + 0.4;
    for (int i = 0; i < 1500; ++i) {
      const Vec3 p = c + r * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      const int contacts = probe.contactsAt(p, randomTurn(rng));
      const bool out = gate.clearance(p) > 0;
      if (contacts > 0) {
        ++touching;
        EXPECT_FALSE(out) << "contact at " << p.transpose() << " ruled out";
      }
      ruled_out += out ? 1 : 0;
      free_not_ruled_out += contacts == 0 && !out ? 1 : 0;
    }
  }
  // Both kinds occur, and most poses without a contact are ruled out (the gate pays).
  EXPECT_GT(touching, 1000);
  EXPECT_GT(ruled_out, 2000);
  EXPECT_LT(free_not_ruled_out, ruled_out / 2);
}

TEST(ContactGate, AWalkPastEveryShapeIsNeverRuledOutWhereItTouches) {
  // The free radius carried from step to step: a random walk in 2 mm steps, as at 1 m/s.
  PhysicsConfig cfg;
  cfg.contact_gate = false;
  QuadrotorSim sim(cfg, kWorlds + "shapes.xml", poseFromXyzYaw(Vec3(0, 0, 2), 0));
  Probe probe(sim);
  ContactGate gate = probe.gate();
  RngStream rng(2, "contact_gate_walk");
  Vec3 p(0, 0, 1.5), v(1, 0.3, 0);
  int touching = 0, skipped = 0;
  const Quat level = Quat::Identity();
  for (int i = 0; i < 60000; ++i) {
    v = (v + 0.05 * Vec3(rng.normal(), rng.normal(), 0.3 * rng.normal())).normalized();
    if (p.head<2>().norm() > 8) v.head<2>() = -p.head<2>().normalized();  // stay among the shapes
    p += 0.002 * v;
    p.z() = std::clamp(p.z(), 0.05, 3.5);
    const bool may = gate.mayTouch(p);
    skipped += may ? 0 : 1;
    if (i % 7 != 0 && may) continue;  // MuJoCo's detection is slow: check every skipped step, a few others
    const int contacts = probe.contactsAt(p, level);
    touching += contacts > 0 ? 1 : 0;
    if (contacts > 0) {
      EXPECT_TRUE(may) << "step " << i << " at " << p.transpose();
    }
  }
  EXPECT_GT(touching, 100);
  EXPECT_GT(skipped, 20000);
}

TEST(ContactGate, StaysOffWhereItCannotBeSure) {
  // Explicit contact pairs (MuJoCo tests them outside the body pairs) and a moving body.
  for (const std::string world : {"explicit_pair.xml", "loose_box.xml"}) {
    QuadrotorSim sim(PhysicsConfig{}, kWorlds + world, poseFromXyzYaw(Vec3(0, 0, 2), 0));
    ASSERT_NE(sim.contactGate(), nullptr);
    EXPECT_FALSE(sim.contactGate()->active()) << world;
    for (int i = 0; i < 10; ++i) sim.beginTick(), sim.endTick(Vec4::Constant(1.325 * 9.81 / 4));
    EXPECT_EQ(sim.stepsSkipped(), 0) << world;
  }
  QuadrotorSim sim(PhysicsConfig{}, kWorlds + "wall_ahead.xml", poseFromXyzYaw(Vec3(0, 0, 2), 0));
  EXPECT_TRUE(sim.contactGate()->active()) << sim.contactGate()->whyInactive();
}

}  // namespace
}  // namespace msb
