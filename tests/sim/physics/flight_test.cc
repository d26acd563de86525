// Closed-loop flight of the MuJoCo quadrotor under the SE(3) controller and trajectory tracker
// (ground-truth state feedback): hover, fast square and figure-eight tracking, wall collision.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sim/physics/quadrotor_sim.h"
#include "sim/physics/se3_controller.h"
#include "sim/physics/trajectory_tracker.h"

namespace msb {
namespace {

const std::string kWorlds = std::string(MSB_SOURCE_DIR) + "/tests/data/worlds/";

struct Sample {
  double t;
  Vec3 pos, ref, vel;
  double yaw_error;  // |yaw − reference yaw|, wrapped
};

// Flies `path` from a ground start; records a sample per controller tick (500 Hz).
struct FlightLog {
  std::vector<Sample> samples;
  std::optional<CollisionEvent> collision;
  bool finished = false;
  int64_t steps_skipped = 0;  // steps without collision detection (the contact gate)
};

FlightLog fly(const std::string& world, const std::vector<Waypoint>& path, double max_s,
              TrajectoryLimits limits = TrajectoryLimits::preset("medium"), double stop_after_finish_s = 1e9,
              const PhysicsConfig& physics = PhysicsConfig{}) {
  QuadrotorSim sim(physics, world, poseFromXyzYaw(Vec3(0, 0, 0.05), 0.0));
  const Se3Controller ctrl(Se3ControllerConfig{}, QuadrotorConfig{});
  TrajectoryTrackerConfig tcfg;
  tcfg.limits = limits;
  TrajectoryTracker tracker(tcfg, Vec3(0, 0, 0.05), 0.0);
  tracker.setPath(path);
  FlightLog log;
  double finished_at = -1;
  while (sim.timeSeconds() < max_s) {
    if (sim.beginTick()) {
      log.collision = sim.collision();
      break;
    }
    const Odometry gt = sim.groundTruth();
    const auto& ref = tracker.update(0.002);
    log.samples.push_back({gt.t_s, gt.T_W_B.translation(), ref.position_m, gt.v_W_mps,
                           std::abs(wrapAngle(yawOf(gt.T_W_B.linear()) - ref.yaw_rad))});
    sim.endTick(ctrl.compute(gt, ref));
    EXPECT_FALSE(sim.diverged());
    if (tracker.finished() && finished_at < 0) finished_at = gt.t_s;
    if (finished_at >= 0 && gt.t_s > finished_at + stop_after_finish_s) break;
  }
  log.finished = finished_at >= 0;
  log.steps_skipped = sim.stepsSkipped();
  return log;
}

double rmsError(const FlightLog& log, double from_s = 0.0) {
  double sum = 0;
  int n = 0;
  for (const auto& s : log.samples)
    if (s.t >= from_s) sum += (s.pos - s.ref).squaredNorm(), ++n;
  return std::sqrt(sum / n);
}

double maxSpeed(const FlightLog& log) {
  double v = 0;
  for (const auto& s : log.samples) v = std::max(v, s.vel.norm());
  return v;
}

// Distance from a point to a polyline.
double distToPath(const Vec3& p, const std::vector<Vec3>& poly) {
  double best = 1e9;
  for (size_t i = 1; i < poly.size(); ++i) {
    const Vec3 ab = poly[i] - poly[i - 1];
    const double t = std::clamp((p - poly[i - 1]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (poly[i - 1] + t * ab - p).norm());
  }
  return best;
}

TEST(Flight, TakesOffAndHoversWithin5cmFor10s) {
  const FlightLog log = fly(kWorlds + "open_field.xml", {{Vec3(0, 0, 2), std::nullopt}}, 18.0);
  ASSERT_FALSE(log.collision);
  ASSERT_TRUE(log.finished);
  double worst = 0;
  for (const auto& s : log.samples)
    if (s.t >= 8.0) worst = std::max(worst, (s.pos - Vec3(0, 0, 2)).norm());
  EXPECT_LT(worst, 0.05);
  EXPECT_GT(log.samples.back().t, 17.9);
}

TEST(Flight, GroundContactBeforeTakeOffIsNotACollision) {
  // Resting on the ground for 2 s with zero thrust, then take off.
  const FlightLog log = fly(kWorlds + "open_field.xml", {{Vec3(0, 0, 1), std::nullopt}}, 6.0);
  EXPECT_FALSE(log.collision);
}

TEST(Flight, SquareAt4mpsIsTrackedWithRmsBelow30cm) {
  std::vector<Waypoint> path = {
      {Vec3(0, 0, 2), {}}, {Vec3(20, 0, 2), {}}, {Vec3(20, 20, 2), {}}, {Vec3(0, 20, 2), {}}, {Vec3(0, 0, 2), {}}};
  const FlightLog log = fly(kWorlds + "open_field.xml", path, 60.0, TrajectoryLimits::preset("medium"), 1.0);
  ASSERT_FALSE(log.collision);
  ASSERT_TRUE(log.finished);
  EXPECT_GT(maxSpeed(log), 3.9);
  EXPECT_LT(rmsError(log), 0.3);
  // The heading follows the direction of travel (the reference turns at ≤ 1 rad/s).
  double worst_yaw = 0;
  for (const auto& s : log.samples) worst_yaw = std::max(worst_yaw, s.yaw_error);
  EXPECT_LT(worst_yaw, 0.2);
  // The flown path stays close to the commanded square (corners are rounded).
  std::vector<Vec3> poly = {Vec3(0, 0, 0.05)};  // take-off point
  for (const auto& w : path) poly.push_back(w.position_m);
  double sum = 0;
  for (const auto& s : log.samples) sum += std::pow(distToPath(s.pos, poly), 2);
  EXPECT_LT(std::sqrt(sum / log.samples.size()), 0.3);
}

TEST(Flight, FigureEightAt4mpsIsTrackedWithRmsBelow30cm) {
  // Lemniscate of Gerono, 40 m x 20 m, sampled every ~0.5 m.
  std::vector<Waypoint> path = {{Vec3(0, 0, 2), {}}};
  for (int i = 1; i <= 240; ++i) {
    const double s = 2 * M_PI * i / 240.0;
    path.push_back({Vec3(20 * std::sin(s), 20 * std::sin(s) * std::cos(s), 2), {}});
  }
  const FlightLog log = fly(kWorlds + "open_field.xml", path, 90.0, TrajectoryLimits::preset("medium"), 1.0);
  ASSERT_FALSE(log.collision);
  ASSERT_TRUE(log.finished);
  EXPECT_GT(maxSpeed(log), 3.8);
  EXPECT_LT(rmsError(log), 0.3);
}

TEST(Flight, FastLimitsAreTrackedToo) {
  std::vector<Waypoint> path = {{Vec3(0, 0, 2), {}}, {Vec3(40, 0, 2), {}}, {Vec3(40, 30, 4), {}}};
  const FlightLog log = fly(kWorlds + "open_field.xml", path, 40.0, TrajectoryLimits::preset("fast"), 1.0);
  ASSERT_FALSE(log.collision);
  EXPECT_GT(maxSpeed(log), 7.5);
  EXPECT_LT(rmsError(log), 0.3);
}

TEST(Flight, FlyingIntoAWallEndsWithCollidedAtTheRightTimeAndPlace) {
  // Level flight at 2 m/s towards the wall face x = 10 m; the front rotor discs reach
  // 0.163 + 0.13 = 0.293 m ahead of the body origin.
  TrajectoryLimits slow = TrajectoryLimits::preset("medium");
  slow.max_speed_mps = 2.0;
  const FlightLog log = fly(kWorlds + "wall_ahead.xml", {{Vec3(0, 0, 2), {}}, {Vec3(20, 0, 2), {}}}, 30.0, slow);
  ASSERT_TRUE(log.collision);
  const auto& c = *log.collision;
  EXPECT_EQ(c.world_geom, "wall");
  EXPECT_TRUE(c.vehicle_geom == "vehicle_rotor_fl" || c.vehicle_geom == "vehicle_rotor_fr") << c.vehicle_geom;
  EXPECT_NEAR(c.vehicle_position_m.x(), 10.0 - 0.293, 0.03);
  EXPECT_NEAR(c.vehicle_position_m.z(), 2.0, 0.1);
  EXPECT_NEAR(c.contact_position_m.x(), 10.0, 0.01);
  // The right time: the first tick at which the vehicle's front reached the wall.
  const auto& last = log.samples.back();  // the tick before detection
  EXPECT_LT(last.pos.x() + 0.293, 10.0 + 1e-3);
  EXPECT_NEAR(c.t_s, last.t + 0.002, 1e-9);
  EXPECT_GT(c.t_s, 5.0);
}

TEST(Collision, TheContactGateChangesNoStateAndNoCollision) {
  // Into the wall with collision detection in every step and only where the gate allows it:
  // the same states bit for bit, the same contact at the same tick.
  TrajectoryLimits slow = TrajectoryLimits::preset("medium");
  slow.max_speed_mps = 2.0;
  const std::vector<Waypoint> path = {{Vec3(0, 0, 2), {}}, {Vec3(20, 0, 2), {}}};
  PhysicsConfig every_step;
  every_step.contact_gate = false;
  const FlightLog gated = fly(kWorlds + "wall_ahead.xml", path, 30.0, slow);
  const FlightLog full = fly(kWorlds + "wall_ahead.xml", path, 30.0, slow, 1e9, every_step);
  EXPECT_EQ(full.steps_skipped, 0);
  EXPECT_GT(gated.steps_skipped, int64_t(gated.samples.size()) / 2);  // most of the flight is far from the wall
  ASSERT_EQ(gated.samples.size(), full.samples.size());
  for (size_t i = 0; i < full.samples.size(); ++i) {
    ASSERT_EQ(gated.samples[i].pos, full.samples[i].pos) << "tick " << i;
    ASSERT_EQ(gated.samples[i].vel, full.samples[i].vel) << "tick " << i;
  }
  ASSERT_TRUE(gated.collision && full.collision);
  EXPECT_EQ(gated.collision->tick, full.collision->tick);
  EXPECT_EQ(gated.collision->vehicle_geom, full.collision->vehicle_geom);
  EXPECT_EQ(gated.collision->contact_position_m, full.collision->contact_position_m);
}

TEST(Collision, StaticWorldGeomsAreNeverTestedAgainstEachOther) {
  // The test world's walls and blocks intersect the ground plane; were world–world pairs
  // tested, MuJoCo would report contacts every step.
  QuadrotorSim sim(PhysicsConfig{}, std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml",
                   poseFromXyzYaw(Vec3(0, 0, 2), 0));
  ASSERT_GT(sim.geomCount(), 40);
  for (int i = 0; i < 50; ++i) {
    EXPECT_FALSE(sim.beginTick());
    EXPECT_EQ(sim.data()->ncon, 0);
    sim.endTick(Vec4::Constant(1.325 * 9.81 / 4));
  }
}

TEST(Flight, YawStepsSettleWithinFiveSeconds) {
  // Regression: yaw torque used to be dropped whenever the motors saturated, which for a
  // quadrotor's weak yaw authority meant no yaw control at all for large heading errors.
  for (double step : {1.0, 2.5, -3.0}) {
    QuadrotorSim sim(PhysicsConfig{}, kWorlds + "open_field.xml", poseFromXyzYaw(Vec3(0, 0, 5), 0));
    const Se3Controller ctrl(Se3ControllerConfig{}, QuadrotorConfig{});
    TrajectoryReference ref;
    ref.position_m = Vec3(0, 0, 5);
    ref.yaw_rad = step;
    double worst_pos = 0;
    for (int i = 0; i < 2500; ++i) {
      sim.beginTick();
      const Odometry gt = sim.groundTruth();
      worst_pos = std::max(worst_pos, (gt.T_W_B.translation() - ref.position_m).norm());
      sim.endTick(ctrl.compute(gt, ref));
    }
    EXPECT_LT(std::abs(wrapAngle(yawOf(sim.groundTruth().T_W_B.linear()) - step)), 0.02) << step;
    EXPECT_LT(worst_pos, 0.1) << step;
  }
}

TEST(Flight, MotorLagIsFirstOrderWithTheConfiguredTimeConstant) {
  QuadrotorSim sim(PhysicsConfig{}, kWorlds + "open_field.xml", poseFromXyzYaw(Vec3(0, 0, 5), 0));
  // Step all motors from 0 to 4 N: after one time constant (30 ms = 15 ticks) ≈ 63 %.
  for (int i = 0; i < 15; ++i) {
    sim.beginTick();
    sim.endTick(Vec4::Constant(4.0));
  }
  EXPECT_NEAR(sim.motorThrusts()[0] / 4.0, 1.0 - std::exp(-1.0), 0.02);
}

}  // namespace
}  // namespace msb
