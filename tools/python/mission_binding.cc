// Mission: a scenario's mission stepped or run from Python, and the files it writes.
#include "tools/python/binding.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>

#include "core/common/wall_time.h"
#include "core/geometry/world_truth.h"
#include "tools/config/method_table.h"
#include "tools/config/world_registry.h"
#include "tools/engine/mission.h"
#include "tools/engine/records.h"
#include "tools/results/mission_outputs.h"
#include "tools/results/output_files.h"
#include "tools/results/provenance.h"
#include "tools/results/run_video.h"

namespace msb {
namespace binding {

namespace {

/// How long an interrupted mission waits for a method call stuck on the loop's second thread
/// before it gives the thread up (the mission is then never freed).
constexpr std::chrono::milliseconds kStuckMethodWait{500};

/// At scope exit, waits for the pipelined loop's perception in flight; when unwinding (a
/// KeyboardInterrupt, an error) drops what has not started, so no method call follows, and
/// waits at most kStuckMethodWait for the one running (`stuck` when it is still running).
struct SyncAtExit {
  Mission& mission;
  bool& stuck;
  int exceptions = std::uncaught_exceptions();
  ~SyncAtExit() {
    if (std::uncaught_exceptions() > exceptions)
      stuck = !mission.abandonWithin(kStuckMethodWait);
    else
      mission.sync();
  }
};

/// Runs Python's signal handlers (called without the GIL): a KeyboardInterrupt they raise is
/// thrown here. Signals reach Python on this thread only, not while a method runs on the
/// pipelined loop's second thread.
void checkSignals() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

/// The loop's wait hook (Mission::setWaitHook): while the loop thread waits for a Python method
/// on the second thread, Python's signal handlers run here every 100 ms; a KeyboardInterrupt
/// is raised in the method's call too and thrown here (the step then abandons the mission).
void checkSignalsWhileWaiting() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) {
    interruptMethodCall();
    throw py::error_already_set();
  }
}

/// A mission of a scenario, stepped from Python.
class PyMission {
 public:
  // `method`: None (the scenario's method) or a factory called with a Context, returning an
  // object with the Python method protocol.
  PyMission(const PyScenario& s, py::object method, py::object goals)
      : scenario_(s), world_(std::make_unique<MissionWorld>()) {
    *world_ = prepareMissionWorld(scenario_.file, scenario_.spec);
    const WorldTruth* truth = world_->truth ? &*world_->truth : nullptr;
    noteModule(method, "the method's module");
    noteModule(goals, "the goal chooser's module");
    if (!goals.is_none()) {
      buildWithGoalChooser(std::move(method), std::move(goals), truth, /*record=*/true);
      return;
    }
    // A scenario naming a goal chooser (`goals:`): started in its own confined process, recorded
    // by the scenario itself (config.yaml's goals section replays it).
    if (method.is_none() && scenario_.spec.goals) {
      const PythonMethodConfig& g = *scenario_.spec.goals;
      scenario_.spec.method.goal_chooser = g.entry;  // metrics.json names it; config.yaml replays it
      const py::module_ methods = py::module_::import("msbench.methods");
      py::object chooser = methods.attr("chooser_of")(g.entry, g.path, yamlToPython(g.params.text), scenario_.file);
      // The module's file, found without importing it: the chooser runs in its own process only.
      const py::object file =
          methods.attr("module_file")(g.entry, methods.attr("method_dir")(g.path, scenario_.file, "goals"));
      if (!file.is_none()) moduleInputs_.push_back({"the goal chooser's module", file.cast<std::string>()});
      buildWithGoalChooser(py::none(), chooser, truth, /*record=*/false);
      return;
    }
    // A scenario naming a Python method (method.type: python): its factory, from msbench.methods.
    const bool from_scenario = method.is_none();
    if (method.is_none() && scenario_.spec.method.type == kPythonMethodType) {
      const auto& c = std::any_cast<const PythonMethodConfig&>(scenario_.spec.method.config);
      const py::module_ methods = py::module_::import("msbench.methods");
      method = methods.attr("factory_of")(c.entry, c.path, yamlToPython(c.params.text), scenario_.file, c.call_budget_s,
                                          c.memory_limit_mib);
      // The module's file, found without importing it: the method runs in its own process only.
      const py::object file =
          methods.attr("module_file")(c.entry, methods.attr("method_dir")(c.path, scenario_.file, "method"));
      if (!file.is_none()) moduleInputs_.push_back({"the method's module", file.cast<std::string>()});
    }
    if (method.is_none()) {
      mission_ = buildNamingFile(scenario_.file,
                                 [&] { return std::make_unique<Mission>(scenario_.spec, world_->box, truth); });
      return;
    }
    if (!from_scenario) recordInProcess(s, method, /*goal_chooser=*/false);
    const ExplorerContext ctx = explorerContext(scenario_.spec, world_->box);
    MethodContext pc;
    pc.box_min = {ctx.exploration_box.min.x(), ctx.exploration_box.min.y(), ctx.exploration_box.min.z()};
    pc.box_max = {ctx.exploration_box.max.x(), ctx.exploration_box.max.y(), ctx.exploration_box.max.z()};
    pc.start_position = {ctx.start.translation().x(), ctx.start.translation().y(), ctx.start.translation().z()};
    pc.start_yaw_rad = yawOf(ctx.start.linear());
    pc.seed = ctx.seed;
    pc.start_pose = readOnly(poseArray(ctx.start));
    py::object instance = method(pc);
    // Where the method ran: its own confined process (a scenario's method), or this process.
    scenario_.spec.method.confinement = py::hasattr(instance, "msbench_confinement")
                                            ? instance.attr("msbench_confinement").cast<std::string>()
                                            : std::string("in-process (unconfined)");
    std::unique_ptr<Explorer> explorer = makePythonExplorer(std::move(instance));
    mission_ = buildNamingFile(scenario_.file, [&] {
      return std::make_unique<Mission>(scenario_.spec, world_->box, truth, std::move(explorer));
    });
  }

