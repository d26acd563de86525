#include "tools/results/output_files.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/common/config_check.h"
#include "tools/results/input_files.h"

namespace msb {

namespace fs = std::filesystem;

std::string readFileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeFileAtomic(const fs::path& path, const std::string& bytes) {
  // Every step is checked — open, each write, close (where some file systems report a full
  // disk) — before the rename; on failure the temporary goes and `path` is as it was.
  const fs::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
  auto fail = [&](const char* step, int err) {
    ::unlink(tmp.c_str());
    throw std::runtime_error(path.string() + ": cannot " + step + " (" + tmp.filename().string() +
                             "): " + std::strerror(err) + "; the file was not changed");
  };
  ::unlink(tmp.c_str());  // a temporary of an earlier process with this pid
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) fail("create the file", errno);
  for (size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : EIO;
      ::close(fd);
      fail("write it", err);
    }
    done += size_t(n);
  }
  if (::close(fd) != 0) fail("close it", errno);
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) fail("rename it into place", ec.value());
}

namespace {

constexpr char kMarker[] = ".msbench-output";

// True if `dir` is `p` or one of its ancestors (both absolute and normalised).
bool isSameOrAncestor(const fs::path& dir, const fs::path& p) {
  auto q = p.begin();
  for (auto d = dir.begin(); d != dir.end(); ++d, ++q) {
    if (d->empty()) continue;  // a trailing separator
    if (q == p.end() || *d != *q) return false;
  }
  return true;
}

bool existsNoFollow(const fs::path& p) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(p, ec));
}

}  // namespace

void checkOutputFile(const fs::path& file, bool overwrite, const std::string& flag, const std::string& magic) {
  checkOutputFile(file, overwrite, flag, [&](const std::string& bytes) {
    return magic.empty() || bytes.compare(0, magic.size(), magic) == 0;
  });
}

