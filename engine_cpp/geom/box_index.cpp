#include "geom/box_index.hpp"

#include <algorithm>
#include <cmath>

namespace xroute {

namespace {
constexpr int64_t kBigCells = 1024;  // a rect covering more cells than this goes to big_
}  // namespace

BoxIndex::BoxIndex(std::vector<Rect> rects) : rects_(std::move(rects)) {
  if (rects_.empty()) return;
  bounds_ = rects_.front();
  double dimSum = 0;
  for (const Rect& r : rects_) {
    bounds_.expandToInclude(r);
    dimSum += std::max(r.width(), r.height());
  }
  const double n = double(rects_.size());
  const double w = double(bounds_.width()) + 1, h = double(bounds_.height()) + 1;
  // About one rectangle per cell, and cells no smaller than the mean size.
  double cell = std::max(std::sqrt(w * h / n), dimSum / n);
  cell = std::max(cell, 1.0);
  // Keep the grid within ~4 cells per rectangle.
  while ((std::ceil(w / cell) * std::ceil(h / cell)) > 4 * n + 16) cell *= 1.5;
  cell_ = Dbu(std::min(cell, 1e9));
  nx_ = int(std::ceil(w / cell_));
  ny_ = int(std::ceil(h / cell_));

  const size_t cells = size_t(nx_) * size_t(ny_);
  cellStart_.assign(cells + 1, 0);
  std::vector<uint8_t> isBig(rects_.size(), 0);
  for (size_t i = 0; i < rects_.size(); ++i) {
    const Rect& r = rects_[i];
    const int x0 = cellX(r.xlo), x1 = cellX(r.xhi), y0 = cellY(r.ylo), y1 = cellY(r.yhi);
    if (int64_t(x1 - x0 + 1) * int64_t(y1 - y0 + 1) > kBigCells) {
      isBig[i] = 1;
      big_.push_back(int32_t(i));
      continue;
    }
    for (int cy = y0; cy <= y1; ++cy)
      for (int cx = x0; cx <= x1; ++cx) ++cellStart_[size_t(cy) * nx_ + cx + 1];
  }
  for (size_t c = 0; c < cells; ++c) cellStart_[c + 1] += cellStart_[c];
  items_.resize(cellStart_[cells]);
  std::vector<int32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  for (size_t i = 0; i < rects_.size(); ++i) {
    if (isBig[i]) continue;
    const Rect& r = rects_[i];
    const int x0 = cellX(r.xlo), x1 = cellX(r.xhi), y0 = cellY(r.ylo), y1 = cellY(r.yhi);
    for (int cy = y0; cy <= y1; ++cy)
      for (int cx = x0; cx <= x1; ++cx) items_[fill[size_t(cy) * nx_ + cx]++] = int32_t(i);
  }
}

double BoxIndex::crowding() const {
  if (rects_.empty()) return 0;
  double scans = 0;  // sum over listed items of their cell's occupancy
  for (size_t c = 0; c + 1 < cellStart_.size(); ++c) {
    const double k = cellStart_[c + 1] - cellStart_[c];
    scans += k * k;
  }
  return scans / double(rects_.size()) + double(big_.size());
}

std::vector<int32_t> BoxIndex::query(const Rect& window) const {
  std::vector<int32_t> out;
  query(window, [&](int32_t id) { out.push_back(id); });
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace xroute
