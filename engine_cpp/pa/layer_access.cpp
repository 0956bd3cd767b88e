// Per routing layer: the vias up, the tracks that count as on-track for an
// access point, and the size of a planar exit stub.
#include <algorithm>

#include "pa/pa_internal.hpp"

namespace xroute::pa {

namespace {

const std::vector<Dbu>& xLines(const LayerTracks& t) { return t.horizontal ? t.cross : t.pref; }
const std::vector<Dbu>& yLines(const LayerTracks& t) { return t.horizontal ? t.pref : t.cross; }

int32_t routingIndexOf(const Tech& tech, LayerId id) { return id.valid() ? tech.layer(id).routingIndex : -1; }

}  // namespace

std::vector<LayerAccess> buildLayerAccess(const Tech& tech, const TrackSet& tracks) {
  const int32_t layers = int32_t(tracks.layers.size());
  std::vector<LayerAccess> out(layers);
  for (int32_t z = 0; z < layers; ++z) {
    LayerAccess& la = out[z];
    const LayerTracks& own = tracks.layers[z];
    const Layer& rules = tech.layer(own.layer);
    la.layer = own.layer;

    // Vias up: bottom on z, top on z+1; DEFAULT ones first, then LEF order.
    for (int32_t i = 0; i < int32_t(tech.vias.size()); ++i) {
      const Via& v = tech.vias[i];
      if (routingIndexOf(tech, v.bottom) == z && routingIndexOf(tech, v.top) == z + 1 && v.cut.valid())
        la.upVias.push_back(ViaId(i));
    }
    std::stable_sort(la.upVias.begin(), la.upVias.end(),
                     [&](ViaId a, ViaId b) { return tech.vias[*a].isDefault && !tech.vias[*b].isDefault; });
    if (la.hasUp()) {
      const Via& v = tech.vias[*la.upVias.front()];
      bool first = true;
      for (const ViaShape& s : v.shapes) {
        if (s.layer != v.cut) continue;
        if (first) la.cutBox = s.rect;
        else la.cutBox.expandToInclude(s.rect);
        first = false;
      }
    }

    // On-track coordinates: where the via lands on both wires (the vertical
    // one of z / z+1 gives x, the horizontal one y); a top layer uses its own.
    if (la.hasUp()) {
      const LayerTracks& up = tracks.layers[z + 1];
      la.xTracks = !up.horizontal ? up.pref : xLines(own);
      la.yTracks = up.horizontal ? up.pref : yLines(own);
      la.spreadOnX = !up.horizontal;
    } else {
      la.xTracks = xLines(own);
      la.yTracks = yLines(own);
      la.spreadOnX = !own.horizontal;
    }

    la.stubWidth = rules.minWidth > 0 ? rules.minWidth : rules.width;
    if (la.stubWidth <= 0) la.stubWidth = own.wireWidth;
    la.stubLength = own.pitch > 0 ? own.pitch : std::max(rules.pitchX, rules.pitchY);
    if (la.stubLength <= 0) la.stubLength = 2 * la.stubWidth;
  }
  return out;
}

std::vector<int32_t> relevantTrackPatterns(const Tech& tech, const Design& design, int32_t z) {
  std::vector<int32_t> out;
  const int32_t layers = int32_t(tech.routingLayers.size());
  for (int32_t i = 0; i < int32_t(design.tracks.size()); ++i) {
    const int32_t rz = routingIndexOf(tech, design.tracks[i].layer);
    if (rz == z || (rz == z + 1 && z + 1 < layers)) out.push_back(i);
  }
  return out;
}

}  // namespace xroute::pa
