// Architecture rules (docs/architecture.md, "Layers"), checked on the source text:
//  - nothing under core/ includes MuJoCo, GL/OSMesa/EGL or yaml-cpp, nor anything of sim/ or tools/;
//  - the method interface (core/explorer) includes and links core/common alone;
//  - exploration methods (every folder under core/methods/, and core/grid, the grid they share)
//    never see ground truth nor the metric: no include of core/geometry/ or core/eval/ (every
//    header there), no link to msb::geometry, msb::eval or msb::eval_truth in any of their
//    CMakeLists.txt; the example method (core/methods/hover_turn) includes and links the interface
//    alone;
//  - a method is its folder: no source outside core/methods/<type>/ includes its headers, save
//    the extensions not yet moved into their method's folder (kExtensionsOutside, which may only
//    shrink), and none spells its type;
//  - sim/ includes no mapping or planning; the engine (tools/engine) includes no yaml-cpp;
//  - tools/: only tools/config includes yaml-cpp; config and results include neither each other
//    nor the sweep or the command line; the sweep does not include the command line; the Python
//    layer (tools/python) includes nothing of the metric (core/eval).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

// Every method's folder (core/methods/<type>/) under the source tree `root`, sorted.
std::vector<fs::path> methodFolders(const fs::path& root) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(root / "core" / "methods"))
    if (e.is_directory()) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// The folders a method's code lives in: every method's folder and the grid they share.
std::vector<fs::path> methodSideFolders() {
  const fs::path src(MSB_SOURCE_DIR);
  std::vector<fs::path> out = methodFolders(src);
  out.push_back(src / "core" / "grid");
  return out;
}

// Every CMakeLists.txt at or below `dir`, with its text.
std::vector<std::pair<fs::path, std::string>> cmakeFiles(const fs::path& dir) {
  std::vector<std::pair<fs::path, std::string>> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().filename() != "CMakeLists.txt") continue;
    std::ifstream in(e.path());
    std::stringstream text;
    text << in.rdbuf();
    out.emplace_back(e.path(), text.str());
  }
  return out;
}

// Every line of the C++ sources under `dir` that matches `rule`, as "file:line: text".
std::vector<std::string> matchingLines(const fs::path& dir, const std::regex& rule, int* files = nullptr) {
  std::vector<std::string> hits;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const auto ext = e.path().extension();
    if (ext != ".h" && ext != ".cc" && ext != ".hpp" && ext != ".cpp") continue;
    if (files) ++*files;
    std::ifstream in(e.path());
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
      if (std::regex_search(line, rule)) hits.push_back(e.path().string() + ":" + std::to_string(n) + ": " + line);
  }
  return hits;
}

const std::regex kForbiddenInCore(R"(^\s*#\s*include\s*[<"](mujoco/|GL/|EGL/|yaml-cpp/|mujoco\.h|sim/|tools/))");

TEST(Architecture, CoreIncludesNoSimulatorGlYamlSimOrTools) {
  int files = 0;
  for (const auto& hit : matchingLines(fs::path(MSB_SOURCE_DIR) / "core", kForbiddenInCore, &files))
    ADD_FAILURE() << hit;
  EXPECT_GT(files, 5);
}

TEST(Architecture, TheRuleDetectsAForbiddenInclude) {
  // Guards the regex above against silently matching nothing.
  EXPECT_TRUE(std::regex_search("#include <mujoco/mujoco.h>", kForbiddenInCore));
  EXPECT_TRUE(std::regex_search("  #include \"yaml-cpp/yaml.h\"", kForbiddenInCore));
  EXPECT_TRUE(std::regex_search("#include <GL/osmesa.h>", kForbiddenInCore));
  EXPECT_TRUE(std::regex_search("#include \"sim/physics/quadrotor_sim.h\"", kForbiddenInCore));
  EXPECT_TRUE(std::regex_search("#include \"tools/engine/records.h\"", kForbiddenInCore));
  EXPECT_FALSE(std::regex_search("#include <opencv2/core.hpp>", kForbiddenInCore));
}