void checkOutputFile(const fs::path& file, bool overwrite, const std::string& flag,
                     const std::function<bool(const std::string&)>& ours) {
  const std::string name = "--" + flag + " " + file.string();
  if (file.empty() || !fs::absolute(file).has_filename()) throw UsageError(name + ": expected a file name");
  if (!isValidUtf8(file.string())) throw UsageError(name + ": the path is not valid UTF-8");
  if (existsNoFollow(file)) {
    if (!fs::is_regular_file(fs::symlink_status(file))) throw UsageError(name + ": exists and is not a regular file");
    if (!overwrite) throw UsageError(name + ": exists (use --overwrite to replace it)");
    if (!ours(readInputFile(file)))
      throw UsageError(name + ": exists and is not a file msbench wrote as this output; refusing to replace it");
  }
  const fs::path dir = fs::absolute(file).parent_path();
  if (!fs::is_directory(dir)) throw UsageError(name + ": directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw UsageError(name + ": directory " + dir.string() + " is not writable");
}

namespace {

// The marker's text of a kind, and the file that shows a directory of that kind written before
// markers named their kind.
const char* kindName(OutputKind k) {
  switch (k) {
    case OutputKind::kRun:
      return "run";
    case OutputKind::kReport:
      return "report";
    case OutputKind::kFly:
      return "fly";
    case OutputKind::kVioEval:
      return "vio-eval";
    case OutputKind::kMapReplay:
      return "map-replay";
    case OutputKind::kWorldShow:
      return "world-show";
    case OutputKind::kWorldImport:
      return "world-import";
    case OutputKind::kExport:
      return "export";
    case OutputKind::kWorldExport:
      return "world-export";
  }
  return "?";
}

const char* characteristicFile(OutputKind k) {
  switch (k) {
    case OutputKind::kRun:
      return "coverage.csv";
    case OutputKind::kReport:
      return "report.md";
    case OutputKind::kFly:
      return "imu.csv";
    case OutputKind::kVioEval:
      return "frames.csv";
    case OutputKind::kMapReplay:
      return "map_stats.csv";
    case OutputKind::kWorldShow:
      return "views.png";
    case OutputKind::kWorldImport:
      return "imported.json";
    case OutputKind::kExport:
      return "export.json";
    case OutputKind::kWorldExport:
      return "world_export.json";
  }
  return "";
}

std::string markerText(OutputKind k) {
  return std::string("This directory was written by msbench (") + kindName(k) +
         "); --overwrite may replace it with the same kind of output.\n";
}

// The marker file's text, empty if there is none or it is not a small regular file.
std::string markerTextOf(const fs::path& dir) {
  try {
    return readInputFile(dir / kMarker, InputLimits{4096, 1});
  } catch (const InputFileError&) {
    return "";
  }
}

// Weakly canonical absolute form (symlinks resolved where the path exists).
fs::path canonicalOf(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(fs::absolute(p), ec);
  if (ec) c = fs::absolute(p).lexically_normal();
  if (!c.has_filename() && c.has_parent_path()) c = c.parent_path();
  return c;
}

}  // namespace

fs::path outputPathOf(const fs::path& path) {
  // The parent as the filesystem resolves it (symlinks, then `..` from where they lead), the
  // last component kept as named (a symlink there is refused by the writers, never followed).
  fs::path p = fs::absolute(path);
  while (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  const fs::path name = p.filename();
  std::error_code ec;
  if (name == "." || name == "..") {
    fs::path c = fs::weakly_canonical(p, ec);
    if (ec) c = p.lexically_normal();
    // "d/." of a directory that does not exist yet normalises to "d/": the directory is d.
    while (!c.has_filename() && c.has_parent_path() && c != c.root_path()) c = c.parent_path();
    return c;
  }
  fs::path parent = fs::weakly_canonical(p.parent_path(), ec);
  if (ec) parent = p.parent_path().lexically_normal();
  return parent / name;
}

void checkNoOverlap(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  auto overlap = [](const fs::path& a, const fs::path& b) { return isSameOrAncestor(a, b) || isSameOrAncestor(b, a); };
  for (size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].path.empty()) continue;
    // The path as written to and, if it is a symlink, where it leads.
    const fs::path o = outputPathOf(outputs[i].path), target = canonicalOf(outputs[i].path);
    const std::string name = outputs[i].flag + " " + outputs[i].path.string();
    for (const NamedPath& in : inputs)
      if (!in.path.empty() && (overlap(o, canonicalOf(in.path)) || overlap(target, canonicalOf(in.path))))
        throw UsageError(name + ": overlaps the input " + in.flag + " " + in.path.string() +
                         " (an output may not be, hold or lie inside an input); refusing it, nothing was written");
    for (size_t j = i + 1; j < outputs.size(); ++j)
      if (!outputs[j].path.empty() && overlap(o, canonicalOf(outputs[j].path)))
        throw UsageError(name + ": overlaps the output " + outputs[j].flag + " " + outputs[j].path.string() +
                         "; refusing it, nothing was written");
  }
}

bool isMsbenchOutput(const fs::path& dir, OutputKind kind) {
  if (!fs::is_directory(dir)) return false;
  const fs::path marker = dir / kMarker;
  if (fs::exists(marker)) {
    const std::string text = markerTextOf(dir);
    if (text == markerText(kind)) return true;
    // A marker from before kinds: the kind's characteristic file decides (a run that ended in an
    // error left only its metrics.json).
    if (text.find("(") == std::string::npos)
      return fs::exists(dir / characteristicFile(kind)) ||
             (kind == OutputKind::kRun && fs::exists(dir / "metrics.json"));
    return false;
  }
  return kind == OutputKind::kRun && isMsbenchOutput(dir);
}

bool isMsbenchOutput(const fs::path& dir) {
  // The marker only: a directory holding a copy of a metrics.json is not msbench's output.
  return fs::is_directory(dir) && markerTextOf(dir).find("msbench") != std::string::npos;
}

namespace {

// What an msbench lock file holds: this line, then the holder's pid.
constexpr char kLockTag[] = "msbench output lock, pid ";

}  // namespace

