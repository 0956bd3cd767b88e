#include "grid/via_set.hpp"

#include <algorithm>
#include <tuple>

#include "io/input_error.hpp"

namespace xroute {

Rect viaMetal(const Tech& tech, const Via& via, LayerId layer) {
  bool any = false;
  Rect box{0, 0, 0, 0};
  for (const ViaShape& s : via.shapes) {
    if (s.layer != layer) continue;
    if (!any) box = s.rect;
    else box.expandToInclude(s.rect);
    any = true;
  }
  return box;
}

namespace {

// How well a metal rect follows a layer's preferred direction: 0 when its
// long side runs along it (or it is square), 1 otherwise.
int misaligned(const Rect& r, bool horizontal) {
  if (r.width() == r.height()) return 0;
  return (r.width() > r.height()) == horizontal ? 0 : 1;
}

}  // namespace

ViaSet chooseVias(const Tech& tech, const TrackSet& tracks) {
  ViaSet set;
  const size_t nz = tracks.layers.size();
  for (size_t z = 0; z + 1 < nz; ++z) {
    const LayerId lo = tracks.layers[z].layer, hi = tracks.layers[z + 1].layer;
    // (not default, misalignment, metal area, name) -> smaller is better.
    using Key = std::tuple<int, int, Area, std::string>;
    bool found = false;
    Key best;
    CutVia choice;
    for (size_t v = 0; v < tech.vias.size(); ++v) {
      const Via& via = tech.vias[v];
      if (via.bottom != lo || via.top != hi || !via.cut.valid()) continue;
      CutVia c;
      c.via = ViaId(static_cast<int32_t>(v));
      c.bottomMetal = viaMetal(tech, via, lo);
      c.topMetal = viaMetal(tech, via, hi);
      c.cut = viaMetal(tech, via, via.cut);
      const Key key{via.isDefault ? 0 : 1,
                    misaligned(c.bottomMetal, tracks.layers[z].horizontal) +
                        misaligned(c.topMetal, tracks.layers[z + 1].horizontal),
                    c.bottomMetal.area() + c.topMetal.area(), via.name};
      if (!found || key < best) {
        best = key;
        choice = c;
        found = true;
      }
    }
    if (!found) {
      const Layer& upper = tech.layer(hi);  // named by the LEF that defines the upper layer
      throw InputError(upper.path.empty() ? std::string("LEF") : upper.path, upper.line,
                       "no VIA connects " + tech.layer(lo).name + " and " + upper.name);
    }
    set.cuts.push_back(choice);
  }
  return set;
}

}  // namespace xroute
