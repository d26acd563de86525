// The one way msbench reads a file it did not just write itself, as bytes: regular files only —
// a FIFO, device or directory is refused before anything is read, so no reader blocks —, and a
// size limit checked before the read. Errors name the file and the reason (docs/robustness.md).
// JSON on top of it: tools/results/input_files.h.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "core/common/config_check.h"

namespace msb {

/// An input file that cannot be read as asked: missing, not a regular file, too large, not
/// valid JSON, nested too deep, a key twice. The message names the file and the reason.
/// Bad input: every command exits 2.
class InputFileError : public FileConfigError {
 public:
  using FileConfigError::FileConfigError;
};

/// Limits of one read.
struct InputLimits {
  size_t max_bytes = size_t(256) << 20;  ///< larger files are refused (256 MiB)
  int max_depth = 64;                    ///< JSON: arrays and objects nested deeper are refused
};

/// The whole file `path`: a regular file (symlinks followed) of at most `limits.max_bytes`.
/// Opens without blocking and checks the opened file, so a FIFO or device never stalls the
/// reader. Throws InputFileError.
std::string readInputFile(const std::filesystem::path& path, const InputLimits& limits = {});

}  // namespace msb