  // The pipelined loop's perception in flight has run, the GIL released (a Python method or
  // chooser on the loop's second thread takes the GIL): nothing runs on that thread once Python
  // code continues or the mission goes.
  ~PyMission() {
    if (stuck_) {
      // A method call still runs on the loop's second thread, in the mission's objects: they are
      // never freed (the thread ends with the process).
      (void)mission_.release();
      (void)world_.release();
      return;
    }
    if (mission_) {
      py::gil_scoped_release release;
      mission_->sync();
    }
    video_.reset();  // an unfinished video: its encoder stopped, its file removed
    std::error_code ec;
    if (!video_dir_.empty()) std::filesystem::remove_all(video_dir_, ec);
  }
  PyMission(const PyMission&) = delete;
  PyMission& operator=(const PyMission&) = delete;

  bool running() const { return !error_ && !interrupted_ && mission_->running(); }

  /// Physics ticks per simulated second.
  int64_t physicsHz() const { return mission_->physicsHz(); }

  /// The coverage area so far (m², the metric's last evaluation).
  double areaM2() const { return mission_->areaM2(); }

  // Steps up to n ticks (fewer if the run ends), the GIL released.
  PyTick step(int64_t n) {
    if (n < 1) throw py::value_error("step(n): n must be >= 1");
    std::optional<SlamPointsFrame> points;
    bool new_frame = false;
    guarded([&] {
      mission_->setWaitHook(checkSignalsWhileWaiting);
      py::gil_scoped_release release;
      const SyncAtExit sync{*mission_, stuck_, std::uncaught_exceptions()};
      const int64_t hz = mission_->physicsHz();
      startVideo();
      for (int64_t i = 0; i < n && mission_->running(); ++i) {
        const TickRecord& r = mission_->step();
        videoFrame(r);
        last_tick_ = r.tick;
        last_t_s_ = r.t_s;
        if (r.frame) new_frame = true;
        if (r.points) points = *r.points;
        if ((i + 1) % hz == 0) checkSignals();  // Ctrl-C within a simulated second
      }
    });
    return record(new_frame, points);
  }

