#include "verify/metrics.hpp"

#include <cstdlib>

namespace xroute {

RoutingMetrics computeMetrics(const Tech& tech, const Design& design) {
  RoutingMetrics m;
  m.layerWirelength.assign(tech.layers.size(), 0);
  m.cutLayerVias.assign(tech.layers.size(), 0);
  for (const Net& net : design.nets) {
    const NetRouting& r = net.routing;
    if (!r.empty()) ++m.netsRouted;
    for (const RouteWire& w : r.wires) {
      const int64_t length = w.length();
      m.wirelength += length;
      if (w.layer.valid() && size_t(*w.layer) < m.layerWirelength.size()) m.layerWirelength[*w.layer] += length;
    }
    for (const RouteVia& v : r.vias) {
      ++m.vias;
      if (!v.via.valid()) continue;
      const LayerId cut = design.via(tech, v.via).cut;
      if (cut.valid() && size_t(*cut) < m.cutLayerVias.size()) ++m.cutLayerVias[*cut];
    }
  }
  const int dbu = design.dbuPerMicron > 0 ? design.dbuPerMicron : tech.dbuPerMicron;
  m.wirelengthMicrons = dbu > 0 ? double(m.wirelength) / dbu : 0.0;
  return m;
}

}  // namespace xroute
