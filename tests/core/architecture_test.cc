// Architecture rule (DESIGN §1): nothing under core/ includes MuJoCo, GL/OSMesa/EGL or yaml-cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace {

TEST(Architecture, CoreIncludesNoSimulatorGlOrYamlHeaders) {
  namespace fs = std::filesystem;
  const fs::path core = fs::path(MSB_SOURCE_DIR) / "core";
  ASSERT_TRUE(fs::is_directory(core));
  const std::regex forbidden(R"(^\s*#\s*include\s*[<"](mujoco/|GL/|EGL/|yaml-cpp/|mujoco\.h))");
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(core)) {
    const auto ext = e.path().extension();
    if (ext != ".h" && ext != ".cc" && ext != ".hpp" && ext != ".cpp") continue;
    ++files;
    std::ifstream in(e.path());
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      EXPECT_FALSE(std::regex_search(line, forbidden)) << e.path() << ":" << n << ": " << line;
    }
  }
  EXPECT_GT(files, 5);
}

TEST(Architecture, TheRuleDetectsAForbiddenInclude) {
  // Guards the regex above against silently matching nothing.
  const std::regex forbidden(R"(^\s*#\s*include\s*[<"](mujoco/|GL/|EGL/|yaml-cpp/|mujoco\.h))");
  EXPECT_TRUE(std::regex_search("#include <mujoco/mujoco.h>", forbidden));
  EXPECT_TRUE(std::regex_search("  #include \"yaml-cpp/yaml.h\"", forbidden));
  EXPECT_TRUE(std::regex_search("#include <GL/osmesa.h>", forbidden));
  EXPECT_FALSE(std::regex_search("#include <opencv2/core.hpp>", forbidden));
}

}  // namespace
