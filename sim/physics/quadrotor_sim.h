// The physical simulation: MuJoCo model (world + quadrotor), one tick = one physics step.
// A tick is split as MuJoCo's mj_step1 / mj_step2 so that everything in between (contacts,
// sensors, rendering, perception, planning, control) sees the same state x_n:
//   beginTick(): kinematics + collision detection of x_n, contact check
//   ... caller reads state, renders, computes motor commands ...
//   endTick(thrusts): dynamics with the new commands, IMU truth of x_n, integrate to x_{n+1}
#pragma once

#include <mujoco/mujoco.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "sim/physics/contact_gate.h"
#include "sim/physics/quadrotor_model.h"

namespace msb {

/// Configuration of the physical simulation.
struct PhysicsConfig {
  int physics_hz = 500;               ///< physics rate (one tick = one step)
  QuadrotorConfig vehicle;            ///< vehicle parameters
  double takeoff_clearance_m = 0.15;  ///< ground contact is allowed until first this high
  bool contact_gate = true;           ///< skip collision detection in steps where no contact is
                                      ///< possible (ContactGate; the same states and contacts)

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("physics_hz", s.physics_hz, Limits::range(100, 5000));
    v.key("takeoff_clearance_m", s.takeoff_clearance_m, Limits::nonNegative());
    v.key("contact_gate", s.contact_gate);
    v.group("vehicle", s.vehicle);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Details of the contact that ended a run.
struct CollisionEvent {
  int64_t tick = 0;          ///< tick of detection
  double t_s = 0.0;          ///< simulated time
  Vec3 vehicle_position_m;   ///< body origin at detection
  Vec3 contact_position_m;   ///< contact point
  std::string vehicle_geom;  ///< name of the vehicle's geom
  std::string world_geom;    ///< name (or "geom#id") of the world's geom
};

/// Noise-free IMU quantities at the last completed tick (body frame).
struct ImuTruth {
  Vec3 specific_force_mps2 = Vec3::Zero();  ///< accelerometer truth
  Vec3 angular_rate_radps = Vec3::Zero();   ///< gyroscope truth
};

/// A world's ground: a colliding horizontal plane (MuJoCo collides with it as a half-space).
struct GroundPlane {
  std::string name;               ///< the geom, quoted ('ground')
  Vec3 centre = Vec3::Zero();     ///< its position (z = the ground's height)
  Vec2 half_size = Vec2::Zero();  ///< its drawn extent (the world's); 0 = unbounded
};

/// MuJoCo quadrotor in a world. Owns mjModel and mjData; single-threaded.
class QuadrotorSim {
 public:
  /// Loads the world MJCF file, adds the vehicle at `start_T_W_B` and compiles. Throws
  /// ConfigError (key `world`) naming the file and MuJoCo's message when the world does not load,
  /// and ConfigError (key `start.position`) when the start pose lies below the ground, beyond
  /// the ground plane's extent or inside a world geom.
  QuadrotorSim(const PhysicsConfig& config, const std::string& world_xml_path, const Pose& start_T_W_B);
  ~QuadrotorSim();
  QuadrotorSim(const QuadrotorSim&) = delete;
  QuadrotorSim& operator=(const QuadrotorSim&) = delete;

  /// Step 1 of a tick: kinematics and collision detection of the current state. Returns the
  /// collision, if the vehicle touches the world (also kept in `collision()`).
  std::optional<CollisionEvent> beginTick();
  /// Step 2 of a tick: applies motor thrust commands (N, FL FR BR BL), computes dynamics and
  /// IMU truth for the current state, integrates to the next tick.
  void endTick(const Vec4& motor_thrust_cmd_n);

  /// Current tick (number of completed steps).
  int64_t tick() const { return tick_; }
  /// Current simulated time.
  double timeSeconds() const { return static_cast<double>(tick_) / config_.physics_hz; }
  /// Ground-truth odometry of the current state.
  Odometry groundTruth() const;
  /// IMU truth computed in the last endTick().
  const ImuTruth& imuTruth() const { return imu_truth_; }
  /// Current (lagged) motor thrusts in N.
  Vec4 motorThrusts() const;
  /// First collision seen, if any.
  const std::optional<CollisionEvent>& collision() const { return collision_; }
  /// True if a non-finite state was detected (status `diverged`).
  bool diverged() const;
  /// The world's ground planes.
  std::vector<GroundPlane> groundPlanes() const;
  /// True if the world has a ground to take off from: a ground plane, or the pieces of an
  /// imported terrain (world geoms with the ground conaffinity bit, sim/world/mjcf_world_builder.h).
  bool hasGround() const;
  /// Why `p` lies outside the world ("is below the ground plane 'ground' (z = 0)", "is outside
  /// the world (its ground ... spans ...)"), or "" if it lies within it.
  std::string outsideTheWorld(const Vec3& p) const;
  /// MuJoCo's non-zero warning counters so far, by name (metrics.json `mujoco_warnings`).
  std::map<std::string, int> warningCounts() const;

  /// MuJoCo model (the renderer may adjust visual settings only).
  mjModel* model() { return m_; }
  const mjModel* model() const { return m_; }
  /// MuJoCo data.
  const mjData* data() const { return d_; }
  /// The validated configuration.
  const PhysicsConfig& config() const { return config_; }
  /// Number of geoms in the compiled model.
  int geomCount() const { return m_->ngeom; }
  /// beginTick() calls so far that ran MuJoCo's collision detection, and that skipped it
  /// (contact_gate).
  int64_t stepsDetected() const { return steps_detected_; }
  int64_t stepsSkipped() const { return steps_skipped_; }
  /// The contact gate, if configured.
  const ContactGate* contactGate() const { return gate_ ? &*gate_ : nullptr; }

 private:
  std::optional<CollisionEvent> checkContacts() const;
  // Refuses a start pose below the ground, beyond the ground's extent or inside a world geom.
  // Refuses a world without any collision geom of its own or without one the vehicle can touch
  // (ConfigError, key `world`).
  void checkWorldGeometry(const std::string& world_xml_path) const;
  void checkStartPose(const std::string& world_xml_path) const;

  PhysicsConfig config_;
  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
  int body_id_ = -1;
  int qpos_adr_ = 0, qvel_adr_ = 0;
  int accel_adr_ = 0, gyro_adr_ = 0;
  int64_t tick_ = 0;
  int64_t steps_detected_ = 0, steps_skipped_ = 0;
  std::optional<ContactGate> gate_;
  bool airborne_ = false;
  double start_z_ = 0.0;
  ImuTruth imu_truth_;
  std::optional<CollisionEvent> collision_;
};

}  // namespace msb
