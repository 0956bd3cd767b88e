#include "io/gzip_text.hpp"

#include <zlib.h>

#include <algorithm>
#include <climits>

#include "io/input_error.hpp"

namespace xroute {

namespace {

// Far above any real design file (ISPD 2019's largest DEF is under 1 GiB): a small file that
// claims more is a decompression bomb, not a design.
constexpr size_t kMaxInflated = size_t{16} << 30;

[[noreturn]] void corrupt(const std::string& path, const z_stream& zs, const char* what) {
  std::string msg = std::string("invalid gzip stream: ") + what;
  if (zs.msg != nullptr) msg += std::string(" (") + zs.msg + ")";
  throw InputError(path, 0, msg);
}

// RAII for one inflate stream.
struct Inflater {
  z_stream zs{};
  explicit Inflater(const std::string& path) {
    if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) throw InputError(path, 0, "cannot start gzip decompression");
  }
  ~Inflater() { inflateEnd(&zs); }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;
};

}  // namespace

bool isGzip(std::string_view data) {
  return data.size() >= 2 && static_cast<unsigned char>(data[0]) == 0x1f &&
         static_cast<unsigned char>(data[1]) == 0x8b;
}

std::string gunzip(const std::string& path, const std::string& data) {
  Inflater in(path);
  z_stream& zs = in.zs;
  std::string out;
  out.resize(std::max<size_t>(data.size() * 4, 1 << 16));
  size_t produced = 0;
  size_t consumed = 0;
  while (true) {
    const size_t inChunk = std::min<size_t>(data.size() - consumed, UINT_MAX);
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data() + consumed));
    zs.avail_in = static_cast<uInt>(inChunk);
    if (produced == out.size()) {
      if (out.size() >= kMaxInflated) throw InputError(path, 0, "gzip stream decompresses to more than 16 GiB");
      out.resize(std::min(out.size() * 2, kMaxInflated));
    }
    const size_t outChunk = std::min<size_t>(out.size() - produced, UINT_MAX);
    zs.next_out = reinterpret_cast<Bytef*>(out.data() + produced);
    zs.avail_out = static_cast<uInt>(outChunk);
    const int rc = inflate(&zs, Z_NO_FLUSH);
    consumed += inChunk - zs.avail_in;
    produced += outChunk - zs.avail_out;
    if (rc == Z_STREAM_END) {
      // Another member may follow (concatenated .gz files); trailing zero padding is allowed.
      const bool more = consumed < data.size() && isGzip(std::string_view(data).substr(consumed));
      if (!more) break;
      if (inflateReset(&zs) != Z_OK) corrupt(path, zs, "bad member");
      continue;
    }
    if (rc == Z_BUF_ERROR && consumed == data.size()) corrupt(path, zs, "file cut short");
    if (rc != Z_OK && rc != Z_BUF_ERROR) corrupt(path, zs, rc == Z_DATA_ERROR ? "corrupt data" : "bad header");
  }
  out.resize(produced);
  return out;
}

}  // namespace xroute
