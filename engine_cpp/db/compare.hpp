// Deep comparison of two designs read with the same Tech: what a DEF round
// trip (read -> write -> read) must preserve.
#pragma once

#include <string>
#include <vector>

#include "db/design.hpp"

namespace xroute {

// Human-readable differences, at most `maxDiffs` of them; empty = equal.
std::vector<std::string> compareDesigns(const Design& a, const Design& b, size_t maxDiffs = 20);

}  // namespace xroute