OutputLock::OutputLock(const fs::path& output, const std::string& flag) : path_(output.string() + ".lock") {
  // Open (a new file, or one an msbench lock left: another holder's or a dead one's), lock, and
  // check the path still names the locked file (a releasing holder removes it between our open
  // and our lock): otherwise try again.
  const std::string tag = kLockTag;
  for (int attempt = 0; attempt < 100; ++attempt) {
    bool created = true;
    fd_ = open(path_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0 && errno == EEXIST) created = false, fd_ = open(path_.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
    if (fd_ < 0 && errno == ENOENT) continue;  // removed between the two opens: again
    if (fd_ < 0)
      throw UsageError(flag + " " + output.string() + ": cannot create its lock file " + path_.string() + ": " +
                       std::strerror(errno));
    // A file of that name msbench did not write (a lock file starts with kLockTag) is never
    // taken, and so never removed; nor is a link or anything but a regular file.
    char text[64] = {};
    const ssize_t got = pread(fd_, text, sizeof(text) - 1, 0);
    struct stat st {};
    const bool ours = created || (got >= ssize_t(tag.size()) && tag.compare(0, tag.size(), text, tag.size()) == 0 &&
                                  fstat(fd_, &st) == 0 && S_ISREG(st.st_mode));
    if (!ours) {
      close(fd_);
      fd_ = -1;
      throw UsageError(flag + " " + output.string() + ": " + path_.string() +
                       " exists and is not an msbench lock file; remove or rename it first");
    }
    if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const std::string holder = got > ssize_t(tag.size()) ? std::string(text + tag.size()) : "?";
      close(fd_);
      fd_ = -1;
      throw UsageError(flag + " " + output.string() + ": another msbench process (pid " + holder +
                       ") is writing it; wait for it or choose another output (lock: " + path_.string() + ")");
    }
    struct stat held {
    }, named{};
    if (fstat(fd_, &held) == 0 && lstat(path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      // The pid is for a second writer's message only: a failure to note it changes nothing.
      const std::string line = tag + std::to_string(getpid());
      const bool noted = ftruncate(fd_, 0) == 0 && pwrite(fd_, line.data(), line.size(), 0) == ssize_t(line.size());
      (void)noted;
      return;
    }
    close(fd_);
    fd_ = -1;
  }
  throw UsageError(flag + " " + output.string() + ": cannot take its lock " + path_.string());
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  unlink(path_.c_str());  // while still held: a waiting writer then locks a fresh file
  close(fd_);
}

namespace {

// The entries below `dir` (relative paths, sorted); empty if it does not exist.
std::vector<std::string> entriesOf(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir, ec))) return out;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    out.push_back(fs::relative(it->path(), dir).string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

void writeOutputMarker(const fs::path& dir, OutputKind kind) { writeFileAtomic(dir / kMarker, markerText(kind)); }

void copyInputFile(const fs::path& from, const fs::path& to, const std::function<void()>& poll) {
  // The source as readInputFile opens it: without blocking, the opened file's type checked.
  const int in = ::open(from.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (in < 0) throw InputFileError(from.string() + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(in, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(in);
    throw InputFileError(from.string() + ": not a regular file (a FIFO, device or directory is never copied)");
  }
  const int out = ::open(to.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (out < 0) {
    const int err = errno;
    ::close(in);
    throw std::runtime_error(to.string() + ": cannot create the file: " + std::strerror(err));
  }
  // Each chunk read from the source (its errors name it), written whole to the copy (its errors
  // name the copy: a full cache is the cache's failure, not the checkout's).
  auto fail = [&](const fs::path& who, const char* step, int err) {
    ::close(in), ::close(out), ::unlink(to.c_str());
    throw std::runtime_error(who.string() + ": cannot " + step + ": " + std::strerror(err));
  };
  std::vector<char> buf(size_t(1) << 20);
  for (;;) {
    if (poll) poll();
    const ssize_t n = ::read(in, buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(from, "read it", errno);
    if (n == 0) break;
    for (ssize_t done = 0; done < n;) {
      const ssize_t w = ::write(out, buf.data() + done, size_t(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) fail(to, "write it", w < 0 ? errno : EIO);
      done += w;
    }
  }
  ::close(in);
  if (::close(out) != 0) {
    const int err = errno;
    ::unlink(to.c_str());
    throw std::runtime_error(to.string() + ": cannot close it: " + std::strerror(err));
  }
}

void replaceDirectory(const fs::path& staged, const fs::path& target) {
  const fs::path aside = target.string() + ".replaced-" + std::to_string(::getpid());
  std::error_code ec;
  const bool had = existsNoFollow(target);
  if (had) {
    fs::rename(target, aside, ec);
    if (ec) throw std::runtime_error(target.string() + ": cannot move the old copy aside: " + ec.message());
  }
  fs::rename(staged, target, ec);
  if (ec) {
    std::error_code back;
    if (had) fs::rename(aside, target, back);
    throw std::runtime_error(target.string() + ": cannot move the new copy in place: " + ec.message() +
                             (had ? (back ? "; the old copy is at " + aside.string() : "; the old copy is kept") : ""));
  }
  if (had && (fs::remove_all(aside, ec), ec))
    std::fprintf(stderr, "msbench: the replaced copy %s could not be removed whole (%s); remove it by hand\n",
                 aside.c_str(), ec.message().c_str());
}

StagedOutputDir::StagedOutputDir(fs::path final_dir, bool overwrite, OutputKind kind)
    : overwrite_(overwrite), kind_(kind) {
  // The form the overlap check uses (outputPathOf: symlinks and `..` resolved as the filesystem
  // does; a trailing slash names the same directory).
  if (final_dir.empty()) throw UsageError("--out: empty path");
  const fs::path p = outputPathOf(final_dir);
  final_ = p;
  const std::string name = final_dir.string();
  if (!isValidUtf8(name)) throw UsageError("--out " + name + ": the path is not valid UTF-8");
  if (p == p.root_path() || isSameOrAncestor(p, fs::current_path().lexically_normal()))
    throw UsageError(name + ": refusing to use the current directory, one of its parents or / as an output directory");
  // An existing target must be a directory; a non-empty one needs --overwrite and must be an
  // msbench result (marker file), so nothing else is ever deleted.
  if (existsNoFollow(p)) {
    if (!fs::is_directory(fs::symlink_status(p)))
      throw UsageError(name + ": exists and is not a directory; refusing to replace it");
    if (!fs::is_empty(p)) {
      if (!overwrite_)
        throw UsageError(name +
                         ": output directory exists and is not empty (use --overwrite to replace an msbench result)");
      if (!isMsbenchOutput(p))
        throw UsageError(name + ": was not written by msbench (no " + kMarker + " inside); refusing to replace it");
      if (!isMsbenchOutput(p, kind_))
        throw UsageError(name + ": is an msbench output of another kind, not a " + kindName(kind_) +
                         " output; refusing to replace it");
    }
  }
  // One writer: a second msbench process writing here is refused before it touches anything.
  std::error_code made;
  if (p.has_parent_path()) fs::create_directories(p.parent_path(), made);
  lock_.emplace(p, "--out");
  // The staging directory: a stale one of an interrupted msbench run is cleared, anything else kept.
  staging_ = p.string() + ".partial";
  if (existsNoFollow(staging_)) {
    if (!fs::is_directory(fs::symlink_status(staging_)) || !isMsbenchOutput(staging_))
      throw UsageError(staging_.string() + ": exists and was not written by msbench; remove or rename it first");
    fs::remove_all(staging_);
  }
  std::error_code ec;
  fs::create_directories(staging_, ec);
  if (ec) throw UsageError(staging_.string() + ": cannot create the output directory: " + ec.message());
  try {
    writeFileAtomic(staging_ / kMarker, markerText(kind_));
  } catch (...) {
    fs::remove_all(staging_, ec);  // a full disk: no empty staging directory is left behind
    throw;
  }
  final_entries_ = entriesOf(p);
}

StagedOutputDir::~StagedOutputDir() {
  if (!committed_ && !kept_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

void StagedOutputDir::commit() {
  // The target is empty or an msbench result (checked at construction), and holds nothing new.
  std::vector<std::string> added;
  const std::vector<std::string> now = entriesOf(final_);
  std::set_difference(now.begin(), now.end(), final_entries_.begin(), final_entries_.end(), std::back_inserter(added));
  if (!added.empty()) {
    kept_ = true;
    throw std::runtime_error(final_.string() + " gained " + std::to_string(added.size()) +
                             " file(s) msbench did not write while it ran (e.g. " + added.front() +
                             "); it is left as it is, and this run's results stay in " + staging_.string());
  }
  if (existsNoFollow(final_)) fs::remove_all(final_);
  if (final_.has_parent_path()) fs::create_directories(final_.parent_path());
  fs::rename(staging_, final_);
  committed_ = true;
}

}  // namespace msb
