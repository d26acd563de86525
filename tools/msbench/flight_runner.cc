#include "tools/msbench/flight_runner.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "core/common/clock.h"
#include "core/common/rng.h"

namespace msb {

uint64_t hashTrajectory(const std::vector<TrajectoryRow>& rows) {
  uint64_t h = fnv1a64(nullptr, 0);
  for (const auto& r : rows) {
    const double v[11] = {r.t_s,
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

FlightResult runFlight(const FlightSpec& spec, const FrameCallback& on_frame,
                       const ProgressCallback& on_progress, double trajectory_rate_hz) {
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
  TrajectoryTracker tracker(spec.trajectory, spec.start_position_m, spec.start_yaw_rad);
  tracker.setPath(spec.waypoints);
  ImuModel imu(spec.imu, spec.seed);

  // Integer schedules of every stage.
  const TickClock clock(spec.physics.physics_hz);
  const int64_t ctrl_div = clock.divisorFor(spec.controller_hz, "controller_hz");
  const RateSchedule cam_schedule(spec.physics.physics_hz, spec.camera_stream.rate_hz,
                                  "camera_stream.rate_hz");
  const RateSchedule imu_schedule(spec.physics.physics_hz, spec.imu.rate_hz, "imu.rate_hz");
  const RateSchedule traj_schedule(spec.physics.physics_hz, trajectory_rate_hz, "trajectory");
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

    // Camera render.
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
    }

    // Trajectory reference and controller.
    if (tick % ctrl_div == 0) {
      const TrajectoryReference& ref = tracker.update(ctrl_dt);
      cmd = controller.compute(gt, ref);
      const double err = (gt.T_W_B.translation() - ref.position_m).norm();
      err_sq_sum += err * err;
      ++err_count;
      result.tracking_max_m = std::max(result.tracking_max_m, err);
      if (tracker.finished() && finished_tick < 0) finished_tick = tick;
    }

    // Records.
    if (traj_schedule.due(tick)) {
      const auto& ref = tracker.reference();
      result.trajectory.push_back({gt.t_s, gt.T_W_B.translation(), Quat(gt.T_W_B.linear()),
                                   gt.v_W_mps, ref.position_m, ref.yaw_rad});
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
    if (finished_tick >= 0 && tick >= finished_tick + hold_ticks) break;
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
