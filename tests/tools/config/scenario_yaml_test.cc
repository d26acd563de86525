// Scenario files: base chains, --set overrides, switches, and one error per class naming the
// file and the key.
#include "tools/config/scenario_yaml.h"
#include "core/common/config_check.h"
#include "core/methods/grid_random/grid_explorer.h"
#include "core/methods/monospheres/planner/monospheres_explorer.h"
#include "tools/config/flight_yaml.h"
#include "tools/config/method_table.h"
#include "tools/config/yaml_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace msb {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
  const fs::path d = fs::path(::testing::TempDir()) /
                     ("msb_scenario_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::create_directories(d / "sub");
  fs::copy_file(fs::path(MSB_SOURCE_DIR) / "worlds/test/world.xml", d / "world.xml",
                fs::copy_options::overwrite_existing);
  return d;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

const char* kBase = R"(
world: world.xml
seed: 3
method:
  type: monospheres
  planner: {local_radius_m: 12.0, viewpoints: {min_value: 5}}
  switches: {ovde: true, dbof: true, fff: true, vpb: true}
)";

// The MonoSpheres config a scenario chose.
MonoSpheresConfig mono(const ScenarioSpec& s) {
  EXPECT_EQ(s.method.type, "monospheres");
  return std::any_cast<MonoSpheresConfig>(s.method.config);
}

// The fixed settings (the benchmark's side of a scenario) ignore what a method or a run chooses
// and see everything else.
TEST(ScenarioYaml, TheFixedSettingsHashIgnoresTheMethodAndTheRunAndSeesTheRest) {
  const fs::path d = tempDir();
  write(d / "s.yaml", kBase);
  const std::string s = (d / "s.yaml").string();
  const std::string h = loadScenario(s).fixed_settings_hash;
  EXPECT_EQ(h.size(), 16u);
  EXPECT_EQ(h, fixedSettingsHash(loadScenario(s)));
  for (const char* same :
       {"method.switches.fff=false", "seed=9", "name=other", "suite=results/table1", "video.enabled=true",
        "mission.progress=false", "method.planner.local_radius_m=15", "mission.write_map_ply=false"})
    EXPECT_EQ(loadScenario(s, {same}).fixed_settings_hash, h) << same;
  for (const char* other : {"duration_s=60", "trajectory.limits=fast", "camera.clip_far_m=150",
                            "mission.map_rate_hz=2.5", "perception.latency_frames=1"})
    EXPECT_NE(loadScenario(s, {other}).fixed_settings_hash, h) << other;
  EXPECT_EQ(fixedSettingsYaml(loadScenario(s)).find("method"), std::string::npos);
  // The suite a run is for: read, written back only when set (older runs' config.yaml unchanged).
  const ScenarioSpec for_suite = loadScenario(s, {"suite=results/table1"});
  EXPECT_EQ(for_suite.suite, "results/table1");
  EXPECT_NE(effectiveScenarioYaml(for_suite).find("suite: results/table1"), std::string::npos);
  EXPECT_EQ(effectiveScenarioYaml(loadScenario(s)).find("suite:"), std::string::npos);
}