TEST(Architecture, TheMethodInterfaceDependsOnCommonAlone) {
  const fs::path dir = fs::path(MSB_SOURCE_DIR) / "core" / "explorer";
  const std::regex other(R"(^\s*#\s*include\s*"(?!core/(common|explorer)/))");
  int files = 0;
  for (const auto& hit : matchingLines(dir, other, &files)) ADD_FAILURE() << hit;
  EXPECT_GT(files, 2);
  const std::regex link(R"(msb::(?!common\b|explorer\b)\w+)");
  for (const auto& [path, text] : cmakeFiles(dir))
    EXPECT_FALSE(std::regex_search(text, link)) << path << " links more than msb::common";
}

TEST(Architecture, MethodsCannotSeeGroundTruthOrTheMetric) {
  // Every header of core/geometry and core/eval: the truth and the metric that scores a method.
  const std::regex eval_include(R"(^\s*#\s*include\s*"core/(geometry|eval)/)");
  for (const char* header : {"core/eval/collision_audit.h", "core/eval/column_coverage.h", "core/eval/map_safety.h",
                             "core/geometry/world_truth.h"})
    EXPECT_TRUE(std::regex_search("#include \"" + std::string(header) + "\"", eval_include)) << header;
  EXPECT_FALSE(std::regex_search("#include \"core/explorer/snapshot.h\"", eval_include));
  const std::regex eval_link(R"(msb::(geometry|eval|eval_truth)\b)");
  int cmake_files = 0;
  for (const fs::path& dir : methodSideFolders()) {
    ASSERT_TRUE(fs::is_directory(dir)) << dir;
    for (const auto& hit : matchingLines(dir, eval_include)) ADD_FAILURE() << hit;
    for (const auto& [path, text] : cmakeFiles(dir)) {
      ++cmake_files;
      EXPECT_FALSE(std::regex_search(text, eval_link)) << path << " links ground truth or the metric";
    }
  }
  EXPECT_GE(cmake_files, 5);  // grid and the four methods
}

TEST(Architecture, MethodCountersAreTypedNotStrings) {
  // A method's counters are named once beside their enumerator (core/explorer/counters.h): a
  // counter written by a string key (`c["name"] = …`) would be a misspelling waiting to happen.
  const std::regex string_key(R"(\[\s*"[A-Za-z_]+"\s*\]\s*(\+|-)?=)");
  EXPECT_TRUE(std::regex_search("  c[\"spheres\"] = double(n);", string_key));
  EXPECT_TRUE(std::regex_search("c[\"links\"] += 0.5;", string_key));
  EXPECT_FALSE(std::regex_search("c[C::kSpheres] = double(n);", string_key));
  for (const fs::path& dir : methodSideFolders())
    for (const auto& hit : matchingLines(dir, string_key)) ADD_FAILURE() << hit;
}

TEST(Architecture, TheExampleMethodUsesTheInterfaceAlone) {
  const fs::path dir = fs::path(MSB_SOURCE_DIR) / "core" / "methods" / "hover_turn";
  const std::regex other(R"(^\s*#\s*include\s*"(?!core/(common|explorer|methods/hover_turn)/))");
  int files = 0;
  for (const auto& hit : matchingLines(dir, other, &files)) ADD_FAILURE() << hit;
  EXPECT_GE(files, 2);
  const std::regex link(R"(msb::(?!common\b|explorer\b)\w+)");
  for (const auto& [path, text] : cmakeFiles(dir)) EXPECT_FALSE(std::regex_search(text, link)) << path;
}

