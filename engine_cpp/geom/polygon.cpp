#include "geom/polygon.hpp"

#include <algorithm>

namespace xroute {

void polygonRects(const std::vector<Point>& pts, std::vector<Rect>& out) {
  const size_t n = pts.size();
  if (n < 3) return;
  Rect box{pts[0].x, pts[0].y, pts[0].x, pts[0].y};
  bool manhattan = true;
  for (size_t i = 0; i < n; ++i) {
    const Point a = pts[i], b = pts[(i + 1) % n];
    box.expandToInclude({b.x, b.y, b.x, b.y});
    manhattan = manhattan && (a.x == b.x || a.y == b.y);
  }
  if (!manhattan) {
    out.push_back(box);
    return;
  }
  std::vector<Dbu> ys;
  for (const Point& p : pts) ys.push_back(p.y);
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  std::vector<Dbu> xs;
  for (size_t k = 0; k + 1 < ys.size(); ++k) {
    xs.clear();
    for (size_t i = 0; i < n; ++i) {
      const Point a = pts[i], b = pts[(i + 1) % n];
      if (a.x == b.x && std::min(a.y, b.y) <= ys[k] && std::max(a.y, b.y) >= ys[k + 1]) xs.push_back(a.x);
    }
    std::sort(xs.begin(), xs.end());
    for (size_t i = 0; i + 1 < xs.size(); i += 2) {
      if (xs[i] < xs[i + 1]) out.push_back({xs[i], ys[k], xs[i + 1], ys[k + 1]});
    }
  }
}

void subtractRect(const Rect& r, const Rect& cut, std::vector<Rect>& out) {
  if (cut.xlo >= r.xhi || cut.xhi <= r.xlo || cut.ylo >= r.yhi || cut.yhi <= r.ylo) {
    out.push_back(r);
    return;
  }
  if (cut.ylo > r.ylo) out.push_back({r.xlo, r.ylo, r.xhi, cut.ylo});
  if (cut.yhi < r.yhi) out.push_back({r.xlo, cut.yhi, r.xhi, r.yhi});
  const Dbu y0 = std::max(r.ylo, cut.ylo), y1 = std::min(r.yhi, cut.yhi);
  if (cut.xlo > r.xlo) out.push_back({r.xlo, y0, cut.xlo, y1});
  if (cut.xhi < r.xhi) out.push_back({cut.xhi, y0, r.xhi, y1});
}

}  // namespace xroute