TEST(ScenarioYaml, BaseChainOverridesAndSwitches) {
  const fs::path d = tempDir();
  write(d / "base.yaml", kBase);
  write(d / "sub" / "mission.yaml",
        "base: ../base.yaml\nduration_s: 30\n"
        "method: {switches: {fff: false}, planner: {viewpoints: {candidates: 50}}}\n");
  const ScenarioSpec s = loadScenario((d / "sub" / "mission.yaml").string());
  EXPECT_EQ(s.name, "mission");
  EXPECT_EQ(s.flight.seed, 3u);
  EXPECT_DOUBLE_EQ(s.flight.duration_s, 30.0);
  EXPECT_EQ(s.flight.world_path, (d / "world.xml").lexically_normal().string());  // relative to base.yaml
  EXPECT_TRUE(s.flight.perception.enabled);
  EXPECT_DOUBLE_EQ(mono(s).planner.goals.local_radius_m, 12.0);  // from the base
  EXPECT_EQ(mono(s).planner.viewpoints.min_value, 5);            // merged map by map
  EXPECT_EQ(mono(s).planner.viewpoints.candidates, 50);
  EXPECT_FALSE(mono(s).planner.goals.fff);
  EXPECT_TRUE(mono(s).planner.viewpoints.vpb);
  EXPECT_FALSE(s.method.switches.at("fff"));
  EXPECT_TRUE(s.start_from_world);
  // Command-line overrides win over both files.
  const ScenarioSpec o =
      loadScenario((d / "sub" / "mission.yaml").string(),
                   {"method.switches.vpb=false", "seed=9", "method.map.r_max_m=8", "duration_s=12.5"});
  EXPECT_FALSE(mono(o).planner.viewpoints.vpb);
  EXPECT_EQ(o.flight.seed, 9u);
  EXPECT_DOUBLE_EQ(mono(o).map.r_max_m, 8.0);
  EXPECT_DOUBLE_EQ(o.flight.duration_s, 12.5);
  // Defaults: 1200 s, all switches on.
  write(d / "plain.yaml", "world: world.xml\n");
  const ScenarioSpec p = loadScenario((d / "plain.yaml").string());
  EXPECT_DOUBLE_EQ(p.flight.duration_s, 1200.0);
  EXPECT_TRUE(mono(p).map.ovde && mono(p).map.dbof && mono(p).planner.goals.fff);
}

TEST(ScenarioYaml, TheMethodTableHoldsTheChosenMethodsKeysOnly) {
  const fs::path d = tempDir();
  write(d / "grid.yaml",
        "world: world.xml\nmethod: {type: grid_random, replan_period_s: 0.2, "
        "planner: {unknown_is_occupied: true}}\n");
  const ScenarioSpec g = loadScenario((d / "grid.yaml").string());
  EXPECT_EQ(g.method.type, "grid_random");
  const auto c = std::any_cast<GridExplorerConfig>(g.method.config);
  EXPECT_DOUBLE_EQ(c.replan_period_s, 0.2);
  EXPECT_TRUE(c.planner.unknown_is_occupied);
  EXPECT_DOUBLE_EQ(c.map.resolution_m, 0.5);
  EXPECT_TRUE(g.method.switches.empty());  // the ablation switches are MonoSpheres'
}