// A method is its folder: the example method registers itself from core/methods/hover_turn/
// (hover_turn_method.cc), so no code outside the folder names it — no central table, no
// CMake list (comments aside).
TEST(Architecture, NoCodeOutsideTheExampleMethodsFolderNamesIt) {
  const std::regex named(R"(^\s*[^/\s].*(HoverTurn|"hover_turn"))");
  EXPECT_TRUE(std::regex_search("  methodEntry<HoverTurnExplorer, HoverTurnConfig>(", named));
  EXPECT_FALSE(std::regex_search("//   registerMethod<HoverTurnExplorer, HoverTurnConfig>(", named));
  const fs::path folder = fs::path(MSB_SOURCE_DIR) / "core" / "methods" / "hover_turn";
  int files = 0;
  for (const char* top : {"core", "sim", "tools"}) {
    for (const auto& hit : matchingLines(fs::path(MSB_SOURCE_DIR) / top, named, &files)) {
      if (hit.rfind(folder.string(), 0) != 0) ADD_FAILURE() << hit;
    }
  }
  EXPECT_GT(files, 100);
  for (const char* top : {"core", "sim", "tools", "cmake"}) {
    for (const auto& [path, text] : cmakeFiles(fs::path(MSB_SOURCE_DIR) / top)) {
      if (path.string().rfind(folder.string(), 0) == 0) continue;
      EXPECT_EQ(text.find("hover_turn"), std::string::npos) << path;
    }
  }
}

// The method folder (core/methods/<type>/) `file` is in, or empty.
fs::path methodFolderOf(const fs::path& file) {
  const fs::path methods = fs::path(MSB_SOURCE_DIR) / "core" / "methods";
  const fs::path rel = file.lexically_relative(methods);
  if (rel.empty() || *rel.begin() == "..") return {};
  return methods / *rel.begin();
}

// Every method registered from a folder, as the build's clash check reads them
// (cmake/MethodTypes.cmake): type → its method's folder (core/methods/<folder>/).
std::map<std::string, fs::path> registeredTypes() {
  const std::regex call(R"re(registerMethod<[^>]*>\s*\(\s*\{\s*"([^"]*)")re");
  std::map<std::string, fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(MSB_SOURCE_DIR) / "core")) {
    if (e.path().extension() != ".cc") continue;
    std::ifstream in(e.path());
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    for (std::sregex_iterator m(text.begin(), text.end(), call), end; m != end; ++m)
      out[(*m)[1].str()] = methodFolderOf(e.path());
  }
  return out;
}

// Every method is its folder: no code outside the folder that registers it spells its type
// (`"grid_random"`), comments aside. Two places name the paper's methods as data, by design:
// the default method of a scenario (tools/engine/methods.h, MonoSpheres) and the paper's findings
// the report checks (tools/sweep/findings.*, which compare MonoSpheres with the grid).
TEST(Architecture, NoCodeOutsideAMethodsFolderSpellsItsType) {
  const auto types = registeredTypes();
  for (const char* t : {"monospheres", "grid_random", "star_discovery", "hover_turn", "python"})
    EXPECT_TRUE(types.count(t)) << t << " is not registered from a folder";
  const fs::path src(MSB_SOURCE_DIR);
  const std::set<fs::path> data = {src / "tools/engine/methods.h", src / "tools/sweep/findings.cc",
                                   src / "tools/sweep/findings.h"};
  for (const auto& [type, folder] : types) {
    const std::regex spelt("^\\s*[^/\\s].*\"" + type + "( [^\"]*)?\"");
    for (const char* top : {"core", "sim", "tools"})
      for (const auto& hit : matchingLines(src / top, spelt)) {
        const fs::path file = hit.substr(0, hit.find(':'));
        if (methodFolderOf(file) == folder || data.count(file)) continue;
        ADD_FAILURE() << type << " (registered in " << folder.string() << ") spelt at " << hit;
      }
  }
  EXPECT_TRUE(
      std::regex_search("  {\"monospheres -ovde\", \"x\"},", std::regex("^\\s*[^/\\s].*\"monospheres( [^\"]*)?\"")));
}

