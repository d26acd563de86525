#include "tools/engine/closed_loop.h"

#include <cmath>

#include "core/common/rng.h"
#include "core/common/wall_time.h"
#include "core/explorer/output_limits.h"
#include "core/geometry/world_truth.h"
#include "core/perception/oracle_features.h"
#include "sim/render/fisheye_renderer.h"

namespace msb {

namespace {

// The renderer named by camera_stream.renderer (none when the stream is off).
std::unique_ptr<FrameRenderer> makeRenderer(const FlightSpec& spec, const FisheyeCamera& camera, QuadrotorSim& sim) {
  if (!spec.camera_stream.enabled) return nullptr;
  if (spec.camera_stream.renderer == RendererKind::kBlank) return std::make_unique<NullRenderer>(camera);
  return std::make_unique<FisheyeRenderer>(spec.render, camera, sim.model());
}

// The feature source named by perception.source (none when perception is off).
std::unique_ptr<FeatureSource> makeFeatureSource(const FlightSpec& spec, const FisheyeCamera& camera,
                                                 const WorldTruth* truth) {
  if (!spec.perception.enabled) return nullptr;
  if (spec.perception.source == FeatureSourceKind::kOracle) {
    if (!truth)
      throw ConfigError("perception.source",
                        "'oracle' needs a generated world (its ground truth); this world has none");
    return std::make_unique<OracleFeatureSource>(spec.perception.oracle, camera, *truth, spec.seed);
  }
  auto tracker = std::make_unique<KltFeatureTracker>(spec.tracker, camera);
  if (spec.frontend.mistrack_share > 0.0)
    tracker->setMistracks(MistrackModel(spec.frontend.mistrack_share, spec.frontend.mistrack_px, spec.seed));
  return tracker;
}

}  // namespace

ClosedLoop::ClosedLoop(const FlightSpec& spec, const LoopSetup& setup)
    : spec_(checkValid(spec)),
      setup_(setup),
      sim_(spec.physics, spec.world_path, poseFromXyzYaw(spec.start_position_m, spec.start_yaw_rad)),
      camera_(spec.camera),
      renderer_(makeRenderer(spec, camera_, sim_)),
      controller_(spec.controller, spec.physics.vehicle),
      trajectory_(spec.trajectory, spec.start_position_m, spec.start_yaw_rad),
      imu_(spec.imu, spec.seed),
      vio_(scaledDrift(spec.vio_drift, spec.frontend.drift_scale), spec.seed),
      features_(makeFeatureSource(spec, camera_, setup.truth)),
      last_position_(spec.start_position_m),
      wall_start_(WallClock::now()) {
  if (spec.perception.enabled)
    slam_ = std::make_unique<SlamPointEstimator>(spec.slam_points, camera_, spec.camera_stream.rate_hz);
  if (spec.frontend.image_noise_sigma > 0.0) image_noise_.emplace(spec.frontend.image_noise_sigma, spec.seed);
  if (spec.frontend.landmark_jitter_inv_depth > 0.0)
    jitter_.emplace(spec.frontend.landmark_jitter_inv_depth, spec.seed);
  // A flight needs a ground to take off from and to stay above.
  if (!sim_.hasGround())
    throw ConfigError(
        "world", spec.world_path + ": the world has no ground (a colliding plane facing up, or an imported terrain)");
  if (renderer_) result_.gl_description = renderer_->description();
  if (!setup_.explorer) {
    // A scripted path stays inside the world (above its ground, within its extent).
    for (size_t i = 0; i < spec.waypoints.size(); ++i)
      if (const std::string why = sim_.outsideTheWorld(spec.waypoints[i].position_m); !why.empty())
        throw ConfigError("trajectory.waypoints[" + std::to_string(i) + "]", "the waypoint " + why);
    trajectory_.setPath(spec.waypoints);
  }

  // Integer schedules of every stage.
  const int hz = spec.physics.physics_hz;
  const TickClock clock(hz);
  ctrl_div_ = clock.divisorFor(spec.controller_hz, "controller_hz");
  ctrl_dt_ = double(ctrl_div_) * clock.tickSeconds();
  cam_schedule_.emplace(hz, spec.camera_stream.rate_hz, "camera_stream.rate_hz");
  imu_schedule_.emplace(hz, spec.imu.rate_hz, "imu.rate_hz");
  traj_schedule_.emplace(hz, setup.trajectory_rate_hz, "trajectory");
  if (setup_.explorer) {
    map_schedule_.emplace(hz, setup.map_rate_hz, "mission.map_rate_hz");
    plan_schedule_.emplace(hz, setup.planning_rate_hz, "mission.planning_rate_hz");
  }
  lost_ticks_ = clock.ticksFor(spec.perception.lost_after_s);
  max_ticks_ = clock.ticksFor(spec.duration_s);
  hold_ticks_ = clock.ticksFor(spec.hold_after_s);
  startPipeline(spec, setup);
}

void ClosedLoop::startPipeline(const FlightSpec& spec, const LoopSetup& setup) {
  if (!features_) {
    if (setup.explorer) throw ConfigError("perception.enabled", "an exploration method needs perception");
    return;
  }
  // The explorer's map updates and plans run with a frame's perception: on camera ticks only.
  auto onCameraTicks = [&](double rate_hz, const char* key) {
    const int64_t cam = std::llround(spec.camera_stream.rate_hz * 1000), r = std::llround(rate_hz * 1000);
    if (r <= 0 || cam % r != 0)
      throw ConfigError(key, "must divide camera_stream.rate_hz (" + std::to_string(spec.camera_stream.rate_hz) +
                                 " Hz): map updates and plans run with a frame's perception");
  };
  if (setup.explorer) {
    onCameraTicks(setup.map_rate_hz, "mission.map_rate_hz");
    onCameraTicks(setup.planning_rate_hz, "mission.planning_rate_hz");
  }
  const int depth = spec.perception.latency_frames;
  const bool threaded = spec.perception.threads == 2 && depth > 0;
  PerceptionStages stages{features_.get(),
                          slam_.get(),
                          jitter_ ? &*jitter_ : nullptr,
                          setup.explorer,
                          [this](const PathCommand& cmd, const VehicleState& vs) { checkWaypoints(cmd, vs); },
                          setup.compute};
  stages.compute.physics_hz = spec.physics.physics_hz;
  stages.compute.frame_ticks =
      std::max<int64_t>(1, int64_t(double(spec.physics.physics_hz) / spec.camera_stream.rate_hz));
  pipeline_ = std::make_unique<PerceptionPipeline>(depth, threaded, std::move(stages));
  if (threaded) result_.threads = 2;
}

ClosedLoop::~ClosedLoop() = default;

bool ClosedLoop::running() const { return !ended_ && sim_.tick() < max_ticks_; }

const TickRecord& ClosedLoop::step() {
  record_ = TickRecord{};
  record_.tick = sim_.tick();
  record_.t_s = sim_.timeSeconds();
  // Physics step 1 and contacts: a collision or a non-finite state ends the run.
  if (!stepPhysicsAndContacts()) return record_;
  // The VIO estimate of the true state (the controller and the planner fly on it).
  estimateState();
  // Camera, then perception: what is due (latency_frames back), this frame's job (tracks, SLAM
  // points, the method's map update and plan due now), what is due again (latency 0: this
  // frame's). Tracking loss ends the run; the method's path replaces the tracker's.
  if (renderer_ && cam_schedule_->due(record_.tick)) {
    renderFrame();
    if (pipeline_) {
      if (!usePerception()) return record_;
      launchPerception();
      if (!usePerception()) return record_;
    }
  }
  // Paths whose planning step ended by now (compute in the loop); then the trajectory reference
  // and controller; records; actuators, integration and the IMU.
  if (!ending_paths_.empty()) takeEndedPaths();
  trackAndControl();
  recordTick();
  actuateAndSampleImu();
  // A scripted flight ends hold_after_s after its path.
  if (!setup_.explorer && finished_tick_ >= 0 && record_.tick >= finished_tick_ + hold_ticks_) ended_ = true;
  record_.completed = true;
  return record_;
}

void ClosedLoop::run() {
  while (running()) step();
}

bool ClosedLoop::stepPhysicsAndContacts() {
  if (sim_.beginTick()) {
    result_.status = RunStatus::kCollided;
    result_.collision = sim_.collision();
    ended_ = true;
    return false;
  }
  if (sim_.diverged()) {
    result_.status = RunStatus::kDiverged;
    ended_ = true;
    return false;
  }
  return true;
}

void ClosedLoop::estimateState() {
  gt_ = sim_.groundTruth();
  est_ = vio_.update(gt_);
}

void ClosedLoop::renderFrame() {
  const Pose T_W_C = gt_.T_W_B * camera_.T_B_C();
  frame_timing_ = RenderTiming{};
  // A frame someone still holds (a Python view, a perception job) is left alone: this one renders
  // into one nobody holds.
  frame_ = frame_pool_.renderTarget(std::move(frame_));
  ++frame_index_;
  CameraFrame& frame = *frame_;
  renderer_->render(sim_.data(), T_W_C, &frame, &frame_timing_);
  frame.tick = record_.tick;
  frame.t_s = gt_.t_s;
  frame.T_W_C = T_W_C;
  if (image_noise_) image_noise_->apply(frame);  // the camera's noise (degradation, off by default)
  auto& sum = result_.render_time_sum;
  sum.scene_ms += frame_timing_.scene_ms;
  sum.render_ms += frame_timing_.render_ms;
  sum.readback_ms += frame_timing_.readback_ms;
  sum.remap_ms += frame_timing_.remap_ms;
  ++result_.frames_rendered;
  record_.frame = frame_.get();
  record_.render = &frame_timing_;
  record_.timing.render_ms = frame_timing_.totalMs();
}

bool ClosedLoop::trackingHolds(const TrackFrame& tracks, int64_t frame_tick) {
  // Perception statistics (records only).
  const int tracked = trackedFromPrevious(tracks);
  if (result_.perception_frames++ > 0) {
    result_.tracked_sum += tracked;
    result_.tracked_min = result_.tracked_min < 0 ? tracked : std::min(result_.tracked_min, tracked);
    result_.frames_few_tracks += tracked < spec_.perception.lost_min_tracks;
  }
  // Tracking loss: too few features tracked from the previous frame (new detections do not
  // count) for lost_after_s.
  if (tracked < spec_.perception.lost_min_tracks) {
    if (few_tracks_since_ < 0) few_tracks_since_ = frame_tick;
  } else {
    few_tracks_since_ = -1;
  }
  if (few_tracks_since_ >= 0 && frame_tick - few_tracks_since_ >= lost_ticks_) {
    result_.status = RunStatus::kVioLost;
    result_.vio_lost_at_s = gt_.t_s;
    ended_ = true;
    return false;
  }
  return true;
}

void ClosedLoop::checkWaypoints(const PathCommand& cmd, const VehicleState& vs) const {
  for (size_t i = 0; i < cmd.waypoints.size(); ++i) {
    if (const auto why = waypointProblem(cmd.waypoints[i], spec_.start_position_m))
      throw MethodOutputError("plan() at t = " + std::to_string(vs.t_s) + " s (tick " + std::to_string(vs.tick) +
                              "): waypoint " + std::to_string(i) + " " + *why);
  }
}

VehicleState ClosedLoop::vehicleState() const {
  VehicleState vs;
  vs.tick = record_.tick;
  vs.t_s = double(record_.tick) / spec_.physics.physics_hz;
  vs.T_W_B = est_.T_W_B;
  vs.velocity_mps = est_.v_W_mps;
  vs.reference = trajectory_.reference();
  // Finished: the tracker is at the end of its path and no path the method sent is still on its
  // way (a planning step's path lands when its compute ends: until then the method's last
  // command is not done, whatever the tracker's previous path says).
  vs.path_finished = trajectory_.finished() && ending_paths_.empty();
  return vs;
}

void ClosedLoop::trackAndControl() {
  if (record_.tick % ctrl_div_ != 0) return;
  // The controller flies on the VIO estimate; the reference lives in the estimate frame.
  const TrajectoryReference& ref = trajectory_.update(ctrl_dt_);
  cmd_ = controller_.compute(est_, ref);
  const double err = (est_.T_W_B.translation() - ref.position_m).norm();
  err_sq_sum_ += err * err;
  ++err_count_;
  result_.tracking_max_m = std::max(result_.tracking_max_m, err);
  if (trajectory_.finished() && finished_tick_ < 0) finished_tick_ = record_.tick;
}

void ClosedLoop::recordTick() {
  if (traj_schedule_->due(record_.tick)) {
    const auto& ref = trajectory_.reference();
    result_.trajectory.push_back({gt_.t_s, gt_.T_W_B.translation(), Quat(gt_.T_W_B.linear()), gt_.v_W_mps,
                                  est_.T_W_B.translation(), yawOf(est_.T_W_B.linear()), ref.position_m, ref.yaw_rad,
                                  Quat(est_.T_W_B.linear())});
    result_.final_drift_m = (est_.T_W_B.translation() - gt_.T_W_B.translation()).norm();
  }
  result_.distance_flown_m += (gt_.T_W_B.translation() - last_position_).norm();
  last_position_ = gt_.T_W_B.translation();
}

void ClosedLoop::actuateAndSampleImu() {
  // Physics step 2 (actuators, integration), then the IMU sample of this tick's state.
  sim_.endTick(cmd_);
  if (!imu_schedule_->due(record_.tick)) return;
  const double tick_s = 1.0 / spec_.physics.physics_hz;
  const double dt = record_.tick == 0 ? 1.0 / spec_.imu.rate_hz : double(record_.tick - last_imu_tick_) * tick_s;
  result_.imu.push_back(
      imu_.sample(record_.tick, gt_.t_s, dt, sim_.imuTruth().specific_force_mps2, sim_.imuTruth().angular_rate_radps));
  last_imu_tick_ = record_.tick;
}

uint64_t ClosedLoop::stateHash() const {
  uint64_t h = hashTrajectory(result_.trajectory);
  const Odometry now = sim_.groundTruth();
  const double v[7] = {now.t_s,
                       now.T_W_B.translation().x(),
                       now.T_W_B.translation().y(),
                       now.T_W_B.translation().z(),
                       now.v_W_mps.x(),
                       now.v_W_mps.y(),
                       now.v_W_mps.z()};
  h = fnv1a64(v, sizeof(v), h);
  for (const auto& s : result_.imu) {
    const double a[6] = {s.accel_mps2.x(), s.accel_mps2.y(), s.accel_mps2.z(),
                         s.gyro_radps.x(), s.gyro_radps.y(), s.gyro_radps.z()};
    h = fnv1a64(a, sizeof(a), h);
  }
  return h;
}

const FlightResult& ClosedLoop::finish() {
  if (finished_) return result_;
  // The perception in flight completes; its error (once) is the run's.
  sync();
  if (pipeline_) {
    pipeline_->rethrowPending();
    result_.perception_wait_ms = pipeline_->waitMs();
    result_.compute_calls = pipeline_->computeCalls();
  }
  finished_ = true;
  result_.ticks = sim_.tick();
  result_.collision_detection_steps = sim_.stepsDetected();
  result_.sim_time_s = sim_.timeSeconds();
  result_.path_finished = finished_tick_ >= 0;
  result_.tracking_rms_m = err_count_ ? std::sqrt(err_sq_sum_ / double(err_count_)) : 0.0;
  result_.trajectory_hash = hashTrajectory(result_.trajectory);
  result_.mujoco_warnings = sim_.warningCounts();
  result_.wall_time_s = secondsSince(wall_start_);
  return result_;
}

void ClosedLoop::launchPerception() {
  // What the job reads is fixed now: the frame, the VIO's pose of it, the state planning starts from.
  auto job = std::make_unique<PerceptionJob>();
  job->frame_index = frame_index_;
  job->tick = record_.tick;
  job->frame = frame_;
  job->camera_estimate = vio_.noisyCameraPose(frame_->T_W_C);
  if (setup_.explorer) {
    job->map_due = map_schedule_->due(record_.tick);
    job->plan_due = plan_schedule_->due(record_.tick);
    // A planning step asked for earlier may start on this frame when compute is charged.
    if (job->plan_due || !setup_.compute.timing.free()) job->plan_state = vehicleState();
  }
  pipeline_->launch(std::move(job));
}

void ClosedLoop::sync() {
  if (pipeline_) pipeline_->sync();
}

void ClosedLoop::abandon() {
  if (pipeline_) pipeline_->abandon();
  ended_ = true;
}

bool ClosedLoop::abandonWithin(std::chrono::milliseconds limit) {
  ended_ = true;
  return !pipeline_ || pipeline_->abandonWithin(limit);
}

bool ClosedLoop::usePerception() {
  const PerceptionJob* due = nullptr;
  try {
    due = pipeline_->takeDue(frame_index_);
  } catch (...) {
    ended_ = true;  // the method failed: the run ends with its error
    throw;
  }
  if (!due) return true;
  const PerceptionJob& j = *due;
  record_.tracks = &j.tracks;
  record_.points = &j.points;
  record_.perceived = j.frame.get();
  record_.map_updated = j.map_updated;
  record_.timing.tracker_ms = j.timing.tracker_ms;
  record_.timing.triangulation_ms = j.timing.triangulation_ms;
  record_.timing.map_ms = j.timing.map_ms;
  record_.timing.planning_ms = j.timing.planning_ms;
  // The frame's results take effect now: the drift rate, its path, tracking loss.
  vio_.setTrackedFeatures(trackedFromPrevious(j.tracks));
  if (j.cmd) {
    ending_paths_.emplace_back(record_.tick + j.cmd_delay_ticks, *j.cmd);
    takeEndedPaths();
  }
  return trackingHolds(j.tracks, j.tick);
}

void ClosedLoop::takeEndedPaths() {
  while (!ending_paths_.empty() && ending_paths_.front().first <= record_.tick) {
    trajectory_.setPath(ending_paths_.front().second.waypoints), last_path_t_s_ = record_.t_s;
    ending_paths_.pop_front();
  }
}

}  // namespace msb