  // Runs to the end, checking for Ctrl-C between simulated seconds; with `progress`, the command
  // line's progress line on stderr every 10 simulated seconds (piped or not; wall time shown only).
  void run(bool progress) {
    const int64_t chunk = mission_->physicsHz();
    int64_t next_progress = 10 * chunk;
    const auto wall_start = WallClock::now();
    while (running()) {
      guarded([&] {
        mission_->setWaitHook(checkSignalsWhileWaiting);
        py::gil_scoped_release release;
        const SyncAtExit sync{*mission_, stuck_, std::uncaught_exceptions()};
        startVideo();
        for (int64_t i = 0; i < chunk && mission_->running(); ++i) {
          const TickRecord& r = mission_->step();
          videoFrame(r);
          last_tick_ = r.tick;
        }
        checkSignals();
      });
      if (progress && last_tick_ + 1 >= next_progress) {  // ticks count from 0: tick k ends at (k + 1) / hz
        next_progress += 10 * chunk;
        const double sim_s = double(last_tick_ + 1) / double(chunk), duration = scenario_.spec.flight.duration_s;
        const double rtf = sim_s / std::max(secondsSince(wall_start), 1e-9);
        std::fprintf(stderr, "run %s: t = %.0f / %.0f s, RTF %.2f, A = %.0f m², ETA %.0f s\n",
                     scenario_.spec.name.c_str(), sim_s, duration, rtf, mission_->areaM2(), (duration - sim_s) / rtf);
      }
    }
  }

  // The metrics (metrics.json's content); finishes the mission on first call.
  py::object result() { return jsonToPython(metrics()); }

  std::string hash() { return hexHash(finished().run_hash); }

  // Writes the files `msbench run` writes into `dir` (staged: whole or not at all); after a
  // method error, config.yaml and the error record.
  std::string write(const std::string& dir, bool overwrite) {
    refuseReentry("write()");
    if (interrupted_) throw std::runtime_error("the mission was interrupted: nothing to write");
    // The output may not be, hold or lie in what the mission reads: the scenario, its base: chain,
    // its world file, the Python method's or chooser's module (before: overwrite=True deleted them).
    checkNoOverlap(missionInputs(scenario_.file, scenario_.spec, moduleInputs_), {{"dir", dir}});
    StagedOutputDir out(dir, overwrite);
    writeFileAtomic(out.staging() / "config.yaml",
                    configYamlText(scenario_.file, !scenario_.sets.empty(), scenario_.effective_yaml,
                                   scenario_.spec.method.not_replayable));
    if (error_) {
      writeErroredMissionOutputs(out.staging(), scenario_.spec, *mission_, *error_, last_tick_,
                                 world_->truth ? &*world_->truth : nullptr, error_status_);
    } else {
      writeMissionOutputs(out.staging(), scenario_.spec, finished(), world_->truth ? &*world_->truth : nullptr,
                          [&] { return finishVideo(out.staging(), out.finalDir()); });
    }
    out.commit();
    return out.finalDir().string();
  }

  // The run's status word: running, error, or the loop's (completed, collided, ...).
  std::string status() {
    if (interrupted_) return "interrupted";
    if (error_) return runStatusName(error_status_);
    if (mission_->running()) return "running";
    return runStatusName(finished().flight.status);
  }

 private:
  // The run's video (video.enabled; docs/video.md), started with the first step: its frames go
  // to a temporary directory until write() moves the file into the output.
  void startVideo() {
    if (!scenario_.spec.video.enabled || video_ || video_done_) return;
    char dir[] = "/tmp/msbench_video.XXXXXX";
    if (!mkdtemp(dir)) throw std::runtime_error("video: cannot create a temporary directory in /tmp");
    video_dir_ = dir;
    video_ = std::make_unique<RunVideo>(video_dir_ / "video.mp4", scenario_.spec.video,
                                        scenario_.spec.name + " (" + methodLabel(scenario_.spec.method) + ")",
                                        scenario_.spec.flight.duration_s, world_->box,
                                        world_->truth ? &*world_->truth : nullptr, mission_->loop().camera().width(),
                                        mission_->loop().camera().height());
    if (const MethodRegistration* e = findRegistration(scenario_.spec.method.type))
      video_->setCaptionCounters(e->info.progress_counters);
    video_ticks_ = video_->periodTicks(mission_->physicsHz());
  }

