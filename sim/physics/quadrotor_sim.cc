#include "sim/physics/quadrotor_sim.h"
#include "sim/world/mjcf_world_builder.h"  // kGroundConaffinityBit (a constant: no link dependency)

#include "sim/physics/mjcf_files.h"
#include "sim/physics/mujoco_messages.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace msb {

void PhysicsConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

namespace {

// MuJoCo reports errors through a global handler; route them to exceptions while loading.
// (Only the compile step uses it; it is restored right after.)
thread_local std::string g_mj_warning;
void recordWarning(const char* msg) { g_mj_warning = msg; }

// A geom as messages name it: 'name', or 'geom#id' when it has none.
std::string quotedGeomName(const mjModel* m, int g) {
  const char* name = mj_id2name(m, mjOBJ_GEOM, g);
  std::string out = "'";
  out += name ? std::string(name) : "geom#" + std::to_string(g);
  return out + "'";
}

}  // namespace

QuadrotorSim::QuadrotorSim(const PhysicsConfig& config, const std::string& world_xml_path, const Pose& start_T_W_B)
    : config_(checkValid(config)) {
  namespace fs = std::filesystem;
  installMujocoHandlers();
  // The world file and a wrapper that includes it, both as virtual files in the world's
  // directory (relative texture and mesh paths resolve against the world file).
  // Every XML file MuJoCo would read (the world and its includes), checked and read here.
  const std::vector<std::pair<std::string, std::string>> files = readMjcfFiles(world_xml_path);
  const std::string& world = files.front().second;
  const fs::path dir = fs::absolute(world_xml_path).parent_path();
  const std::string world_name = fs::path(world_xml_path).filename().string();
  const std::string wrapper_name = "msbench_composed_model.xml";
  if (world_name == wrapper_name || world_name.find('"') != std::string::npos)
    throw ConfigError("world", world_xml_path + ": unsupported world file name");
  const std::string xml = composeModelXml(world_name, config_.vehicle, start_T_W_B, 1.0 / config_.physics_hz);
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  auto addFile = [&](const std::string& name, const std::string& text) {
    const std::string path = (dir / name).string();
    if (mj_makeEmptyFileVFS(vfs.get(), path.c_str(), static_cast<int>(text.size())) != 0)
      throw std::runtime_error(world_xml_path + ": cannot create MuJoCo virtual file");
    const int idx = mj_findFileVFS(vfs.get(), path.c_str());
    std::copy(text.begin(), text.end(), static_cast<char*>(vfs->filedata[idx]));
  };
  addFile(world_name, world);
  addFile(wrapper_name, xml);
  for (size_t i = 1; i < files.size(); ++i)
    addFile(fs::path(files[i].first).lexically_relative(dir).string(), files[i].second);

  char error[1024] = "";
  auto* prev_warning = mju_user_warning;
  mju_user_warning = recordWarning;
  g_mj_warning.clear();
  try {
    m_ = mj_loadXML((dir / wrapper_name).string().c_str(), vfs.get(), error, sizeof(error));
  } catch (const MujocoError& e) {
    mju_user_warning = prev_warning;
    mj_deleteVFS(vfs.get());
    throw ConfigError("world", world_xml_path + ": MuJoCo error: " + e.what());
  }
  mju_user_warning = prev_warning;
  mj_deleteVFS(vfs.get());
  if (!m_) throw ConfigError("world", world_xml_path + ": MuJoCo could not compile: " + error);
  if (error[0] != '\0' || !g_mj_warning.empty()) {
    mj_deleteModel(m_);
    m_ = nullptr;
    throw ConfigError("world", world_xml_path + ": MuJoCo warning: " + (error[0] ? std::string(error) : g_mj_warning));
  }
  // The simulator owns the options: a world that sets its own would change the physics.
  if (m_->opt.timestep != 1.0 / config_.physics_hz || m_->opt.integrator != mjINT_EULER) {
    mj_deleteModel(m_);
    m_ = nullptr;
    throw ConfigError("world", world_xml_path + ": world MJCF must not set <option> (the simulator owns it)");
  }
  try {
    d_ = mj_makeData(m_);
  } catch (const MujocoError& e) {
    mj_deleteModel(m_);
    m_ = nullptr;
    throw ConfigError("world", world_xml_path + ": MuJoCo error: " + e.what());
  }

  // Cache addresses of the vehicle's state and IMU sensors (every lookup checked).
  body_id_ = mj_name2id(m_, mjOBJ_BODY, mjcf_names::kVehicleBody);
  const int accel = mj_name2id(m_, mjOBJ_SENSOR, mjcf_names::kAccelSensor);
  const int gyro = mj_name2id(m_, mjOBJ_SENSOR, mjcf_names::kGyroSensor);
  if (body_id_ < 0 || accel < 0 || gyro < 0 || m_->body_jntadr[body_id_] < 0) {
    mj_deleteData(d_);
    mj_deleteModel(m_);
    d_ = nullptr;
    m_ = nullptr;
    throw ConfigError(
        "world", world_xml_path + ": the composed model lacks the vehicle (a world element collides with its names?)");
  }
  const int jnt = m_->body_jntadr[body_id_];
  qpos_adr_ = m_->jnt_qposadr[jnt];
  qvel_adr_ = m_->jnt_dofadr[jnt];
  accel_adr_ = m_->sensor_adr[accel];
  gyro_adr_ = m_->sensor_adr[gyro];
  start_z_ = start_T_W_B.translation().z();
  mj_forward(m_, d_);
  try {
    checkWorldGeometry(world_xml_path);
    checkStartPose(world_xml_path);
    if (config_.contact_gate) gate_.emplace(m_, d_, body_id_);
  } catch (...) {
    mj_deleteData(d_);
    mj_deleteModel(m_);
    d_ = nullptr;
    m_ = nullptr;
    throw;
  }
}

