// gzip-compressed input (.def.gz, .lef.gz, .guide.gz): recognised by its magic bytes, not its
// name, and decompressed whole with zlib before the lexer sees it.
#pragma once

#include <string>
#include <string_view>

namespace xroute {

// True when `data` starts with the gzip magic bytes 1f 8b.
bool isGzip(std::string_view data);

// The decompressed bytes of a gzip file (several concatenated members are read one after the
// other, as gunzip does). Throws InputError naming `path` when the stream is corrupt or cut short.
std::string gunzip(const std::string& path, const std::string& data);

}  // namespace xroute