  // A video frame at the end of every frame period's tick.
  void videoFrame(const TickRecord& r) {
    if (!video_ || !r.completed || r.tick % video_ticks_ != 0) return;
    const auto start = WallClock::now();
    video_->addFrame(*mission_);
    video_s_ += secondsSince(start);
  }

  // Ends the video into `staging` (after the run's other files): metrics.json's `video`.
  nlohmann::json finishVideo(const std::filesystem::path& staging, const std::filesystem::path& final_dir) {
    nlohmann::json j = nlohmann::json::object();
    if (!video_) return j;
    video_done_ = true;
    nlohmann::json v =
        finishRunVideo(*video_, finished(), mission_->loop().sharedFrame().get(), video_s_, final_dir / "video.mp4");
    video_.reset();
    if (!v["file"].is_null()) {
      std::error_code ec;
      std::filesystem::copy_file(video_dir_ / "video.mp4", staging / "video.mp4", ec);
      if (ec) {
        std::filesystem::remove(staging / "video.mp4", ec);
        v = {{"file", nullptr}, {"error", "cannot copy it into the output: " + ec.message()}};
        std::fprintf(stderr, "msbench run: video %s not written: %s\n", (final_dir / "video.mp4").c_str(),
                     v["error"].get<std::string>().c_str());
      }
    }
    j["video"] = v;
    return j;
  }

  // Runs `f`; a method error (or any failure of the loop) ends the run with status error.
  template <class F>
  void guarded(F&& f) {
    refuseReentry("step() or run()");
    if (interrupted_) throw std::runtime_error("the mission was interrupted: it cannot go on or be written");
    if (error_) throw std::runtime_error("the mission ended with an error: " + *error_);
    struct Stepping {  // while the loop runs: a call back into the mission is refused
      std::atomic<bool>& flag;
      explicit Stepping(std::atomic<bool>& f) : flag(f) { flag = true; }
      ~Stepping() { flag = false; }
    } stepping{stepping_};
    try {
      f();
    } catch (py::error_already_set& e) {
      // Only a KeyboardInterrupt reaches here as a Python error (method errors are MethodError).
      interrupted_ = true;
      throw;
    } catch (const MethodProcessError& e) {
      error_ = e.what();
      error_status_ = e.status;
      throw;
    } catch (const std::exception& e) {
      error_ = e.what();
      throw;
    }
  }

  // The scenario's grid explorer with its goals from `goals` (the goal-only helper).
  void buildWithGoalChooser(py::object method, py::object goals, const WorldTruth* truth, bool record) {
    if (!method.is_none()) throw py::value_error("Mission: give a method or goals, not both");
    if (record) recordInProcess(scenario_, goals, /*goal_chooser=*/true);
    // Where the chooser ran: its own confined process (a scenario's `goals`), or this process.
    scenario_.spec.method.confinement = py::hasattr(goals, "msbench_confinement")
                                            ? goals.attr("msbench_confinement").cast<std::string>()
                                            : std::string("in-process goal chooser (unconfined)");
    std::unique_ptr<Explorer> explorer = scenario_.spec.method.make(FisheyeCamera(scenario_.spec.flight.camera),
                                                                    explorerContext(scenario_.spec, world_->box));
    attachGoalChooser(*explorer, scenario_.spec.method.type, std::move(goals), scenario_.file);
    mission_ = buildNamingFile(scenario_.file, [&] {
      return std::make_unique<Mission>(scenario_.spec, world_->box, truth, std::move(explorer));
    });
  }