std::vector<GroundPlane> QuadrotorSim::groundPlanes() const {
  // A colliding plane facing up. MuJoCo collides with a plane as a half-space (below it is
  // inside the ground); its drawn size is the world's extent.
  std::vector<GroundPlane> out;
  for (int g = 0; g < m_->ngeom; ++g) {
    if (m_->geom_type[g] != mjGEOM_PLANE || m_->geom_bodyid[g] == body_id_) continue;
    if (m_->geom_contype[g] == 0 && m_->geom_conaffinity[g] == 0) continue;  // drawn only (sky)
    const mjtNum* R = d_->geom_xmat + 9 * g;
    if (R[8] < 0.999) continue;  // a wall or ceiling plane, not the ground
    GroundPlane p;
    p.name = quotedGeomName(m_, g);
    p.centre = Vec3(d_->geom_xpos[3 * g], d_->geom_xpos[3 * g + 1], d_->geom_xpos[3 * g + 2]);
    p.half_size = Vec2(m_->geom_size[3 * g], m_->geom_size[3 * g + 1]);
    out.push_back(p);
  }
  return out;
}

bool QuadrotorSim::hasGround() const {
  if (!groundPlanes().empty()) return true;
  for (int g = 0; g < m_->ngeom; ++g)
    if (m_->geom_bodyid[g] != body_id_ && (m_->geom_conaffinity[g] & kGroundConaffinityBit)) return true;
  return false;
}

std::string QuadrotorSim::outsideTheWorld(const Vec3& p) const {
  char text[256];
  for (const GroundPlane& g : groundPlanes()) {
    if (p.z() < g.centre.z()) {
      std::snprintf(text, sizeof(text), "is below the ground plane %s (z = %g)", g.name.c_str(), g.centre.z());
      return text;
    }
    const Vec2 d = (p.head<2>() - g.centre.head<2>()).cwiseAbs();
    if ((g.half_size.array() > 0).all() && (d.array() > g.half_size.array()).any()) {
      std::snprintf(text, sizeof(text), "is outside the world (its ground %s spans x in [%g, %g], y in [%g, %g])",
                    g.name.c_str(), g.centre.x() - g.half_size.x(), g.centre.x() + g.half_size.x(),
                    g.centre.y() - g.half_size.y(), g.centre.y() + g.half_size.y());
      return text;
    }
  }
  return "";
}

void QuadrotorSim::checkWorldGeometry(const std::string& world_xml_path) const {
  // A world is something to explore and to hit: collision geoms besides the vehicle, which the
  // vehicle's geoms can touch (MuJoCo's rule: contype of one & conaffinity of the other).
  int vehicle_type = 0, vehicle_affinity = 0;
  for (int g = 0; g < m_->ngeom; ++g)
    if (m_->geom_bodyid[g] == body_id_)
      vehicle_type |= m_->geom_contype[g], vehicle_affinity |= m_->geom_conaffinity[g];
  bool collides = false, touchable = false;
  for (int g = 0; g < m_->ngeom; ++g) {
    if (m_->geom_bodyid[g] == body_id_) continue;
    collides = collides || m_->geom_contype[g] != 0 || m_->geom_conaffinity[g] != 0;
    touchable =
        touchable || (m_->geom_contype[g] & vehicle_affinity) != 0 || (vehicle_type & m_->geom_conaffinity[g]) != 0;
  }
  if (!collides)
    throw ConfigError("world", world_xml_path + ": the world has no collision geometry (nothing to explore or to hit)");
  if (!touchable)
    throw ConfigError("world", world_xml_path +
                                   ": no geom of the world can touch the vehicle (their contype/conaffinity bits "
                                   "never meet the vehicle's): a run could not collide");
}

void QuadrotorSim::checkStartPose(const std::string& world_xml_path) const {
  const Vec3 p(d_->qpos[qpos_adr_], d_->qpos[qpos_adr_ + 1], d_->qpos[qpos_adr_ + 2]);
  char where[96];
  std::snprintf(where, sizeof(where), "the start position (%g, %g, %g)", p.x(), p.y(), p.z());
  if (const std::string why = outsideTheWorld(p); !why.empty())
    throw ConfigError("start.position", std::string(where) + " of " + world_xml_path + " " + why);
  // Inside an obstacle: a contact with a world geom at t = 0 (the same test that ends a run;
  // before take-off, resting on the ground is no contact).
  if (const auto hit = checkContacts())
    throw ConfigError("start.position", std::string(where) + " puts the vehicle inside geom '" + hit->world_geom +
                                            "' of " + world_xml_path);
}

