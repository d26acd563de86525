#include "tools/msbench/output_files.h"

#include <unistd.h>

#include <fstream>
#include <stdexcept>

namespace msb {

namespace fs = std::filesystem;

void writeFileAtomic(const fs::path& path, const std::string& bytes) {
  const fs::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(tmp.string() + ": cannot write");
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error(tmp.string() + ": write failed");
  }
  fs::rename(tmp, path);
}

StagedOutputDir::StagedOutputDir(fs::path final_dir, bool overwrite)
    : final_(std::move(final_dir)), overwrite_(overwrite) {
  if (fs::exists(final_) && !fs::is_empty(final_) && !overwrite_)
    throw std::runtime_error(final_.string() +
                             ": output directory exists and is not empty (use --overwrite)");
  staging_ = final_.string() + ".partial";
  fs::remove_all(staging_);
  fs::create_directories(staging_);
}

StagedOutputDir::~StagedOutputDir() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

void StagedOutputDir::commit() {
  if (fs::exists(final_)) fs::remove_all(final_);
  if (final_.has_parent_path()) fs::create_directories(final_.parent_path());
  fs::rename(staging_, final_);
  committed_ = true;
}

}  // namespace msb