  // Records what flies instead of the scenario's method: an in-process factory becomes a Python
  // method, a goal chooser the scenario's `goals` section, named by module and name —
  // config.yaml replays the run when that name imports back to the object, and says why not
  // otherwise (a lambda, a closure, a script's own function). The effective YAML is rebuilt
  // from the scenario as loaded (`original`: before the world filled in the start).
  void recordInProcess(const PyScenario& original, const py::object& obj, bool goal_chooser) {
    const py::tuple rec = py::module_::import("msbench.methods").attr("record_of")(obj);
    const std::string entry = rec[0].cast<std::string>(), why = rec[2].cast<std::string>();
    ScenarioSpec spec = original.spec;
    if (goal_chooser && why.empty()) {
      // A module-level chooser imports back to itself: recorded as a scenario's `goals` section,
      // so config.yaml replays the run.
      PythonMethodConfig g;
      g.entry = entry;
      g.path = rec[1].cast<std::string>();
      spec.goals = g;
      spec.method.goal_chooser = entry;
      scenario_.spec.goals = g;
    } else if (goal_chooser) {
      spec.method.goal_chooser = entry;
      spec.method.not_replayable = "the goals came from the in-process goal chooser " + entry + " (" + why + ")";
    } else {
      PythonMethodConfig c;
      c.entry = entry;
      c.path = rec[1].cast<std::string>();
      spec.method.type = kPythonMethodType;
      spec.method.config = c;
      spec.method.switches.clear();
      spec.method.not_replayable = why;
    }
    scenario_.effective_yaml = effectiveScenarioYaml(runOwnComputeLog(spec));
    scenario_.spec.method.type = spec.method.type;
    scenario_.spec.method.config = spec.method.config;
    scenario_.spec.method.switches = spec.method.switches;
    scenario_.spec.method.not_replayable = spec.method.not_replayable;
    scenario_.spec.method.goal_chooser = spec.method.goal_chooser;
  }

  // A method or goal chooser that calls its own mission back (step, run, result, write) while the
  // loop waits for it would deadlock: refused, naming the call (the chooser's error ends the run).
  void refuseReentry(const char* call) const {
    if (stepping_)
      throw std::runtime_error(std::string("Mission.") + call +
                               " called while the mission is stepping, from its own method or goal chooser: a "
                               "chooser decides from the request it is given and never steps the mission");
  }

  const MissionResult& finished() {
    refuseReentry("result(), hash or write()");
    if (error_) throw std::runtime_error("the mission ended with an error (write() records it): " + *error_);
    if (!result_) {
      if (mission_->running())
        throw std::runtime_error("the mission is still running: step() or run() it to its end first");
      result_ = mission_->finish();
    }
    return *result_;
  }

  nlohmann::json metrics() {
    const MissionResult& r = finished();
    return missionMetrics(scenario_.spec, r, world_->truth ? &*world_->truth : nullptr);
  }

  PyTick record(bool new_frame, const std::optional<SlamPointsFrame>& points) const {
    PyTick t;
    t.tick = last_tick_;
    t.t_s = last_t_s_;
    t.running = mission_->running();
    const ClosedLoop& loop = mission_->loop();
    if (new_frame) {
      const std::shared_ptr<const CameraFrame> f = loop.sharedFrame();
      t.frame = frameView(f);
      t.frame_pose = readOnly(poseArray(f->T_W_C));
      t.frame_tick = py::int_(f->tick);
    }
    if (points) fillPoints(t, *points);
    t.true_pose = readOnly(poseArray(loop.groundTruth().T_W_B));
    t.est_pose = readOnly(poseArray(loop.estimate().T_W_B));
    t.true_velocity = readOnly(vec3Array(loop.groundTruth().v_W_mps));
    t.est_velocity = readOnly(vec3Array(loop.estimate().v_W_mps));
    return t;
  }

  // Records the source file of `obj` (a function, class or module) as an input of write().
  void noteModule(const py::object& obj, const std::string& what) {
    if (obj.is_none()) return;
    const py::object file = py::module_::import("msbench.methods").attr("source_file")(obj);
    if (!file.is_none()) moduleInputs_.push_back({what, file.cast<std::string>()});
  }

