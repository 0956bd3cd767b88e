#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>

#include "io/input_error.hpp"

namespace xroute {

namespace {

// Creates a fresh temporary file beside `path`, exclusively (O_CREAT|O_EXCL: an
// existing file or a planted symlink of that name is never opened, let alone
// followed). Its name, ".<name>.<pid>.<hex>.tmp" in the folder of `path`, has the
// form xroute.outputs.clean_stale_temporaries removes after a killed run.
int createTemporary(const std::string& path, std::string& tmp) {
  static std::atomic<unsigned> counter{0};
  const size_t slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  for (int attempt = 0; attempt < 100; ++attempt) {
    const auto tick = static_cast<unsigned long long>(std::chrono::steady_clock::now().time_since_epoch().count());
    char hex[16];
    std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>((tick ^ (tick >> 32)) + 7919u * counter++));
    tmp = dir + "." + base + "." + std::to_string(static_cast<long>(getpid())) + "." + hex + ".tmp";
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  errno = EEXIST;
  return -1;
}

}  // namespace

void writeFileAtomically(const std::string& path, std::string_view text, std::string_view what) {
  auto fail = [&](int err) {
    return InputError(path, 0, "cannot write " + std::string(what) + ": " + std::string(std::strerror(err)));
  };
  std::string tmp;
  const int fd = createTemporary(path, tmp);
  if (fd < 0) throw fail(errno);
  size_t done = 0;
  int err = 0;
  while (done < text.size()) {
    const ssize_t w = ::write(fd, text.data() + done, text.size() - done);
    if (w < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    done += static_cast<size_t>(w);
  }
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) {
    ::unlink(tmp.c_str());
    throw fail(err);
  }
  // rename() replaces a symlink named `path` itself; it never writes through it.
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    err = errno;
    ::unlink(tmp.c_str());
    throw fail(err);
  }
}

}  // namespace xroute
