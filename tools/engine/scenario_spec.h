// A mission scenario (`msbench run`, docs/architecture.md §12): a flight (world, seed, duration, sensors)
// flown by an exploration method chosen by `method.type`, with the ablation switches and the
// rates of the closed loop. Plain structs with defaults and validation; YAML lives in
// scenario_yaml.cc only.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/common/aabb.h"
#include "core/common/config_fields.h"
#include "core/methods/python/python_method.h"
#include "tools/engine/compute_clock.h"
#include "tools/engine/flight_spec.h"
#include "tools/engine/methods.h"

namespace msb {

/// The closed loop's rates and outputs.
struct MissionSettings {
  double map_rate_hz = 5.0;          ///< map updates (latest SLAM frame)
  double planning_rate_hz = 5.0;     ///< planning steps
  double metric_rate_hz = 1.0;       ///< coverage samples
  double trajectory_rate_hz = 10.0;  ///< trajectory.csv rows
  bool write_map_ply = true;         ///< final map as map.ply
  bool progress = true;              ///< progress line on stderr

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("map_rate_hz", s.map_rate_hz, Limits::range(0.1, 100.0));
    v.key("planning_rate_hz", s.planning_rate_hz, Limits::range(0.1, 100.0));
    v.key("metric_rate_hz", s.metric_rate_hz, Limits::range(0.01, 100.0));
    v.key("trajectory_rate_hz", s.trajectory_rate_hz, Limits::range(0.1, 500.0));
    v.key("write_map_ply", s.write_map_ply);
    v.key("progress", s.progress);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A video of the run (video.mp4; docs/video.md): the fisheye frame beside the top-down map as
/// it grows, one frame every speedup / fps simulated seconds.
struct VideoSettings {
  bool enabled = false;  ///< write video.mp4 (`msbench run --video`)
  double speedup = 10;   ///< simulated seconds per second of video
  int fps = 10;          ///< frames per second of video
  int height = 720;      ///< frame height in pixels (even; the width follows the box)

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("enabled", s.enabled);
    v.key("speedup", s.speedup, Limits::range(0.1, 1000.0));
    v.key("fps", s.fps, Limits::range(1, 60));
    v.key("height", s.height, Limits::range(240, 2160));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A flight with the defaults of a mission where they differ from a scripted flight's: 20
/// simulated minutes (Table I), perception on with a latency of 3 frames on a second thread,
/// no frames saved.
FlightSpec missionFlightDefaults();

/// Everything `msbench run` needs. Default-constructed, it is a valid mission once it names a
/// world (`flight.world_path` or `flight.world_name`).
struct ScenarioSpec {
  std::string name;  ///< run name (defaults to the file's stem)
  /// The benchmark suite the run is for (docs/sweeps.md, "Suites"): a directory of published runs,
  /// e.g. results/table1 ("" = none). Recorded in metrics.json; `msbench report` checks the run
  /// against it. Not a fixed setting.
  std::string suite;
  /// Not a key: the paper's Table I world the resolved world is (its spec's paper_world), set
  /// where the world is resolved; metrics.json `paper_world` when not empty.
  std::string paper_world;
  /// Not a key: the commitment of the salt a held-out world was drawn with (`held_out: true`;
  /// sim/world/world_salt.h), set where the world is resolved; metrics.json
  /// `world_salt_commitment` when not empty. The salt itself is never recorded.
  std::string world_salt_commitment;
  FlightSpec flight = missionFlightDefaults();  ///< world, seed, duration, start, vehicle, sensors
  bool start_from_world = true;                 ///< take start pose from the generated world unless `start` is given
  std::optional<Aabb> exploration_box;          ///< overrides the world's box
  MethodChoice method = defaultMethod();        ///< the exploration method and its config
  /// A goal chooser written in Python for the method (grid_random or monospheres), named by the
  /// scenario's `goals` section (entry, path, params); runs through the Python module.
  std::optional<PythonMethodConfig> goals;
  MissionSettings mission;
  VideoSettings video;   ///< off by default; nothing of the run depends on it
  ComputeTiming timing;  ///< how the method's computation is charged (default: free)
  /// Not a key: the latencies `timing.replay` names (tools/results/compute_log.h reads them).
  ComputeLog compute_replay;
  /// The files the scenario was read from: the file itself, then its `base:` chain (absolute).
  /// Outputs may not overlap them (checkNoOverlap).
  std::vector<std::string> input_files;
  /// The hash of the benchmark's side of the scenario (everything but what a method or a run
  /// chooses; tools/config/scenario_yaml.h fixedSettingsHash), set by loadScenario; "" for a
  /// spec built in code. Recorded in metrics.json.
  std::string fixed_settings_hash;
  /// replaySettingsHash (tools/config/scenario_yaml.h), set by loadScenario ("" for a spec built
  /// in code): a charged run's latency log names it, and replays only into the same.
  std::string replay_settings_hash;

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

}  // namespace msb
