// Result files are never half-written and finished results are never overwritten: a run's
// outputs go to a staging directory that is renamed into place when everything is written.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace msb {

/// Writes `bytes` to `path` through a temporary file in the same directory and a rename.
void writeFileAtomic(const std::filesystem::path& path, const std::string& bytes);

/// A staging directory "<final>.partial" that becomes "<final>" on commit().
class StagedOutputDir {
 public:
  /// Fails (std::runtime_error) if `final_dir` exists and is not empty, unless `overwrite`.
  StagedOutputDir(std::filesystem::path final_dir, bool overwrite);
  /// Removes the staging directory if commit() was never called.
  ~StagedOutputDir();
  /// Where to write files now.
  const std::filesystem::path& staging() const { return staging_; }
  /// The final location.
  const std::filesystem::path& finalDir() const { return final_; }
  /// Moves the staged files into the final directory.
  void commit();

 private:
  std::filesystem::path final_, staging_;
  bool overwrite_, committed_ = false;
};

}  // namespace msb