  PyScenario scenario_;
  std::vector<NamedPath> moduleInputs_;  // Python modules the mission runs: outputs may not overlap them
  std::unique_ptr<MissionWorld> world_;  // the truth the mission points into: never moves
  std::unique_ptr<Mission> mission_;
  std::optional<MissionResult> result_;
  std::unique_ptr<RunVideo> video_;  // the run's video while it is recorded (video.enabled)
  std::filesystem::path video_dir_;  // its temporary directory (removed with the mission)
  int64_t video_ticks_ = 1;
  double video_s_ = 0;
  bool video_done_ = false;
  std::optional<std::string> error_;            // the run ended with an error (a Python method raised)
  RunStatus error_status_ = RunStatus::kError;  // or its process failed (method_timeout, method_exited)
  std::atomic<bool> stepping_{false};           // the loop runs (guarded): re-entry is refused
  bool interrupted_ = false;                    // a KeyboardInterrupt ended it: nothing to write
  bool stuck_ = false;                          // interrupted with a method call still running
  int64_t last_tick_ = 0;
  double last_t_s_ = 0.0;
};

/// Writes the record of a run whose method failed before its first step (its factory timed out
/// or its process ended, `status` as metrics.json spells it): config.yaml and metrics.json, staged
/// like a run's files. Returns the output directory.
std::string writeStartFailure(const PyScenario& s, const std::string& dir, const std::string& status,
                              const std::string& what, bool overwrite) {
  const std::optional<RunStatus> st = parseRunStatus(status);
  if (!st) throw py::value_error("write_start_failure: unknown status '" + status + "'");
  std::vector<NamedPath> modules;
  if (s.spec.method.type == kPythonMethodType) {
    const auto& c = std::any_cast<const PythonMethodConfig&>(s.spec.method.config);
    const py::module_ methods = py::module_::import("msbench.methods");
    const py::object file = methods.attr("module_file")(c.entry, methods.attr("method_dir")(c.path, s.file, "method"));
    if (!file.is_none()) modules.push_back({"the method's module", file.cast<std::string>()});
  }
  checkNoOverlap(missionInputs(s.file, s.spec, modules), {{"dir", dir}});
  StagedOutputDir out(dir, overwrite);
  writeFileAtomic(out.staging() / "config.yaml",
                  configYamlText(s.file, !s.sets.empty(), s.effective_yaml, s.spec.method.not_replayable));
  nlohmann::json m = errorMetrics(s.spec, what, *st);
  m["error_tick"] = 0;
  writeFileAtomic(out.staging() / "metrics.json", m.dump(2) + "\n");
  out.commit();
  return out.finalDir().string();
}

}  // namespace

void bindMission(py::module_& m) {
  m.def("write_start_failure", &writeStartFailure, py::arg("scenario"), py::arg("dir"), py::arg("status"),
        py::arg("error"), py::arg("overwrite") = false,
        "Writes config.yaml and metrics.json for a run whose method failed before its first step.");
  py::class_<PyMission>(m, "Mission", "A mission of a scenario, stepped or run from Python.")
      .def(py::init([](const py::object& scenario, py::object method, py::object goals) {
             return std::make_unique<PyMission>(scenarioOf(scenario), std::move(method), std::move(goals));
           }),
           py::arg("scenario"), py::arg("method") = py::none(), py::arg("goals") = py::none(),
           "scenario: a Scenario or a path; method: None (the scenario's) or a factory(Context) returning a Python "
           "method; goals: a "
           "goal chooser for the scenario's method (the goal-only helper): grid_random: "
           "goals(GoalRequest) -> None | (x, y, z) | [(x, y, z), ...]; monospheres: "
           "goals(ViewpointRequest) -> None | 0 | viewpoint id")
      .def_property_readonly("area_m2", &PyMission::areaM2, "The coverage area so far (m², the paper's metric).")
      .def_property_readonly("physics_hz", &PyMission::physicsHz, "physics ticks per simulated second")
      .def_property_readonly("status", &PyMission::status, "The run status: running, completed, collided, ...")
      .def_property_readonly("running", &PyMission::running, "True until the run ends.")
      .def("step", &PyMission::step, py::arg("n") = 1, "Steps up to n physics ticks; returns a TickRecord.")
      .def("run", &PyMission::run, py::arg("progress") = true, "Runs to the end (Ctrl-C raises KeyboardInterrupt).")
      .def("result", &PyMission::result, "metrics.json's content as a dict (the run must have ended).")
      .def_property_readonly("hash", &PyMission::hash,
                             "The determinism hash (as msbench run prints it); the run must have ended.")
      .def("write", &PyMission::write, py::arg("dir"), py::arg("overwrite") = false,
           "Writes the files msbench run writes into dir; returns its path.");
}

}  // namespace binding
}  // namespace msb
