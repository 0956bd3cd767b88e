// PLACEHOLDER: the LEF reader is being written.
#include "io/readers.hpp"
#include "io/lexer.hpp"

namespace xroute {
void readLef(const std::string& path, Tech& tech) { throw InputError(path, 0, "LEF reader not built yet"); }
void readLefText(const std::string& name, std::string, Tech&) { throw InputError(name, 0, "LEF reader not built yet"); }
}  // namespace xroute
