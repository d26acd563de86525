// Seeded mutation fuzzing of the readers that take user files (tests/tools/config/fuzz_test.cc,
// tests/tools/results/perception_log_test.cc): each valid input is mutated a bounded number of
// times (byte flips, deletions, insertions of hostile tokens, truncation); every result must
// either load or be refused with one of the documented error types — never crash, hang or throw
// anything else. Under the sanitizer build (.ci/run) memory and undefined-behaviour errors abort.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/common/config_check.h"
#include "core/common/rng.h"

namespace msb {
namespace fuzz_test {

namespace fs = std::filesystem;

inline std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// One mutation of `text`, chosen by the stream.
inline std::string mutate(std::string text, RngStream& rng) {
  static const char* const kTokens[] = {"nan", "-inf",     "1e308", "-1", "99999999999999999999",
                                        "[",   "]",        "{",     "}",  ":",
                                        "- ",  "\n",       "''",    "~",  "&a",
                                        "*a",  "!!binary", "\t",    "\0", ",,"};
  const int kinds = 5;
  const int rounds = 1 + int(rng.uniformInt(3));
  for (int r = 0; r < rounds && !text.empty(); ++r) {
    const size_t at = size_t(rng.uniformInt(text.size()));
    switch (int(rng.uniformInt(kinds))) {
      case 0:
        text[at] = char(rng.uniformInt(256));
        break;  // flip a byte
      case 1:
        text.erase(at, 1 + size_t(rng.uniformInt(8)));
        break;  // delete a run
      case 2:
        text.insert(at, kTokens[rng.uniformInt(sizeof(kTokens) / sizeof(*kTokens))]);
        break;  // hostile token
      case 3:
        text.resize(at);
        break;  // truncate
      default:
        text.insert(at, text.substr(at, size_t(rng.uniformInt(32))));
        break;  // repeat a run
    }
  }
  return text;
}

// Runs `load` on `n` mutations of `seed_text` written to `file`; only documented errors may escape.
template <class Load>
void fuzz(const std::string& seed_text, const fs::path& file, int n, const char* stream, Load load) {
  RngStream rng(11, stream);
  int loaded = 0, refused = 0;
  for (int i = 0; i < n; ++i) {
    const std::string input = mutate(seed_text, rng);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << input;
    try {
      load(file.string());
      ++loaded;
    } catch (const FileConfigError&) {
      ++refused;
    } catch (const ConfigError&) {
      ++refused;
    } catch (const UsageError&) {
      ++refused;
    } catch (const std::exception& e) {  // anything else (yaml-cpp's own, a bare runtime_error) is a defect
      ADD_FAILURE() << stream << " input " << i << ": unexpected " << typeid(e).name() << ": " << e.what()
                    << "\n--- input ---\n"
                    << input;
    }
  }
  EXPECT_EQ(loaded + refused, n);
  EXPECT_GT(loaded, 0) << stream << ": no mutation loaded (is the seed input valid?)";
  EXPECT_GT(refused, n / 10) << stream << ": the mutations should break most inputs";
}

inline fs::path dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("msb_fuzz_" + name);
  fs::create_directories(d);
  fs::copy_file(fs::path(MSB_SOURCE_DIR) / "worlds/test/world.xml", d / "world.xml",
                fs::copy_options::overwrite_existing);
  return d;
}

}  // namespace fuzz_test
}  // namespace msb
