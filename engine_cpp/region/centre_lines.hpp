// A net's routing read as centre lines: which wires and vias pass through a point of a layer.
// Routes are made on centre lines (a path's wire ends and vias sit on the tree it joins), so this
// tells joins that routes made apart from metal that merely overlaps.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "geom/geom.hpp"

namespace xroute {

class CentreLineIndex {
 public:
  // Piece `piece` runs on routing layer z from a to b (axis-parallel; a point when a == b, such as
  // one layer of a via).
  void add(int32_t piece, int z, Point a, Point b) {
    if (a.y == b.y) horizontal_[{z, a.y}].push_back({std::min(a.x, b.x), std::max(a.x, b.x), piece});
    else vertical_[{z, a.x}].push_back({std::min(a.y, b.y), std::max(a.y, b.y), piece});
  }
  // Calls fn(piece) for every piece whose centre line holds p on layer z (a piece may come twice).
  template <class Fn>
  void at(int z, Point p, Fn&& fn) const {
    if (auto it = horizontal_.find({z, p.y}); it != horizontal_.end())
      for (const Span& s : it->second)
        if (s.lo <= p.x && p.x <= s.hi) fn(s.piece);
    if (auto it = vertical_.find({z, p.x}); it != vertical_.end())
      for (const Span& s : it->second)
        if (s.lo <= p.y && p.y <= s.hi) fn(s.piece);
  }

 private:
  struct Span {
    Dbu lo, hi;
    int32_t piece;
  };
  std::map<std::pair<int, Dbu>, std::vector<Span>> horizontal_, vertical_;
};

}  // namespace xroute
