// Entry points of the file readers and the DEF writer. Each throws
// InputError (file and line) on bad input and leaves no partial output file.
#pragma once

#include <string>
#include <vector>

#include "db/database.hpp"
#include "db/design.hpp"
#include "db/tech.hpp"
#include "io/input_error.hpp"

namespace xroute {

// LEF: may be called several times on one Tech (technology LEF, then cell LEFs).
void readLef(const std::string& path, Tech& tech);
void readLefText(const std::string& name, std::string text, Tech& tech);

// DEF: needs the Tech for layer, via and macro names.
void readDef(const std::string& path, const Tech& tech, Design& design);
void readDefText(const std::string& name, std::string text, const Tech& tech, Design& design);

// ISPD guide file: "net\n(\nxlo ylo xhi yhi layer\n...\n)\n" per net.
// Fills Design::guideStart/guideRects/guideLayers.
void readGuides(const std::string& path, const Tech& tech, Design& design);
void readGuidesText(const std::string& name, std::string text, const Tech& tech, Design& design);

// A Database: LEF files in order (then the technology checked), the DEF
// (then the design checked), then the guide file if given.
Database loadDatabase(const std::vector<std::string>& lefPaths, const std::string& defPath,
                      const std::string& guidePath);

// DEF out: the whole design, nets with their routing as ROUTED/NEW paths.
std::string writeDefText(const Tech& tech, const Design& design);
// Writes to a temporary file beside `path`, then renames it into place.
void writeDef(const std::string& path, const Tech& tech, const Design& design);

}  // namespace xroute
