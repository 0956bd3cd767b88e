// Shorts: shapes of different nets (or a net and an obstruction) that overlap
// or touch. Metal layers give Short, cut layers CutShort; the marker box is
// the intersection (a segment or a point when they only touch).
#include "drc/layer_shapes.hpp"

namespace xroute::drc {

void checkShorts(const LayerShapes& ls, MarkerType type, MarkerSink& out) {
  for (size_t i = 0; i < ls.size(); ++i) {
    if (!ls.seed[i]) continue;
    const int32_t a = int32_t(i);
    ls.index.queryExcept(ls.rects[a], ls.nets[a], [&](int32_t b) {  // other nets only: same net never conflicts
      if (b == a || (ls.seed[b] && b < a) || !ls.conflicting(a, b)) return;
      addPairMarker(out, ls, type, gapBox(ls.rects[a], ls.rects[b]), a, b);
    });
  }
}

}  // namespace xroute::drc
