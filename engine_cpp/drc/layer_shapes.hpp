// Internal to the checker: the shapes of one layer with their spatial index
// and same-net connectivity, and the helpers every rule family shares.
#pragma once

#include <cstdint>
#include <vector>

#include "drc/drc.hpp"
#include "geom/box_index.hpp"
#include "geom/rect_tree.hpp"
#include "geom/union_find.hpp"

namespace xroute::drc {

// The spatial index of one layer's shapes: BoxIndex's uniform grid (the fastest on routed
// designs), or a RectTree when the grid is crowded (many long shapes over one place, such as
// thousands of overlapping copies of a wire: the grid would scan them all for every query).
// Both report the same rects; the rules do not depend on the order.
class ShapeIndex {
 public:
  // BoxIndex::crowding() above this: the tree. Measured on layers of routed designs: at most 28
  // (TritonRoute's ispd18_test1 and ispd19_test1), 57 (a 191-shape layer of ispd18_sample3); 2,371
  // with 50,000 copies of a wire shifted by 1 DBU. Either index gives the same markers.
  static constexpr double kMaxCrowding = 256;

  ShapeIndex() = default;
  ShapeIndex(const std::vector<Rect>& rects, const std::vector<int32_t>& nets) : grid_(rects) {
    if (grid_.crowding() > kMaxCrowding) {
      tree_ = RectTree(rects, nets);
      grid_ = BoxIndex();
      useTree_ = true;
    } else {
      nets_ = nets;
    }
  }
  // Every rect intersecting `window` (closed: touching counts), once each.
  template <class Visit>
  void query(const Rect& window, Visit&& visit) const {
    if (useTree_) tree_.query(window, visit);
    else grid_.query(window, visit);
  }
  // The same, leaving out the rects of net `net` (obstructions: -1).
  template <class Visit>
  void queryExcept(const Rect& window, int32_t net, Visit&& visit) const {
    if (useTree_) {
      tree_.queryExcept(window, net, visit);
    } else {
      grid_.query(window, [&](int32_t j) {
        if (nets_[j] != net) visit(j);
      });
    }
  }

 private:
  BoxIndex grid_;
  RectTree tree_;
  std::vector<int32_t> nets_;  // by rect, for the grid's queryExcept (the tree keeps its own)
  bool useTree_ = false;
};

struct LayerShapes {
  LayerId layer;
  const Layer* rules = nullptr;
  bool euclidean = true;          // CLEARANCEMEASURE EUCLIDEAN (else MAXXY)
  std::vector<Rect> rects;        // DBU, sorted canonically
  std::vector<int32_t> nets;      // per shape; < 0 = obstruction
  std::vector<uint8_t> fixed;     // per shape: 1 = pin / OBS / special net
  std::vector<uint8_t> taper;     // per shape: 1 = tapered routing (DrcShape::taper)
  std::vector<uint8_t> seed;      // per shape: 1 = near the window (pairs start here)
  ShapeIndex index;               // over rects (queryExcept: the other nets' only)
  // Connectivity: same-net shapes touching along a segment (not just a
  // corner point) form one component; an obstruction is its own component.
  std::vector<int32_t> comp;        // per shape: component id
  std::vector<int32_t> compStart;   // component c owns compMembers[compStart[c] .. compStart[c+1])
  std::vector<int32_t> compMembers; // shape indices, ascending
  std::vector<uint8_t> compFixed;   // 1 = every member fixed
  std::vector<uint8_t> compSeed;    // 1 = some member is a seed

