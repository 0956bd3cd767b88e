// PLACEHOLDER: design comparison is being written.
#include "db/compare.hpp"

namespace xroute {
std::vector<std::string> compareDesigns(const Design&, const Design&, size_t) { return {"not implemented"}; }
}  // namespace xroute
