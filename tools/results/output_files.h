// Result files are never half-written and finished results are never overwritten: a run's
// outputs go to a staging directory that is renamed into place when everything is written.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace msb {

/// The whole file as bytes (empty if it cannot be read).
std::string readFileText(const std::filesystem::path& path);

/// Writes `bytes` to `path` through a temporary file in the same directory and a rename.
void writeFileAtomic(const std::filesystem::path& path, const std::string& bytes);

/// Checks before a run that `file` can be written as an output file named by `flag`: not a
/// directory, its directory exists and is writable, and an existing file only with `overwrite`
/// and only when it starts with `magic` (what msbench writes as that kind of file: "MSBLOG" for a
/// perception log, the PNG signature for a picture). Throws UsageError (exit 2).
void checkOutputFile(const std::filesystem::path& file, bool overwrite, const std::string& flag,
                     const std::string& magic = "");

/// The same with a predicate on the existing file's bytes deciding that msbench wrote it as this
/// output (e.g. isMsbenchPng).
void checkOutputFile(const std::filesystem::path& file, bool overwrite, const std::string& flag,
                     const std::function<bool(const std::string&)>& ours);

/// A path a command reads or writes, with the flag (or argument) the user gave it by.
struct NamedPath {
  std::string flag;  ///< e.g. "--out", "--record", "SCENARIO"
  std::filesystem::path path;
};

/// Refuses (UsageError, exit 2, before anything is written) an output equal to, inside, or
/// containing an input or another output. `inputs` are files or directories the command reads;
/// `outputs` what it writes (a directory output includes its "<dir>.partial" staging directory).
void checkNoOverlap(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

/// The kinds of output directory msbench writes; --overwrite replaces only one of the same kind.
enum class OutputKind { kRun, kReport, kFly, kVioEval, kMapReplay, kWorldShow, kWorldImport, kExport, kWorldExport };

/// True if `dir` is a directory msbench wrote (it holds the marker file `.msbench-output`); with
/// `kind`, only one of that kind (a marker written before kinds existed counts for the kind whose
/// characteristic file the directory holds).
bool isMsbenchOutput(const std::filesystem::path& dir);
bool isMsbenchOutput(const std::filesystem::path& dir, OutputKind kind);

/// Writes the marker file of `kind` into `dir` (an output directory msbench made itself).
void writeOutputMarker(const std::filesystem::path& dir, OutputKind kind);

/// Copies the regular file `from` (an input: opened without blocking, a FIFO, device or
/// directory refused as InputFileError naming it) to the new file `to`, in chunks, calling
/// `poll` between them (an interrupt check). A failed write names `to` and the reason
/// (std::runtime_error, `to` removed).
void copyInputFile(const std::filesystem::path& from, const std::filesystem::path& to,
                   const std::function<void()>& poll);

/// Puts the directory `staged` in place of `target` without a moment in which neither holds a
/// whole copy: an existing `target` is renamed aside (`<target>.replaced-<pid>`), `staged` renamed
/// in, then the old one removed (what cannot be removed is left there, named on stderr). If the
/// second rename fails, the old `target` is put back. Throws std::runtime_error naming the step.
void replaceDirectory(const std::filesystem::path& staged, const std::filesystem::path& target);

/// The path msbench writes an output `path` at: absolute, with symlinks and `..` in its parent
/// resolved as the filesystem resolves them (not lexically: `link/../d` is d beside the link's
/// target), the last component as named. The overlap check and every writer use this form.
std::filesystem::path outputPathOf(const std::filesystem::path& path);

/// One writer per output: an exclusive lock (flock) on "<output>.lock", held from construction
/// to destruction. The lock file holds the holder's pid and is removed on release. The kernel
/// releases the lock when its process ends in any way (exit, signal, crash), so a lock file a
/// dead process left behind is taken over by the next writer without a check of its pid.
class OutputLock {
 public:
  /// Takes the lock of `output` (the file or directory msbench will write); `flag` names it in
  /// messages. Another process holding it: UsageError (exit 2) naming the output and its pid.
  OutputLock(const std::filesystem::path& output, const std::string& flag);
  /// Removes the lock file, then releases the lock.
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

/// A staging directory "<final>.partial" that becomes "<final>" on commit(). Safe by
/// construction: the path is outputPathOf's (a trailing slash is the same directory); the current
/// directory, its parents, `/` and anything that is not a directory are refused; a non-empty
/// target needs `overwrite` and is replaced only if msbench wrote it (marker file); a
/// "<final>.partial" msbench did not write is never touched. Every output directory gets the
/// marker file.
class StagedOutputDir {
 public:
  /// Checks the target and creates the staging directory; refusals throw UsageError (exit 2). An
  /// existing non-empty target is replaced only with `overwrite` and only if it is an msbench
  /// output of the same kind.
  StagedOutputDir(std::filesystem::path final_dir, bool overwrite, OutputKind kind = OutputKind::kRun);
  /// Removes the staging directory if commit() was never called.
  ~StagedOutputDir();
  /// Where to write files now.
  const std::filesystem::path& staging() const { return staging_; }
  /// The final location.
  const std::filesystem::path& finalDir() const { return final_; }
  /// Moves the staged files into the final directory. A target that gained entries msbench did
  /// not write since construction (a user's file) is never deleted: the staging directory is
  /// kept and the error (std::runtime_error, exit 1) says where the results are.
  void commit();

 private:
  std::filesystem::path final_, staging_;
  bool overwrite_, committed_ = false, kept_ = false;
  OutputKind kind_;
  std::optional<OutputLock> lock_;          // one writer: "<final>.lock" while this object lives
  std::vector<std::string> final_entries_;  // what an existing target held at construction
};

}  // namespace msb
