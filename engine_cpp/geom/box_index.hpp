// A static spatial index of rectangles for window queries: a uniform bucket
// grid over the rectangles' bounding box. Each rectangle is listed in every
// cell it covers (rectangles covering very many cells go to a short list that
// every query scans), and a query reports each rectangle once, without any
// per-query state, so const queries may run concurrently.
#pragma once

#include <cstdint>
#include <vector>

#include "geom/geom.hpp"

namespace xroute {

class BoxIndex {
 public:
  BoxIndex() = default;
  explicit BoxIndex(std::vector<Rect> rects);

  size_t size() const { return rects_.size(); }
  const Rect& rect(int32_t id) const { return rects_[id]; }

  // Calls visit(id) once for every rectangle that intersects `window`
  // (closed rectangles: touching counts), in no particular order.
  template <class Visit>
  void query(const Rect& window, Visit&& visit) const;

  // The ids of the rectangles intersecting `window`, ascending.
  std::vector<int32_t> query(const Rect& window) const;

  // How crowded the cells are: the mean, over the rectangles, of the number of rectangles a query
  // of one of them scans (the occupants of its cells, the big list included). About 1 to 10 on
  // routed designs; thousands when many long rectangles crowd one place (then prefer RectTree).
  double crowding() const;

 private:
  int cellX(Dbu x) const;
  int cellY(Dbu y) const;

  std::vector<Rect> rects_;        // DBU, by id
  Rect bounds_;                    // DBU, bounding box of all rects
  Dbu cell_ = 1;                   // DBU, cell side
  int nx_ = 0, ny_ = 0;            // cells along x and y
  std::vector<int32_t> cellStart_; // cell c owns items_[cellStart_[c] .. cellStart_[c+1])
  std::vector<int32_t> items_;     // rect ids
  std::vector<int32_t> big_;       // rect ids scanned by every query
};

inline int BoxIndex::cellX(Dbu x) const {
  const int64_t c = (int64_t(x) - bounds_.xlo) / cell_;
  return c < 0 ? 0 : (c >= nx_ ? nx_ - 1 : int(c));
}

inline int BoxIndex::cellY(Dbu y) const {
  const int64_t c = (int64_t(y) - bounds_.ylo) / cell_;
  return c < 0 ? 0 : (c >= ny_ ? ny_ - 1 : int(c));
}

template <class Visit>
void BoxIndex::query(const Rect& w, Visit&& visit) const {
  if (rects_.empty()) return;
  for (int32_t id : big_) {
    if (rects_[id].overlaps(w)) visit(id);
  }
  if (nx_ == 0 || !bounds_.overlaps(w)) return;
  const int wx0 = cellX(w.xlo), wx1 = cellX(w.xhi), wy0 = cellY(w.ylo), wy1 = cellY(w.yhi);
  for (int cy = wy0; cy <= wy1; ++cy) {
    for (int cx = wx0; cx <= wx1; ++cx) {
      const int c = cy * nx_ + cx;
      for (int32_t k = cellStart_[c]; k < cellStart_[c + 1]; ++k) {
        const int32_t id = items_[k];
        const Rect& r = rects_[id];
        // Report a rect only from the first cell it shares with the window.
        const int fx = std::max(cellX(r.xlo), wx0), fy = std::max(cellY(r.ylo), wy0);
        if (fx == cx && fy == cy && r.overlaps(w)) visit(id);
      }
    }
  }
}

}  // namespace xroute
