// Routing metrics of a design: wirelength and via counts of the regular nets,
// as ISPD and TritonRoute report them.
#pragma once

#include <cstdint>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"

namespace xroute {

struct RoutingMetrics {
  int64_t wirelength = 0;               // DBU: sum of |to - from| over RouteWires (extensions not counted)
  double wirelengthMicrons = 0;         // microns: wirelength / DEF dbuPerMicron (LEF's if the DEF has none)
  std::vector<int64_t> layerWirelength; // DBU, by LayerId value (all layers; 0 on non-routing layers)
  int64_t vias = 0;                     // via instances (a multi-cut via counts once)
  std::vector<int64_t> cutLayerVias;    // via instances by the via's cut LayerId value (all layers)
  int32_t netsRouted = 0;               // regular nets with non-empty routing
};

// Regular nets only (NETS); special nets are not counted.
RoutingMetrics computeMetrics(const Tech& tech, const Design& design);

}  // namespace xroute