// The headers of a method included from outside its folder that are known: the extensions of a
// method not yet moved into its folder (issue 95), as (including file, method). The list may only
// shrink: a new include from outside fails, and so does an entry whose include has gone.
const std::set<std::pair<std::string, std::string>> kExtensionsOutside = {
    {"tools/config/method_table.cc", "monospheres"},     // readSphereMapKeys: map-replay's --set map.KEY
    {"tools/config/scenario_yaml.h", "monospheres"},     // loadMapOverrides: the same
    {"tools/msbench/cmd_bench_map.cc", "monospheres"},   // msbench bench-map
    {"tools/msbench/cmd_grid_audit.cc", "grid_random"},  // msbench grid-audit
    {"tools/msbench/cmd_map_replay.cc", "monospheres"},  // msbench map-replay
    {"tools/msbench/map_replay.h", "monospheres"},
    {"tools/python/goal_choosers.cc", "grid_random"},  // the Python goal and viewpoint choosers
    {"tools/python/goal_choosers.cc", "monospheres"},
    // A scenario's goals: section names an outside chooser as a Python method names its code.
    {"tools/engine/scenario_spec.h", "python"},
};

// Every include of a method's header (core/methods/<type>/) from a C++ source under `root`'s
// core/, sim/ or tools/ outside that method's folder, as (file relative to `root`, type).
std::set<std::pair<std::string, std::string>> methodIncludesFromOutside(const fs::path& root) {
  const std::regex include(R"re(^\s*#\s*include\s*"core/methods/([A-Za-z0-9_]+)/)re");
  std::set<std::pair<std::string, std::string>> out;
  for (const char* top : {"core", "sim", "tools"}) {
    if (!fs::exists(root / top)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root / top)) {
      const auto ext = e.path().extension();
      if (ext != ".h" && ext != ".cc" && ext != ".hpp" && ext != ".cpp") continue;
      const fs::path rel = e.path().lexically_relative(root);
      auto part = rel.begin();
      const bool in_methods = *part == "core" && ++part != rel.end() && *part == "methods" && ++part != rel.end();
      const std::string own = in_methods ? part->string() : "";
      std::ifstream in(e.path());
      std::smatch m;
      for (std::string line; std::getline(in, line);)
        if (std::regex_search(line, m, include) && m[1].str() != own) out.emplace(rel.string(), m[1].str());
    }
  }
  return out;
}

TEST(Architecture, NoSourceOutsideAMethodsFolderIncludesItsHeaders) {
  const auto found = methodIncludesFromOutside(fs::path(MSB_SOURCE_DIR));
  for (const auto& [file, type] : found)
    if (!kExtensionsOutside.count({file, type}))
      ADD_FAILURE() << file << " includes a header of " << type << " from outside core/methods/" << type << "/";
  for (const auto& [file, type] : kExtensionsOutside)
    EXPECT_TRUE(found.count({file, type}))
        << file << " no longer includes " << type << ": take it off kExtensionsOutside";
}

TEST(Architecture, TheMethodIncludeRuleFailsOnAPlantedInclude) {
  // A tree with two methods: a's own include is no hit; b's and a tool's include of a's header are.
  const fs::path root = fs::path(::testing::TempDir()) / "msb_arch_methods";
  fs::remove_all(root);
  for (const char* dir : {"core/methods/a/part", "core/methods/b", "tools/x"}) fs::create_directories(root / dir);
  std::ofstream(root / "core/methods/a/part/a.cc") << "#include \"core/methods/a/a.h\"\n";
  std::ofstream(root / "core/methods/b/b.cc") << "#include \"core/methods/a/a.h\"\n";
  std::ofstream(root / "tools/x/y.cc")
      << "// #include \"core/methods/b/b.h\"\n  #include \"core/methods/a/part/a.h\"\n";
  const std::set<std::pair<std::string, std::string>> want = {{"core/methods/b/b.cc", "a"}, {"tools/x/y.cc", "a"}};
  EXPECT_EQ(methodIncludesFromOutside(root), want);
}

