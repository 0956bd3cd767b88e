// The DRC report file: one line per marker, after a header line with the
// counts by type.
//
//   # markers 3 Short 2 MetalSpacing 0 EndOfLine 0 CutShort 0 CutSpacing 0 AdjacentCuts 0 MinArea 1 CornerSpacing 0
//   Short M1 1450 1450 1600 1550 n1 -
//   <type> <layer> <xlo> <ylo> <xhi> <yhi> <net1 name or -> <net2 name or ->
//
// The header names every type, in MarkerType order, zeros included; markers
// are written in the order given (checkShapes sorts them). Coordinates in DBU.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "drc/drc.hpp"

namespace xroute {

// Markers by type, indexed by int(MarkerType).
std::array<int64_t, kMarkerTypes> countMarkers(const std::vector<Marker>& markers);

// netNames: by net id, as collectDesignShapes(..., &netNames) gives them; a
// negative id (obstruction, or no second net) is written "-", an id without
// a name as its number.
std::string drcReportText(const Tech& tech, const std::vector<Marker>& markers,
                          const std::vector<std::string>& netNames);

// Writes drcReportText atomically (temporary file, then rename); throws
// InputError(path, 0, ...) when the file cannot be written, leaving nothing.
void writeDrcReport(const std::string& path, const Tech& tech, const std::vector<Marker>& markers,
                    const std::vector<std::string>& netNames);

}  // namespace xroute
