#include "core/common/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

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

}  // namespace msb