TEST(Architecture, SimHasNoMappingOrPlanningAndTheLoopNoYaml) {
  const std::regex mapping(R"(^\s*#\s*include\s*"core/(methods|grid|perception|eval)/)");
  for (const auto& hit : matchingLines(fs::path(MSB_SOURCE_DIR) / "sim", mapping)) ADD_FAILURE() << hit;
  const std::regex yaml(R"(^\s*#\s*include\s*[<"](yaml-cpp/|tools/msbench/))");
  for (const auto& hit : matchingLines(fs::path(MSB_SOURCE_DIR) / "tools" / "engine", yaml)) ADD_FAILURE() << hit;
}

// The include rules of tools/' libraries: folder → includes it must not have.
const struct {
  const char* folder;
  const char* forbidden;
} kToolsRules[] = {
    {"engine", "yaml-cpp/|tools/config/|tools/results/|tools/sweep/|tools/msbench/"},
    {"config", "tools/results/|tools/sweep/|tools/msbench/"},
    {"results", "yaml-cpp/|tools/config/|tools/sweep/|tools/msbench/"},
    {"sweep", "yaml-cpp/|tools/msbench/"},
    {"msbench", "yaml-cpp/"},
    // The Python layer hands a method's output to the loop: it checks the method contract
    // (core/explorer/output_limits.h), never the metric's internals; YAML reaches it through
    // tools/config (yaml_json.h), never yaml-cpp itself.
    {"python", "yaml-cpp/|core/eval/"},
};

std::regex includeOf(const std::string& forbidden) {
  return std::regex(R"(^\s*#\s*include\s*[<"]()" + forbidden + ")");
}

// Every line under `tools` (a tools/ tree) that breaks a rule of kToolsRules; `files` counts
// the sources each rule's folder holds (absent folders count 0).
std::vector<std::string> toolsRuleHits(const fs::path& tools, std::vector<int>* files) {
  std::vector<std::string> hits;
  for (const auto& r : kToolsRules) {
    int n = 0;
    if (fs::exists(tools / r.folder))
      for (auto& hit : matchingLines(tools / r.folder, includeOf(r.forbidden), &n)) hits.push_back(hit);
    files->push_back(n);
  }
  return hits;
}

TEST(Architecture, ToolsLibrariesKeepTheirConcerns) {
  std::vector<int> files;
  for (const auto& hit : toolsRuleHits(fs::path(MSB_SOURCE_DIR) / "tools", &files)) ADD_FAILURE() << hit;
  for (size_t i = 0; i < files.size(); ++i) EXPECT_GT(files[i], 1) << kToolsRules[i].folder;
}

TEST(Architecture, TheToolsRulesFailOnAPlantedInclude) {
  // A copy of tools/python with one file that reaches the metric: the rule names it.
  const fs::path tools = fs::path(::testing::TempDir()) / "msb_arch_tools";
  fs::remove_all(tools);
  fs::create_directories(tools);
  fs::copy(fs::path(MSB_SOURCE_DIR) / "tools" / "python", tools / "python", fs::copy_options::recursive);
  std::vector<int> files;
  EXPECT_TRUE(toolsRuleHits(tools, &files).empty());
  std::ofstream(tools / "python" / "planted.cc")
      << "#include \"core/explorer/explorer.h\"\n#include \"core/eval/mission_coverage.h\"\n";
  files.clear();
  const auto hits = toolsRuleHits(tools, &files);
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_NE(hits[0].find("planted.cc:2"), std::string::npos) << hits[0];
  EXPECT_TRUE(std::regex_search("#include \"tools/sweep/sweep_report.h\"", includeOf("tools/sweep/")));
}

}  // namespace
