// Architecture rules (docs/architecture.md §1), checked on the source text:
//  - nothing under core/ includes MuJoCo, GL/OSMesa/EGL or yaml-cpp;
//  - exploration methods (every folder listed in kMethodFolders) never see ground truth: no
//    include of core/geometry/ or of the truth-based evaluation, no link to msb::geometry or
//    msb::eval_truth;
//  - sim/ includes no mapping or planning; the loop library (tools/loop) includes no yaml-cpp;
//  - tools/: only tools/config includes yaml-cpp; config and results include neither each other
//    nor the sweep or the command line; the sweep does not include the command line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

// The folders that hold exploration methods (a new method adds its folder here).
const char* const kMethodFolders[] = {"core/planning", "core/baseline"};

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

const std::regex kForbiddenInCore(R"(^\s*#\s*include\s*[<"](mujoco/|GL/|EGL/|yaml-cpp/|mujoco\.h))");

TEST(Architecture, CoreIncludesNoSimulatorGlOrYamlHeaders) {
  int files = 0;
  for (const auto& hit : matchingLines(fs::path(MSB_SOURCE_DIR) / "core", kForbiddenInCore, &files)) ADD_FAILURE() << hit;
  EXPECT_GT(files, 5);
}

TEST(Architecture, TheRuleDetectsAForbiddenInclude) {
  // Guards the regex above against silently matching nothing.
  EXPECT_TRUE(std::regex_search("#include <mujoco/mujoco.h>", kForbiddenInCore));
  EXPECT_TRUE(std::regex_search("  #include \"yaml-cpp/yaml.h\"", kForbiddenInCore));
  EXPECT_TRUE(std::regex_search("#include <GL/osmesa.h>", kForbiddenInCore));
  EXPECT_FALSE(std::regex_search("#include <opencv2/core.hpp>", kForbiddenInCore));
}

TEST(Architecture, MethodsCannotSeeGroundTruth) {
  const std::regex truth_include(
      R"(^\s*#\s*include\s*"core/(geometry/|eval/(mission_coverage|map_safety|slam_point_truth)\.h))");
  EXPECT_TRUE(std::regex_search("#include \"core/geometry/world_truth.h\"", truth_include));
  EXPECT_FALSE(std::regex_search("#include \"core/eval/column_coverage.h\"", truth_include));
  const std::regex truth_link(R"(msb::(geometry|eval_truth)\b)");
  for (const char* folder : kMethodFolders) {
    const fs::path dir = fs::path(MSB_SOURCE_DIR) / folder;
    ASSERT_TRUE(fs::is_directory(dir)) << dir;
    for (const auto& hit : matchingLines(dir, truth_include)) ADD_FAILURE() << hit;
    std::ifstream cmake(dir / "CMakeLists.txt");
    std::stringstream text;
    text << cmake.rdbuf();
    EXPECT_FALSE(std::regex_search(text.str(), truth_link)) << folder << "/CMakeLists.txt links ground truth";
  }
}

TEST(Architecture, SimHasNoMappingOrPlanningAndTheLoopNoYaml) {
  const std::regex mapping(R"(^\s*#\s*include\s*"core/(map|planning|perception|eval)/)");
  for (const auto& hit : matchingLines(fs::path(MSB_SOURCE_DIR) / "sim", mapping)) ADD_FAILURE() << hit;
  const std::regex yaml(R"(^\s*#\s*include\s*[<"](yaml-cpp/|tools/msbench/))");
  for (const auto& hit : matchingLines(fs::path(MSB_SOURCE_DIR) / "tools" / "loop", yaml)) ADD_FAILURE() << hit;
}

TEST(Architecture, ToolsLibrariesKeepTheirConcerns) {
  const fs::path tools = fs::path(MSB_SOURCE_DIR) / "tools";
  auto rule = [](const std::string& forbidden) {
    return std::regex(R"(^\s*#\s*include\s*[<"]()" + forbidden + ")");
  };
  const struct {
    const char* folder;
    std::string forbidden;
  } kRules[] = {
      {"loop", "yaml-cpp/|tools/config/|tools/results/|tools/sweep/|tools/msbench/"},
      {"config", "tools/results/|tools/sweep/|tools/msbench/"},
      {"results", "yaml-cpp/|tools/config/|tools/sweep/|tools/msbench/"},
      {"sweep", "yaml-cpp/|tools/msbench/"},
      {"msbench", "yaml-cpp/"},
  };
  for (const auto& r : kRules) {
    int files = 0;
    for (const auto& hit : matchingLines(tools / r.folder, rule(r.forbidden), &files)) ADD_FAILURE() << hit;
    EXPECT_GT(files, 1) << r.folder;
  }
  EXPECT_TRUE(std::regex_search("#include \"tools/sweep/sweep_report.h\"", rule("tools/sweep/")));
}

}  // namespace
