#include "tools/msbench/flight_runner.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "core/common/clock.h"
#include "core/common/wall_time.h"
#include "core/common/rng.h"

namespace msb {

uint64_t hashTrajectory(const std::vector<TrajectoryRow>& rows) {
  uint64_t h = fnv1a64(nullptr, 0);
  for (const auto& r : rows) {
    const double v[15] = {r.t_s,
                          r.est_position_m.x(),
                          r.est_position_m.y(),
                          r.est_position_m.z(),
                          r.est_yaw_rad,
                          r.position_m.x(),
                          r.position_m.y(),
                          r.position_m.z(),
                          r.orientation.w(),
                          r.orientation.x(),
                          r.orientation.y(),
                          r.orientation.z(),
                          r.velocity_mps.x(),
                          r.velocity_mps.y(),
                          r.velocity_mps.z()};
    h = fnv1a64(v, sizeof(v), h);
  }
  return h;
}

FlightResult runFlight(const FlightSpec& spec, const FlightObservers& observers) {
  const auto& on_frame = observers.on_frame;
  const auto& on_progress = observers.on_progress;
  checkValid(spec);
  const auto wall_start = std::chrono::steady_clock::now();
  FlightResult result;

  // Components, each from its own validated config.
  const Pose start = poseFromXyzYaw(spec.start_position_m, spec.start_yaw_rad);
  QuadrotorSim sim(spec.physics, spec.world_path, start);
  const FisheyeCamera camera(spec.camera);
  std::unique_ptr<FisheyeRenderer> renderer;
  if (spec.camera_stream.enabled)
    renderer = std::make_unique<FisheyeRenderer>(spec.render, camera, sim.model());
  if (renderer) result.gl_description = renderer->glDescription();
  const Se3Controller controller(spec.controller, spec.physics.vehicle);
  TrajectoryTracker trajectory(spec.trajectory, spec.start_position_m, spec.start_yaw_rad);
  trajectory.setPath(spec.waypoints);
  ImuModel imu(spec.imu, spec.seed);
  VioDriftModel vio(spec.vio_drift, spec.seed);
  std::unique_ptr<KltFeatureTracker> tracker;
  std::unique_ptr<SlamPointEstimator> slam;
  if (spec.perception.enabled) {
    tracker = std::make_unique<KltFeatureTracker>(spec.tracker, camera);
    slam = std::make_unique<SlamPointEstimator>(spec.slam_points, camera);
  }

  // Integer schedules of every stage.
  const TickClock clock(spec.physics.physics_hz);
  const int64_t ctrl_div = clock.divisorFor(spec.controller_hz, "controller_hz");
  const RateSchedule cam_schedule(spec.physics.physics_hz, spec.camera_stream.rate_hz,
                                  "camera_stream.rate_hz");
  const RateSchedule imu_schedule(spec.physics.physics_hz, spec.imu.rate_hz, "imu.rate_hz");
  const RateSchedule traj_schedule(spec.physics.physics_hz, observers.trajectory_rate_hz, "trajectory");
  const int64_t lost_ticks = clock.ticksFor(spec.perception.lost_after_s);
  int64_t few_tracks_since = -1;
  const int64_t max_ticks = clock.ticksFor(spec.duration_s);
  const int64_t hold_ticks = clock.ticksFor(spec.hold_after_s);
  const double ctrl_dt = ctrl_div * clock.tickSeconds();

  Vec4 cmd = Vec4::Zero();
  int64_t finished_tick = -1, last_imu_tick = 0;
  double err_sq_sum = 0.0;
  int64_t err_count = 0;
  Vec3 last_pos = spec.start_position_m;
  CameraFrame frame;

  while (sim.tick() < max_ticks) {
    const int64_t tick = sim.tick();
    // Physics step 1 and contacts.
    if (sim.beginTick()) {
      result.status = "collided";
      result.collision = sim.collision();
      break;
    }
    if (sim.diverged()) {
      result.status = "diverged";
      break;
    }
    const Odometry gt = sim.groundTruth();
    const Odometry est = vio.update(gt);

    // Camera render.
    std::optional<SlamPointsFrame> tick_points;
    if (renderer && cam_schedule.due(tick)) {
      RenderTiming rt;
      renderer->render(sim.data(), gt.T_W_B * camera.T_B_C(), &frame, &rt);
      frame.tick = tick;
      frame.t_s = gt.t_s;
      frame.T_W_C = gt.T_W_B * camera.T_B_C();
      auto& sum = result.render_time_sum;
      sum.scene_ms += rt.scene_ms;
      sum.render_ms += rt.render_ms;
      sum.readback_ms += rt.readback_ms;
      sum.remap_ms += rt.remap_ms;
      if (on_frame) on_frame(frame, result.frames_rendered);
      ++result.frames_rendered;

      // Perception: tracks, SLAM points from the estimated camera pose, tracking loss.
      if (tracker) {
        auto t0 = std::chrono::steady_clock::now();
        const TrackFrame tracks = tracker->process(frame);
        const double tracker_ms = msSince(t0);
        t0 = std::chrono::steady_clock::now();
        const SlamPointsFrame points = slam->update(tracks, vio.noisyCameraPose(frame.T_W_C));
        const double tri_ms = msSince(t0);
        if (observers.on_perception)
          observers.on_perception({frame, tracks, points, tracker_ms, tri_ms, rt.totalMs()});
        if (observers.autopilot) tick_points = points;
        if (int(tracks.tracks.size()) < spec.perception.lost_min_tracks) {
          if (few_tracks_since < 0) few_tracks_since = tick;
        } else {
          few_tracks_since = -1;
        }
        if (few_tracks_since >= 0 && tick - few_tracks_since >= lost_ticks) {
          result.status = "vio_lost";
          result.vio_lost_at_s = gt.t_s;
          break;
        }
      }
    }

    // Closed loop: mapping and planning may replace the path.
    if (observers.autopilot) {
      if (auto path = observers.autopilot({tick, est, tick_points ? &*tick_points : nullptr, trajectory}))
        trajectory.setPath(*path);
    }

    // Trajectory reference and controller.
    if (tick % ctrl_div == 0) {
      // The controller flies on the VIO estimate; the reference lives in the estimate frame.
      const TrajectoryReference& ref = trajectory.update(ctrl_dt);
      cmd = controller.compute(est, ref);
      const double err = (est.T_W_B.translation() - ref.position_m).norm();
      err_sq_sum += err * err;
      ++err_count;
      result.tracking_max_m = std::max(result.tracking_max_m, err);
      if (trajectory.finished() && finished_tick < 0) finished_tick = tick;
    }

    // Records.
    if (traj_schedule.due(tick)) {
      const auto& ref = trajectory.reference();
      result.trajectory.push_back({gt.t_s, gt.T_W_B.translation(), Quat(gt.T_W_B.linear()),
                                   gt.v_W_mps, est.T_W_B.translation(), yawOf(est.T_W_B.linear()),
                                   ref.position_m, ref.yaw_rad});
      result.final_drift_m = (est.T_W_B.translation() - gt.T_W_B.translation()).norm();
    }
    result.distance_flown_m += (gt.T_W_B.translation() - last_pos).norm();
    last_pos = gt.T_W_B.translation();

    // Physics step 2 (actuators, integration) and the IMU sample of this tick's state.
    sim.endTick(cmd);
    if (imu_schedule.due(tick)) {
      const double dt = tick == 0 ? 1.0 / spec.imu.rate_hz : (tick - last_imu_tick) * clock.tickSeconds();
      result.imu.push_back(imu.sample(tick, gt.t_s, dt, sim.imuTruth().specific_force_mps2,
                                      sim.imuTruth().angular_rate_radps));
      last_imu_tick = tick;
    }
    if (on_progress && tick > 0 && tick % spec.physics.physics_hz == 0)
      on_progress(gt.t_s, std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                                        wall_start).count());
    if (!observers.autopilot && finished_tick >= 0 && tick >= finished_tick + hold_ticks) break;
  }

  result.ticks = sim.tick();
  result.sim_time_s = sim.timeSeconds();
  result.path_finished = finished_tick >= 0;
  result.tracking_rms_m = err_count ? std::sqrt(err_sq_sum / err_count) : 0.0;
  result.trajectory_hash = hashTrajectory(result.trajectory);
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace msb
