// Internal to the checker: the shapes of one layer with their spatial index
// and same-net connectivity, and the helpers every rule family shares.
#pragma once

#include <cstdint>
#include <vector>

#include "drc/drc.hpp"
#include "geom/box_index.hpp"

namespace xroute::drc {

struct LayerShapes {
  LayerId layer;
  const Layer* rules = nullptr;
  bool euclidean = true;          // CLEARANCEMEASURE EUCLIDEAN (else MAXXY)
  std::vector<Rect> rects;        // DBU, sorted canonically
  std::vector<int32_t> nets;      // per shape; < 0 = obstruction
  std::vector<uint8_t> fixed;     // per shape: 1 = pin / OBS / special net
  std::vector<uint8_t> seed;      // per shape: 1 = near the window (pairs start here)
  BoxIndex index;
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