  size_t size() const { return rects.size(); }
  bool isObs(int32_t i) const { return nets[i] < 0; }
  // True when the two shapes may conflict: different nets, not both obstructions.
  bool conflicting(int32_t a, int32_t b) const {
    if (nets[a] < 0 && nets[b] < 0) return false;
    return nets[a] < 0 || nets[b] < 0 || nets[a] != nets[b];
  }
};

struct RawMarker {
  Marker marker;
  bool fixed = false;  // every shape involved is fixed
};
using MarkerSink = std::vector<RawMarker>;

// Joins in `uf` the rects of one net that share a segment (not just a corner point):
// same-net connectivity (same_net_links.cpp).
void joinSameNet(const LayerShapes& ls, UnionFind& uf);

// A marker about two shapes: nets ordered (obstruction last), fixed if both are.
void addPairMarker(MarkerSink& out, const LayerShapes& ls, MarkerType type, const Rect& box, int32_t a, int32_t b);

// The overlap of two rects when they intersect, else the gap between them
// (degenerate along an axis where their projections just touch).
inline Rect gapBox(const Rect& a, const Rect& b) {
  const Dbu x1 = std::max(a.xlo, b.xlo), x2 = std::min(a.xhi, b.xhi);
  const Dbu y1 = std::max(a.ylo, b.ylo), y2 = std::min(a.yhi, b.yhi);
  return {std::min(x1, x2), std::min(y1, y2), std::max(x1, x2), std::max(y1, y2)};
}

// Gap along x and y (0 when the projections overlap or touch), DBU.
inline Dbu gapX(const Rect& a, const Rect& b) { return std::max({Dbu(0), b.xlo - a.xhi, a.xlo - b.xhi}); }
inline Dbu gapY(const Rect& a, const Rect& b) { return std::max({Dbu(0), b.ylo - a.yhi, a.ylo - b.yhi}); }

// Is the distance (dx, dy) strictly smaller than `space`? Euclidean or MAXXY.
inline bool closerThan(Dbu dx, Dbu dy, Dbu space, bool euclidean) {
  if (!euclidean) return std::max(dx, dy) < space;
  return int64_t(dx) * dx + int64_t(dy) * dy < int64_t(space) * space;
}

// Strict (positive-area) overlap of a closed rect with an open box.
inline bool overlapsOpen(const Rect& r, const Rect& box) {
  return r.xlo < box.xhi && r.xhi > box.xlo && r.ylo < box.yhi && r.yhi > box.ylo;
}

inline Rect expanded(const Rect& r, Dbu d) { return {r.xlo - d, r.ylo - d, r.xhi + d, r.yhi + d}; }

// Does component `c` cover the point (x2 / 2, y2 / 2)? x2, y2 are doubled
// coordinates, odd for the half-integer probes used at edge ends.
bool compCovers(const LayerShapes& ls, int32_t c, int64_t x2, int64_t y2);

// A boundary edge of the union of one component. Side says where the outside
// is: Top (+y), Bottom (-y), Right (+x), Left (-x). Horizontal edges (Top,
// Bottom) lie at y = coord over x in [lo, hi]; vertical ones at x = coord.
enum class Side : uint8_t { Bottom, Top, Left, Right };
struct Edge {
  Side side = Side::Top;
  Dbu coord = 0;           // DBU
  Dbu lo = 0, hi = 0;      // DBU, lo < hi
  bool convexLo = false;   // the corner at lo is convex (outside turns away)
  bool convexHi = false;
};
std::vector<Edge> componentEdges(const LayerShapes& ls, int32_t c);
// The same edges (convexity not set) by a sweep over the members (edge_sweep.cpp): used for
// components of more than kSweepMembers members, where a query per member side would scan the
// overlapping members over and over.
inline constexpr int32_t kSweepMembers = 32;
std::vector<Edge> componentEdgesBySweep(const LayerShapes& ls, int32_t c);

// The rule families (one file each).
void checkShorts(const LayerShapes& ls, MarkerType type, MarkerSink& out);
void checkPrlSpacing(const LayerShapes& ls, const DrcOptions& options, MarkerSink& out);
void checkEndOfLine(const LayerShapes& ls, MarkerSink& out);
void checkCutSpacing(const LayerShapes& ls, MarkerSink& out);
void checkMinArea(const LayerShapes& ls, MarkerSink& out);
void checkCornerSpacing(const LayerShapes& ls, MarkerSink& out);

// Longest distance at which any rule of the layer relates two shapes, DBU.
Dbu interactionRange(const Layer& layer);

}  // namespace xroute::drc
