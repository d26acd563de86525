#include "tools/results/input_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <set>
#include <vector>

namespace msb {

namespace {

// Closes a file descriptor on scope exit.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// What a non-regular file is, in words.
std::string fileTypeName(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISCHR(m) || S_ISBLK(m)) return "a device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string readInputFile(const std::filesystem::path& path, const InputLimits& limits) {
  const std::string name = path.string();
  // O_NONBLOCK: opening a FIFO for reading returns at once; the type is checked on the open file.
  const Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (f.fd < 0)
    throw InputFileError(name + ": " + (errno == ENOENT ? std::string("file not found") : std::strerror(errno)));
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) throw InputFileError(name + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw InputFileError(name + ": is " + fileTypeName(st.st_mode) + ", not a regular file");
  if (size_t(st.st_size) > limits.max_bytes)
    throw InputFileError(name + ": " + std::to_string(st.st_size) + " bytes, more than the limit of " +
                         std::to_string(limits.max_bytes));
  std::string bytes;
  bytes.reserve(size_t(st.st_size));
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(f.fd, buf, sizeof(buf));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputFileError(name + ": read failed: " + std::strerror(errno));
    if (n == 0) break;
    bytes.append(buf, size_t(n));
    if (bytes.size() > limits.max_bytes)  // grew while read
      throw InputFileError(name + ": more than the limit of " + std::to_string(limits.max_bytes) + " bytes");
  }
  return bytes;
}

nlohmann::json parseJsonStrict(const std::string& text, const std::string& where, const InputLimits& limits) {
  // One set of keys per open object; the depth is checked as each array or object opens, so a
  // deeply nested document is refused before it is built.
  std::vector<std::set<std::string>> keys;
  const nlohmann::json::parser_callback_t check = [&](int depth, nlohmann::json::parse_event_t event,
                                                      nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    if ((event == E::object_start || event == E::array_start) && depth >= limits.max_depth)
      throw InputFileError(where + ": JSON nested more than " + std::to_string(limits.max_depth) + " levels deep");
    if (event == E::object_start) keys.emplace_back();
    if (event == E::object_end && !keys.empty()) keys.pop_back();
    if (event == E::key && !keys.empty() && !keys.back().insert(parsed.get<std::string>()).second)
      throw InputFileError(where + ": key '" + parsed.get<std::string>() + "' appears twice in one object");
    return true;
  };
  try {
    return nlohmann::json::parse(text, check);
  } catch (const nlohmann::json::parse_error& e) {
    // The library's message carries its own prefix; keep the position and the reason.
    std::string what = e.what();
    const auto colon = what.find("parse error");
    throw InputFileError(where + ": not valid JSON (" + (colon == std::string::npos ? what : what.substr(colon)) + ")");
  } catch (const nlohmann::json::out_of_range&) {
    throw InputFileError(where + ": a number too large for a double");
  } catch (const nlohmann::json::exception&) {
    throw InputFileError(where + ": not valid JSON");
  }
}

nlohmann::json readJsonFile(const std::filesystem::path& path, const InputLimits& limits) {
  return parseJsonStrict(readInputFile(path, limits), path.string(), limits);
}

}  // namespace msb
