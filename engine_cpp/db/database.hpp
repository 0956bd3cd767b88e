// One loaded design: its technology, its design, and where they came from.
// This is the object Python holds.
#pragma once

#include <string>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"

namespace xroute {

struct Database {
  Tech tech;
  Design design;
  std::vector<std::string> lefPaths;  // the DEF's path is the design's (Design::path)
  std::string guidePath;  // empty when no guide was read
};

}  // namespace xroute
