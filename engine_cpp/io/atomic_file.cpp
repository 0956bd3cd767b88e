#include "io/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "io/input_error.hpp"

namespace xroute {

void writeFileAtomically(const std::string& path, std::string_view text, std::string_view what) {
  auto fail = [&](int err) {
    return InputError(path, 0, "cannot write " + std::string(what) + ": " + std::string(std::strerror(err)));
  };
  const std::string tmp = path + ".tmp." + std::to_string(static_cast<long>(getpid()));
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw fail(errno);
  const bool wrote = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const int writeErrno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!wrote || !closed) {
    const int err = wrote ? errno : writeErrno;
    std::remove(tmp.c_str());
    throw fail(err);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    std::remove(tmp.c_str());
    throw fail(err);
  }
}

}  // namespace xroute
