// Writing an output file all at once or not at all: the text goes to a
// temporary file beside `path`, which is then renamed over it.
#pragma once

#include <string>
#include <string_view>

namespace xroute {

// Writes `text` to `path` atomically, through a temporary file created exclusively
// (O_CREAT|O_EXCL|O_NOFOLLOW) beside it. On failure nothing is left behind (no
// temporary file, `path` untouched) and InputError(path, 0, "cannot write
// <what>: <reason>") is thrown.
void writeFileAtomically(const std::string& path, std::string_view text, std::string_view what);

}  // namespace xroute
