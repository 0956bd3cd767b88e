// Checks run after reading, on what the router relies on: a technology with
// routing layers of positive width and pitch and known units, a design with a
// die area. A problem throws InputError naming the file and line of the
// statement at fault; odd but routable things are added to the warnings.
#pragma once

#include <string>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"

namespace xroute {

// After all LEF files: `lefPaths` names the files for problems of the whole.
void validateTech(const Tech& tech, const std::vector<std::string>& lefPaths);
// After the DEF (before the guides): `defPath` names the DEF.
void validateDesign(const Tech& tech, Design& design, const std::string& defPath);

}  // namespace xroute
