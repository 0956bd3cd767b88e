// Same-net connectivity of one layer's shapes: rects of one net that share a
// segment (not just a corner point) are joined.
//
// Shifted copies of a wire overlap each other by the thousand; asking the
// index for each rect's neighbours would then cost the square of their number.
// So runs of collinear rects are joined first, by sorting: rects of one net
// with the same y-interval whose x-ranges overlap or touch are one rect, their
// union, with the same contacts (a segment shared with the union is shared
// with one of them: the union of two corner points has no segment); then the
// same along y, over those unions. Each union then asks the index for the rects
// it shares a segment with.
#include <algorithm>
#include <tuple>

#include "drc/layer_shapes.hpp"

namespace xroute::drc {

namespace {

struct Run {
  Rect rect;    // DBU: the union of the run's rects
  int32_t net;  // < 0: an obstruction, never joined
  int32_t rep;  // one rect of the run (they are joined in the union-find)
};

// Joins the collinear runs of `runs` along x (same net and y-interval) or along y, in place.
void joinRuns(std::vector<Run>& runs, bool alongX, UnionFind& uf) {
  auto key = [&](const Run& r) {
    const Rect& b = r.rect;
    return alongX ? std::make_tuple(r.net, b.ylo, b.yhi, b.xlo, b.xhi) : std::make_tuple(r.net, b.xlo, b.xhi, b.ylo, b.yhi);
  };
  std::sort(runs.begin(), runs.end(), [&](const Run& a, const Run& b) { return key(a) < key(b); });
  size_t kept = 0;
  for (size_t k = 0; k < runs.size(); ++k) {
    const Run& r = runs[k];
    if (kept > 0 && r.net >= 0 && runs[kept - 1].net == r.net) {
      Rect& b = runs[kept - 1].rect;
      const bool sameSection = alongX ? (b.ylo == r.rect.ylo && b.yhi == r.rect.yhi)
                                      : (b.xlo == r.rect.xlo && b.xhi == r.rect.xhi);
      if (sameSection && (alongX ? r.rect.xlo <= b.xhi : r.rect.ylo <= b.yhi)) {
        uf.unite(runs[kept - 1].rep, r.rep);
        b.expandToInclude(r.rect);
        continue;
      }
    }
    runs[kept++] = r;
  }
  runs.resize(kept);
}

}  // namespace

void joinSameNet(const LayerShapes& ls, UnionFind& uf) {
  std::vector<Run> runs;
  runs.reserve(ls.size());
  for (size_t i = 0; i < ls.size(); ++i) runs.push_back({ls.rects[i], ls.nets[i], int32_t(i)});
  joinRuns(runs, true, uf);
  joinRuns(runs, false, uf);
  // A run touches another along a segment when it does so with one of the other's rects.
  for (const Run& r : runs) {
    if (r.net < 0) continue;
    ls.index.query(r.rect, [&](int32_t j) {
      if (ls.nets[j] == r.net && sharesSegment(r.rect, ls.rects[j])) uf.unite(r.rep, j);
    });
  }
}

}  // namespace xroute::drc
