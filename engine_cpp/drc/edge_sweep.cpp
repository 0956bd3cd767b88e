// componentEdges for large components: the boundary of the union of the member
// rects by a sweep, O(M log M) for M members, instead of one index query per
// side of each member (O(M^2) when the members overlap each other, as
// thousands of copies of a wire shifted by one DBU do). It gives the same
// edges: the pieces of a member's side not covered by another member that
// continues the metal past it are, merged, the union's boundary runs.
//
// Each kind of side is computed as a Top side in a frame where it is one:
// Bottom mirrors y; Right swaps the axes; Left swaps and mirrors. A Top side
// at y is covered over x by the members with ylo <= y < yhi (closed in x).
#include <algorithm>

#include "drc/layer_shapes.hpp"

namespace xroute::drc {

namespace {

// Cover counts over the elementary segments (xs[k], xs[k+1]): range add, and
// the segments of a range whose count is zero.
class CoverTree {
 public:
  explicit CoverTree(size_t segments) : n_(std::max<size_t>(segments, 1)), add_(4 * n_, 0), min_(4 * n_, 0) {}
  void add(size_t lo, size_t hi, int v) { add(1, 0, n_, lo, hi, v); }  // segments [lo, hi)
  template <class Out>
  void zeros(size_t lo, size_t hi, Out&& out) const { zeros(1, 0, n_, lo, hi, out); }

 private:
  void add(size_t node, size_t l, size_t r, size_t lo, size_t hi, int v) {
    if (hi <= l || r <= lo) return;
    if (lo <= l && r <= hi) {
      add_[node] += v;
      min_[node] += v;
      return;
    }
    const size_t m = (l + r) / 2;
    add(2 * node, l, m, lo, hi, v);
    add(2 * node + 1, m, r, lo, hi, v);
    min_[node] = add_[node] + std::min(min_[2 * node], min_[2 * node + 1]);
  }
  template <class Out>
  void zeros(size_t node, size_t l, size_t r, size_t lo, size_t hi, Out& out) const {
    if (hi <= l || r <= lo || min_[node] > 0) return;  // counts are never negative: a zero needs add_ 0 on the way
    if (r - l == 1) {
      out(l);
      return;
    }
    const size_t m = (l + r) / 2;
    zeros(2 * node, l, m, lo, hi, out);
    zeros(2 * node + 1, m, r, lo, hi, out);
  }

  size_t n_;
  std::vector<int> add_;  // per node: added to all of its range
  std::vector<int> min_;  // per node: the least count in its range (its own add_ included)
};

struct Run {
  Dbu coord, lo, hi;  // DBU, in the frame
};

// The uncovered runs of the Top sides of `rs` (frame coordinates), by coord then lo.
std::vector<Run> topRuns(const std::vector<Rect>& rs) {
  const std::vector<Dbu> xs = edgeCoords(rs, true);
  auto at = [&](Dbu x) { return size_t(std::lower_bound(xs.begin(), xs.end(), x) - xs.begin()); };
  std::vector<int32_t> byLo(rs.size()), byHi(rs.size());
  for (size_t i = 0; i < rs.size(); ++i) byLo[i] = byHi[i] = int32_t(i);
  std::sort(byLo.begin(), byLo.end(), [&](int32_t a, int32_t b) { return rs[a].ylo < rs[b].ylo; });
  std::sort(byHi.begin(), byHi.end(), [&](int32_t a, int32_t b) { return rs[a].yhi < rs[b].yhi; });
  CoverTree tree(xs.size() - 1);
  std::vector<Run> runs;
  std::vector<std::pair<Dbu, Dbu>> tops;
  size_t nextLo = 0, nextHi = 0;
  while (nextHi < byHi.size()) {
    const Dbu y = nextLo < byLo.size() ? std::min(rs[byLo[nextLo]].ylo, rs[byHi[nextHi]].yhi) : rs[byHi[nextHi]].yhi;
    tops.clear();
    for (; nextHi < byHi.size() && rs[byHi[nextHi]].yhi == y; ++nextHi) {  // ends here: covers no more
      const Rect& r = rs[byHi[nextHi]];
      tree.add(at(r.xlo), at(r.xhi), -1);
      tops.push_back({r.xlo, r.xhi});
    }
    for (; nextLo < byLo.size() && rs[byLo[nextLo]].ylo == y; ++nextLo) {  // starts here: covers y
      const Rect& r = rs[byLo[nextLo]];
      tree.add(at(r.xlo), at(r.xhi), +1);
    }
    std::sort(tops.begin(), tops.end());
    for (size_t k = 0; k < tops.size();) {
      Dbu lo = tops[k].first, hi = tops[k].second;
      for (++k; k < tops.size() && tops[k].first <= hi; ++k) hi = std::max(hi, tops[k].second);
      tree.zeros(at(lo), at(hi), [&](size_t s) {
        if (!runs.empty() && runs.back().coord == y && runs.back().hi == xs[s]) runs.back().hi = xs[s + 1];
        else runs.push_back({y, xs[s], xs[s + 1]});
      });
    }
  }
  return runs;
}

}  // namespace

std::vector<Edge> componentEdgesBySweep(const LayerShapes& ls, int32_t c) {
  std::vector<Edge> edges;
  std::vector<Rect> frame;
  for (Side side : {Side::Bottom, Side::Top, Side::Left, Side::Right}) {
    frame.clear();
    for (int32_t k = ls.compStart[c]; k < ls.compStart[c + 1]; ++k) {
      const Rect& r = ls.rects[ls.compMembers[k]];
      switch (side) {
        case Side::Top: frame.push_back(r); break;
        case Side::Bottom: frame.push_back({r.xlo, -r.yhi, r.xhi, -r.ylo}); break;
        case Side::Right: frame.push_back({r.ylo, r.xlo, r.yhi, r.xhi}); break;
        case Side::Left: frame.push_back({r.ylo, -r.xhi, r.yhi, -r.xlo}); break;
      }
    }
    std::vector<Run> runs = topRuns(frame);
    const bool mirrored = side == Side::Bottom || side == Side::Left;
    if (mirrored) {  // ascending coord in the design
      for (Run& r : runs) r.coord = -r.coord;
      std::stable_sort(runs.begin(), runs.end(), [](const Run& a, const Run& b) { return a.coord < b.coord; });
    }
    for (const Run& r : runs) edges.push_back({side, r.coord, r.lo, r.hi, false, false});
  }
  return edges;
}

}  // namespace xroute::drc