QuadrotorSim::~QuadrotorSim() {
  if (d_) mj_deleteData(d_);
  if (m_) mj_deleteModel(m_);
}

std::optional<CollisionEvent> QuadrotorSim::beginTick() {
  // Collision detection only where a contact is possible: otherwise MuJoCo runs the step with
  // contacts disabled, which it treats as a detection that found none.
  const Vec3 p(d_->qpos[qpos_adr_], d_->qpos[qpos_adr_ + 1], d_->qpos[qpos_adr_ + 2]);
  const bool detect = !gate_ || gate_->mayTouch(p);
  if (!detect) m_->opt.disableflags |= mjDSBL_CONTACT;
  mj_step1(m_, d_);
  if (!detect) m_->opt.disableflags &= ~mjDSBL_CONTACT;
  ++(detect ? steps_detected_ : steps_skipped_);
  if (!airborne_ && d_->qpos[qpos_adr_ + 2] > start_z_ + config_.takeoff_clearance_m) airborne_ = true;
  auto hit = checkContacts();
  if (hit && !collision_) collision_ = hit;
  return hit;
}

std::optional<CollisionEvent> QuadrotorSim::checkContacts() const {
  for (int i = 0; i < d_->ncon; ++i) {
    const mjContact& c = d_->contact[i];
    if (c.dist > 0.0) continue;
    const bool v1 = m_->geom_bodyid[c.geom1] == body_id_;
    const bool v2 = m_->geom_bodyid[c.geom2] == body_id_;
    if (v1 == v2) continue;  // not a vehicle–world pair
    const int vg = v1 ? c.geom1 : c.geom2;
    const int wg = v1 ? c.geom2 : c.geom1;
    // Resting on the ground (a plane, or an imported terrain's piece) before take-off is not a
    // collision.
    const bool ground = m_->geom_type[wg] == mjGEOM_PLANE || (m_->geom_conaffinity[wg] & kGroundConaffinityBit);
    if (!airborne_ && ground) continue;
    CollisionEvent ev;
    ev.tick = tick_;
    ev.t_s = timeSeconds();
    ev.vehicle_position_m = Vec3(d_->qpos[qpos_adr_], d_->qpos[qpos_adr_ + 1], d_->qpos[qpos_adr_ + 2]);
    ev.contact_position_m = Vec3(c.pos[0], c.pos[1], c.pos[2]);
    const char* vn = mj_id2name(m_, mjOBJ_GEOM, vg);
    const char* wn = mj_id2name(m_, mjOBJ_GEOM, wg);
    ev.vehicle_geom = vn ? vn : "geom#" + std::to_string(vg);
    ev.world_geom = wn ? wn : "geom#" + std::to_string(wg);
    return ev;
  }
  return std::nullopt;
}

void QuadrotorSim::endTick(const Vec4& cmd) {
  for (int i = 0; i < 4; ++i) d_->ctrl[i] = std::clamp(cmd[i], 0.0, config_.vehicle.max_thrust_n);
  mj_step2(m_, d_);
  // Sensors of mj_step2 describe the state before integration (x_n).
  const mjtNum* s = d_->sensordata;
  imu_truth_.specific_force_mps2 = Vec3(s[accel_adr_], s[accel_adr_ + 1], s[accel_adr_ + 2]);
  imu_truth_.angular_rate_radps = Vec3(s[gyro_adr_], s[gyro_adr_ + 1], s[gyro_adr_ + 2]);
  ++tick_;
}

Odometry QuadrotorSim::groundTruth() const {
  Odometry o;
  o.tick = tick_;
  o.t_s = timeSeconds();
  const mjtNum* q = d_->qpos + qpos_adr_;
  o.T_W_B.translation() = Vec3(q[0], q[1], q[2]);
  o.T_W_B.linear() = Quat(q[3], q[4], q[5], q[6]).normalized().toRotationMatrix();
  // Free joint: linear velocity in world frame, angular velocity in body frame.
  const mjtNum* v = d_->qvel + qvel_adr_;
  o.v_W_mps = Vec3(v[0], v[1], v[2]);
  o.omega_B_radps = Vec3(v[3], v[4], v[5]);
  return o;
}

Vec4 QuadrotorSim::motorThrusts() const { return Vec4(d_->act[0], d_->act[1], d_->act[2], d_->act[3]); }

std::map<std::string, int> QuadrotorSim::warningCounts() const { return mujocoWarningCounts(d_); }

bool QuadrotorSim::diverged() const {
  for (int i = 0; i < m_->nq; ++i)
    if (!std::isfinite(d_->qpos[i])) return true;
  for (int i = 0; i < m_->nv; ++i)
    if (!std::isfinite(d_->qvel[i])) return true;
  return d_->warning[mjWARN_BADQACC].number > 0;
}

}  // namespace msb
