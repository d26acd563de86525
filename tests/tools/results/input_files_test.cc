// The one input reader (tools/results/input_files): what it refuses, and that it refuses without
// blocking, exhausting memory or recursing.
#include "tools/results/input_files.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace msb {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / "msb_input_files";
  fs::create_directories(d);
  const fs::path p = d / name;
  fs::remove_all(p);
  return p;
}

fs::path writeText(const std::string& name, const std::string& text) {
  const fs::path p = scratch(name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// The message of the InputFileError `f` throws (empty if it throws none).
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const InputFileError& e) {
    return e.what();
  }
  return "";
}

TEST(InputFiles, AFifoADeviceAndADirectoryAreRefusedWithoutReading) {
  // Before the shared reader, a FIFO as sweep.json or metrics.json blocked `report` forever.
  const fs::path fifo = scratch("fifo.json");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(refusal([&] { readJsonFile(fifo); }).find("is a FIFO, not a regular file"), std::string::npos);
  EXPECT_NE(refusal([&] { readInputFile("/dev/zero"); }).find("is a device"), std::string::npos);
  EXPECT_NE(refusal([&] { readInputFile(fifo.parent_path()); }).find("is a directory"), std::string::npos);
  EXPECT_NE(refusal([&] { readInputFile(scratch("absent.json")); }).find("file not found"), std::string::npos);
}

TEST(InputFiles, AFileOverTheSizeLimitIsRefusedNamingTheLimit) {
  const fs::path p = writeText("big.json", std::string(5000, ' ') + "{}");
  EXPECT_NE(refusal([&] {
              readJsonFile(p, InputLimits{4096, 64});
            }).find("more than the limit of 4096"),
            std::string::npos);
  EXPECT_TRUE(readJsonFile(p).is_object());
}

TEST(InputFiles, DeepNestingIsRefusedBeforeItIsBuilt) {
  // A million nested arrays crashed `report` (recursion) before the limit.
  const std::string deep = std::string(1000000, '[') + std::string(1000000, ']');
  EXPECT_NE(refusal([&] { parseJsonStrict(deep, "deep.json"); }).find("nested more than 64 levels"), std::string::npos);
  const std::string ok = std::string(60, '[') + std::string(60, ']');
  EXPECT_TRUE(parseJsonStrict(ok, "ok.json").is_array());
}

TEST(InputFiles, ADuplicateKeyIsRefusedNamingIt) {
  // A second "coverage" object used to win silently (A = 99 999).
  const std::string text = R"({"coverage": {"area_m2": 1}, "coverage": {"area_m2": 99999}})";
  EXPECT_NE(refusal([&] { parseJsonStrict(text, "m.json"); }).find("key 'coverage' appears twice"), std::string::npos);
  // The same key in two different objects is fine.
  EXPECT_NO_THROW(parseJsonStrict(R"({"a": {"x": 1}, "b": {"x": 2}})", "m.json"));
}

TEST(InputFiles, BadJsonAndHugeNumbersNameTheFile) {
  EXPECT_EQ(refusal([&] { parseJsonStrict("1e400", "n.json"); }), "n.json: a number too large for a double");
  EXPECT_EQ(refusal([&] { parseJsonStrict("{\"a\": ", "t.json"); }).rfind("t.json: not valid JSON (parse error", 0),
            0u);
}

}  // namespace
}  // namespace msb