void expectError(const std::string& text, std::initializer_list<std::string> fragments,
                 const std::vector<std::string>& sets = {}) {
  const fs::path d = tempDir();
  write(d / "base.yaml", kBase);
  const std::string path = (d / "bad.yaml").string();
  write(path, text);
  try {
    loadScenario(path, sets);
    FAIL() << "expected an error for:\n" << text;
  } catch (const FileConfigError& e) {
    const std::string msg = e.what();
    for (const auto& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg << "\n  missing: " << f;
  } catch (const UsageError& e) {
    const std::string msg = e.what();
    for (const auto& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg << "\n  missing: " << f;
  }
}

TEST(ScenarioYaml, ErrorsNameFileAndKey) {
  expectError("base: base.yaml\nmethod: {planner: {local_radius: 3}}\n",
              {"bad.yaml", "method.planner.local_radius", "unknown key"});
  expectError("base: base.yaml\nmethod: {map: {ovde: false}}\n", {"method.map.ovde", "unknown key"});
  expectError("base: base.yaml\nmethod: {switches: {fff: maybe}}\n", {"method.switches.fff", "true or false"});
  expectError("base: base.yaml\nswitches: {fff: false}\n", {"'switches'", "unknown key"});
  // The published code's switches: names, values, the scalar form, MonoSpheres only.
  expectError("base: base.yaml\nmethod: {reference_code: {pinhole: true}}\n",
              {"bad.yaml", "method.reference_code.pinhole", "unknown key"});
  expectError("base: base.yaml\nmethod: {reference_code: {path_resend_8s: 8}}\n",
              {"bad.yaml", "method.reference_code.path_resend_8s", "true or false"});
  expectError("base: base.yaml\nmethod: {reference_code: paper}\n",
              {"bad.yaml", "method.reference_code", "published, intended or a map"});
  expectError("world: world.xml\nmethod: {type: grid_random, reference_code: {published: true}}\n",
              {"bad.yaml", "method.reference_code", "published or intended"});
  // Keys of one method are unknown keys for another.
  expectError("world: world.xml\nmethod: {type: grid_random, switches: {vpb: false}}\n",
              {"method.switches", "unknown key"});
  expectError("world: world.xml\nmethod: {type: grid_random, map: {r_max_m: 8}}\n",
              {"method.map.r_max_m", "unknown key"});
  expectError("world: world.xml\nmethod: {type: monospheres, goal_square_m: 30}\n",
              {"method.goal_square_m", "unknown key"});
  expectError("world: world.xml\nmethod: {type: grid_random, map: {resolution_m: -1}}\n", {"method.map.resolution_m"});
  // A planning tree finer than half the map's leaves connects nothing (issue 91).
  expectError("world: world.xml\nmethod: {type: grid_random, planner: {planning_tree_resolution_m: 0.2}}\n",
              {"bad.yaml", "method.planner.planning_tree_resolution_m", "at least half the map's resolution"});
  expectError("base: base.yaml\nmethod: {type: magic}\n",
              {"method.type", "unknown method 'magic'", "monospheres", "grid_random"});
  expectError("base: base.yaml\nmethod: {planner: {viewpoints: {min_value: 0}}}\n",
              {"method.planner.viewpoints.min_value"});
  expectError("base: base.yaml\nmission: {map_rate_hz: -1}\n", {"mission.map_rate_hz"});
  expectError("base: nowhere.yaml\n", {"bad.yaml", "key 'base'", "file not found"});
  // Before: "file not found: .../b" (the name cut at the NUL).
  expectError("base: \"b\\0ase.yaml\"\n", {"bad.yaml", "key 'base'", "NUL character"});
  // Before: the file's own frontend.mistrack_share silently overrode the preset asked for.
  expectError("base: base.yaml\nfrontend: {preset: clean, mistrack_share: 0.2}\n",
              {"--set frontend.preset", "also sets frontend.mistrack_share", "override"}, {"frontend.preset=severe"});
  expectError("base: bad.yaml\n", {"circular"});
  expectError("world: missing.xml\n", {"bad.yaml", "world", "file not found"});
  expectError("base: base.yaml\nexploration_box: {min: [0, 0, 0]}\n", {"exploration_box.max", "required"});
  expectError("base: base.yaml\n", {"method.planner.carrot", "unknown key"}, {"method.planner.carrot=3"});
  expectError("base: base.yaml\n", {"--set", "KEY=VALUE"}, {"novalue"});
  expectError("base: base.yaml\n", {"--set", "not a map"}, {"seed.x=1"});
  // Front-end degradation: presets by name, axes range-checked, unknown axes refused.
  expectError("base: base.yaml\nfrontend: {preset: awful}\n",
              {"frontend.preset", "unknown preset 'awful'", "clean", "real_flight"});
  expectError("base: base.yaml\nfrontend: {mistrack_share: 0.9}\n", {"frontend.mistrack_share", "[0, 0.5]"});
  expectError("base: base.yaml\nfrontend: {blur_px: 2}\n", {"frontend.blur_px", "unknown key"});
  expectError("base: base.yaml\nfrontend: {drift_scale: 15}\nvio_drift: {position_drift_fraction: 0.1}\n",
              {"position_drift_fraction", "scaled by frontend.drift_scale"});
}

TEST(ScenarioYaml, ThePublishedCodeSwitches) {
  // method.reference_code: `published` turns every switch on; in a map, `published: true` first,
  // then the switches named beside it; each switch alone; recorded for the run and read back.
  const fs::path d = tempDir();
  write(d / "base.yaml", kBase);
  write(d / "published.yaml", "base: base.yaml\nmethod: {reference_code: published}\n");
  const ScenarioSpec p = loadScenario((d / "published.yaml").string());
  EXPECT_TRUE(mono(p).reference_code.path_resend_8s);
  EXPECT_TRUE(mono(p).reference_code.safety_cost_inverted);
  for (const auto& [name, on] : p.method.reference_code) EXPECT_TRUE(on) << name;
  EXPECT_EQ(p.method.reference_code.size(), ReferenceCodeConfig::switches().size());
  write(d / "minus.yaml",
        "base: base.yaml\nmethod: {reference_code: {published: true, heading_check_signed: false}}\n");
  const ScenarioSpec m = loadScenario((d / "minus.yaml").string());
  EXPECT_FALSE(mono(m).reference_code.heading_check_signed);
  EXPECT_TRUE(mono(m).reference_code.viewpoints_anywhere);
  const ScenarioSpec one = loadScenario((d / "base.yaml").string(), {"method.reference_code.path_resend_8s=true"});
  EXPECT_TRUE(mono(one).reference_code.path_resend_8s);
  EXPECT_FALSE(mono(one).reference_code.viewpoints_anywhere);
  const ScenarioSpec set = loadScenario((d / "base.yaml").string(), {"method.reference_code=published"});
  EXPECT_TRUE(mono(set).reference_code.any());
  // The intended method by default; the effective configuration writes every switch.
  const ScenarioSpec none = loadScenario((d / "base.yaml").string());
  EXPECT_FALSE(mono(none).reference_code.any());
  const std::string text = effectiveScenarioYaml(m);
  EXPECT_NE(text.find("heading_check_signed: false"), std::string::npos) << text;
  EXPECT_NE(text.find("path_resend_8s: true"), std::string::npos) << text;
}

// The published configuration (docs/deviations.md): `reference_code: published` also takes the
// authors' settings — MonoSpheres r_min 1.6 m and FFF's 0.314159 rad/m (mrs_sim.yaml), the grid
// unknown space traversable and a pruned OctoMap (the grid session) — before the keys named beside
// it, which win; the intended method keeps msbench's; the written configuration reads back the same.
TEST(ScenarioYaml, ThePublishedConfigurationTakesTheAuthorsSettingsAndNamedKeysWin) {
  const fs::path d = tempDir();
  write(d / "base.yaml", kBase);
  write(d / "published.yaml", "base: base.yaml\nmethod: {reference_code: published}\n");
  const ScenarioSpec p = loadScenario((d / "published.yaml").string());
  EXPECT_DOUBLE_EQ(mono(p).map.r_min_m, 1.6);
  EXPECT_DOUBLE_EQ(mono(p).planner.goals.fff_turn_rate_rad_per_m, 0.314159);
  EXPECT_DOUBLE_EQ(mono(p).planner.goals.local_radius_m, 12.0);  // the base's key still applies
  const ScenarioSpec named = loadScenario((d / "published.yaml").string(), {"method.map.r_min_m=1.4"});
  EXPECT_DOUBLE_EQ(mono(named).map.r_min_m, 1.4);
  EXPECT_DOUBLE_EQ(mono(loadScenario((d / "base.yaml").string())).map.r_min_m, 1.4);
  // Switch by switch (no `published`), the settings stay msbench's.
  const ScenarioSpec one = loadScenario((d / "base.yaml").string(), {"method.reference_code.path_resend_8s=true"});
  EXPECT_DOUBLE_EQ(mono(one).map.r_min_m, 1.4);
  // config.yaml reads back to the same configuration.
  write(d / "effective.yaml", effectiveScenarioYaml(p));
  EXPECT_EQ(effectiveScenarioYaml(loadScenario((d / "effective.yaml").string())), effectiveScenarioYaml(p));
  // The grid.
  write(d / "grid.yaml", "world: world.xml\nmethod: {type: grid_random, reference_code: published}\n");
  const ScenarioSpec g = loadScenario((d / "grid.yaml").string());
  const auto& gc = std::any_cast<const GridExplorerConfig&>(g.method.config);
  // The authors' A*: known free cells only, no clearance from unknown ones (issue 91).
  EXPECT_TRUE(gc.planner.unknown_is_occupied);
  EXPECT_EQ(gc.planner.unknown_clearance_m, 0.0);
  EXPECT_TRUE(gc.map.prune);
  const ScenarioSpec gi = loadScenario((d / "grid.yaml").string(), {"method.reference_code=intended"});
  EXPECT_TRUE(std::any_cast<const GridExplorerConfig&>(gi.method.config).planner.unknown_is_occupied);
  EXPECT_EQ(std::any_cast<const GridExplorerConfig&>(gi.method.config).planner.unknown_clearance_m, -1.0);
  // A key named beside the profile wins over it (a config.yaml of an earlier run replays as flown).
  const ScenarioSpec gn = loadScenario((d / "grid.yaml").string(), {"method.planner.unknown_is_occupied=false"});
  EXPECT_FALSE(std::any_cast<const GridExplorerConfig&>(gn.method.config).planner.unknown_is_occupied);
  EXPECT_TRUE(std::any_cast<const GridExplorerConfig&>(gn.method.config).map.prune);
}

// `published` flies its paths through the MRS trajectory generator (issue 91): by name, as a map
// with `published: true`, for the grid too; a scenario that names the generator keeps it; the
// intended method and switch-by-switch runs keep msbench's tracker; a speed-set name also picks
// the MRS constraint set of that name; config.yaml names the generator, so a run replays as flown.
TEST(ScenarioYaml, PublishedFliesTheMrsGeneratorUnlessTheScenarioNamesOne) {
  const fs::path d = tempDir();
  write(d / "base.yaml", kBase);
  write(d / "published.yaml", "base: base.yaml\nmethod: {reference_code: published}\n");
  const ScenarioSpec p = loadScenario((d / "published.yaml").string(), {"trajectory.limits=fast"});
  EXPECT_EQ(p.flight.trajectory.generator, "mrs");
  EXPECT_DOUBLE_EQ(p.flight.trajectory.mrs.constraints.vertical_speed_mps, 4.0);  // MRS `fast`
  EXPECT_DOUBLE_EQ(p.flight.trajectory.mrs.constraints.horizontal_jerk_mps3, 60.0);
  EXPECT_EQ(loadScenario((d / "base.yaml").string()).flight.trajectory.generator, "msbench");
  EXPECT_EQ(loadScenario((d / "base.yaml").string(), {"method.reference_code.raw_sphere_paths=true"})
                .flight.trajectory.generator,
            "msbench");
  EXPECT_EQ(
      loadScenario((d / "base.yaml").string(), {"method.reference_code.published=true"}).flight.trajectory.generator,
      "mrs");
  const ScenarioSpec named = loadScenario((d / "published.yaml").string(), {"trajectory.generator=msbench"});
  EXPECT_EQ(named.flight.trajectory.generator, "msbench");
  write(d / "grid.yaml", "world: world.xml\nmethod: {type: grid_random, reference_code: published}\n");
  EXPECT_EQ(loadScenario((d / "grid.yaml").string()).flight.trajectory.generator, "mrs");
  // The effective configuration names the generator and its constraint set.
  write(d / "effective.yaml", effectiveScenarioYaml(p));
  const ScenarioSpec back = loadScenario((d / "effective.yaml").string());
  EXPECT_EQ(back.flight.trajectory.generator, "mrs");
  EXPECT_EQ(effectiveScenarioYaml(back), effectiveScenarioYaml(p));
  // A constraint of the set named beside the speed set wins; an unknown generator is refused.
  EXPECT_DOUBLE_EQ(loadScenario((d / "published.yaml").string(),
                                {"trajectory.limits=fast", "trajectory.mrs.constraints.heading_accel_radps2=8"})
                       .flight.trajectory.mrs.constraints.heading_accel_radps2,
                   8.0);
  EXPECT_THROW(loadScenario((d / "base.yaml").string(), {"trajectory.generator=ros"}), FileConfigError);
}

// The message of the FileConfigError loading `path` throws ("" and a test failure if none).
std::string loadError(const fs::path& path) {
  try {
    loadScenario(path.string());
  } catch (const FileConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an error loading " << path;
  return "";
}

// A preset given by --set over a file's own values is fine when --set gives those values too, and
// over a file without the section; a base that is a symlink loop says so (before: "file not found").
TEST(ScenarioYaml, PresetSetsAndSymlinkLoops) {
  const fs::path d = tempDir();
  write(d / "base.yaml", kBase);
  write(d / "s.yaml", "base: base.yaml\nfrontend: {preset: clean, mistrack_share: 0.2}\n");
  EXPECT_NO_THROW(loadScenario((d / "s.yaml").string(), {"frontend.preset=severe", "frontend.mistrack_share=0.1"}));
  // A preset over a file without that section (the conditions sweep's axis; before: "invalid node").
  const ScenarioSpec noon = loadScenario((d / "s.yaml").string(), {"conditions.preset=noon"});
  EXPECT_EQ(noon.flight.render.conditions.sun_elevation_deg, 75.0);
  fs::remove(d / "l1.yaml"), fs::remove(d / "l2.yaml");
  fs::create_symlink(d / "l2.yaml", d / "l1.yaml");
  fs::create_symlink(d / "l1.yaml", d / "l2.yaml");
  write(d / "loop.yaml", "base: l1.yaml\n");
  EXPECT_NE(loadError(d / "loop.yaml").find("symbolic links"), std::string::npos);
}

// A key's error names the file of the base chain that gave the key (before: always the
// scenario file, so an error in a base pointed at a file without that key).
TEST(ScenarioYaml, AnErrorInABaseNamesTheBase) {
  const fs::path d = tempDir();
  const std::string top = (d / "top.yaml").string();
  write(d / "base.yaml", std::string(kBase) + "exploration_bo: {min: [0, 0, 0]}\n");
  write(d / "mid.yaml", "base: base.yaml\nduration_s: -4\n");
  write(top, "base: mid.yaml\nseed: 2\n");
  std::string msg = loadError(top);
  EXPECT_NE(msg.find("base.yaml (a base of " + top + "): key 'exploration_bo'"), std::string::npos) << msg;
  write(d / "base.yaml", kBase);
  msg = loadError(top);
  EXPECT_NE(msg.find("mid.yaml (a base of"), std::string::npos) << msg;
  EXPECT_NE(msg.find("duration_s"), std::string::npos) << msg;
  // The scenario's own key, and a key the scenario overrides, name the scenario.
  write(top, "base: mid.yaml\nduration_s: -3\n");
  msg = loadError(top);
  EXPECT_EQ(msg.find("a base of"), std::string::npos) << msg;
  EXPECT_EQ(msg.rfind(top + ": key 'duration_s'", 0), 0u) << msg;
}

// A bad value given on the command line (--set, --seed, a sweep's `set:`) is named as the
// --set it came from, not as the base whose node the merged tree once shared (before: the
// last base, "base.yaml (a base of …)", which does not hold the value).
TEST(ScenarioYaml, AnErrorInASetValueNamesTheSet) {
  const fs::path d = tempDir();
  const std::string top = (d / "top.yaml").string();
  write(d / "base.yaml", kBase);
  write(top, "base: base.yaml\nseed: 2\n");
  for (const auto& [set, key] : std::vector<std::pair<std::string, std::string>>{
           {"duration_s=-5", "duration_s"}, {"seed=-1", "seed"}, {"method.map.r_max_m=-2", "method.map.r_max_m"}}) {
    std::string msg;
    try {
      loadScenario(top, {set});
      ADD_FAILURE() << "expected an error for --set " << set;
    } catch (const FileConfigError& e) {
      msg = e.what();
    }
    EXPECT_EQ(msg.find("a base of"), std::string::npos) << msg;
    EXPECT_EQ(msg.rfind(top + " (with --set " + key + "): key '" + key + "'", 0), 0u) << msg;
  }
  // A key the files give is still named by its file when another key is --set.
  write(d / "base.yaml", std::string(kBase) + "exploration_bo: {min: [0, 0, 0]}\n");
  try {
    loadScenario(top, {"duration_s=10"});
    ADD_FAILURE() << "expected an error";
  } catch (const FileConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("base.yaml (a base of"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// The effective configuration reads back to the same configuration: a named world without a
// start (the world's start applies), a conditions preset with unset fields, a --set override,
// angles in degrees, every method.
TEST(ScenarioYaml, TheEffectiveConfigurationReadsBackToItself) {
  const fs::path d = tempDir();
  for (const MethodRegistration& reg : methodRegistrations()) {
    const MethodInfo& method = reg.info;
    SCOPED_TRACE(method.type);
    write(d / "named.yaml",
          "world: urban\nconditions: {preset: dusk}\nfrontend: {preset: real_flight, drift_scale: 3}\n"
          "method: {type: " +
              method.type + (method.type == "python" ? ", entry: \"m:f\", params: {a: 1, b: [x, 2]}" : "") + "}\n");
    const ScenarioSpec s = loadScenario((d / "named.yaml").string(), {"camera.mount_pitch_down_deg=7.5", "seed=4"});
    const std::string text = effectiveScenarioYaml(s);
    EXPECT_EQ(text.find("start:"), std::string::npos) << "the world's start applies";
    EXPECT_NE(text.find("world: urban"), std::string::npos);
    EXPECT_NE(text.find("mount_pitch_down_deg: 7.5"), std::string::npos);
    EXPECT_NE(text.find("image_noise_sigma: 4"), std::string::npos);  // the preset's, written out
    EXPECT_NE(text.find("drift_scale: 3"), std::string::npos);        // the override wins
    write(d / "effective.yaml", text);
    const ScenarioSpec again = loadScenario((d / "effective.yaml").string());
    EXPECT_TRUE(again.start_from_world);
    EXPECT_EQ(effectiveScenarioYaml(again), text);
  }
}

// Every shipped scenario, example and flight file loads (sweeps: Sweep.EveryShippedSweepLoadsEveryRun);
// base.yaml is a base only, and a method file (no world of its own) loads with one.
TEST(ScenarioYaml, EveryShippedFileLoads) {
  const fs::path src(MSB_SOURCE_DIR);
  int n = 0;
  for (const fs::path& dir : {src / "scenarios/missions", src / "examples"})
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() != ".yaml" || e.path().filename() == "base.yaml") continue;
      std::ifstream in(e.path());
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      const bool has_world = text.rfind("world:", 0) == 0 || text.find("\nworld:") != std::string::npos;
      const std::vector<std::string> sets =
          has_world ? std::vector<std::string>{} : std::vector<std::string>{"world=urban"};
      EXPECT_NO_THROW(loadScenario(e.path().string(), sets)) << e.path();
      ++n;
    }
  for (const fs::path& dir : {src / "scenarios/fly", src / "scenarios/vio"})
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() != ".yaml") continue;
      EXPECT_NO_THROW(loadFlightSpec(e.path().string())) << e.path();
      ++n;
    }
  EXPECT_GE(n, 25);
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// A key under a preset name is set on the preset's values; one boolean rule for every key.
TEST(ScenarioYaml, AKeyUnderAPresetAndOneBooleanRule) {
  const std::string urban = std::string(MSB_SOURCE_DIR) + "/scenarios/missions/urban_short.yaml";
  const ScenarioSpec s = loadScenario(urban, {"trajectory.limits.max_yaw_rate_radps=1.5"});
  const TrajectoryLimits medium = TrajectoryLimits::preset("medium");
  EXPECT_DOUBLE_EQ(s.flight.trajectory.limits.max_yaw_rate_radps, 1.5);
  EXPECT_DOUBLE_EQ(s.flight.trajectory.limits.max_speed_mps, medium.max_speed_mps);
  EXPECT_DOUBLE_EQ(s.flight.trajectory.limits.max_accel_mps2, medium.max_accel_mps2);
  for (const char* word : {"yes", "no", "on", "off", "y", "1", "0", "\"yes\""})
    EXPECT_THROW(loadScenario(urban, {std::string("video.enabled=") + word}), FileConfigError) << word;
  for (const char* word : {"true", "false", "\"true\""})
    EXPECT_NO_THROW(loadScenario(urban, {std::string("video.enabled=") + word})) << word;
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// A newcomer's scenario kept anywhere names its base by a mission's name; a typo in a key or a
// method type gets the nearest name.
TEST(ScenarioYaml, BaseByNameAndDidYouMean) {
  const fs::path d = fs::path(::testing::TempDir()) / "msb_base_by_name";
  fs::create_directories(d);
  std::ofstream(d / "mine.yaml") << "base: urban_short\nduration_s: 5\n";
  const ScenarioSpec s = loadScenario((d / "mine.yaml").string(), {});
  EXPECT_DOUBLE_EQ(s.flight.duration_s, 5.0);
  EXPECT_EQ(s.flight.world_name, "urban");
  auto error = [&](const std::string& set) {
    try {
      loadScenario((d / "mine.yaml").string(), {set});
    } catch (const FileConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("method.map.r_max=3").find("did you mean 'method.map.r_max_m'?"), std::string::npos);
  EXPECT_NE(error("method.type=monosphere").find("did you mean 'monospheres'?"), std::string::npos);
  EXPECT_EQ(error("zzzz=1").find("did you mean"), std::string::npos) << error("zzzz=1");
}

}  // namespace
}  // namespace msb
