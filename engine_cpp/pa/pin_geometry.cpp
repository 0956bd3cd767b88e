// Pin metal as rects: placing macro shapes (polygons cut into slabs), the
// coverage test used for via cuts, and rect subtraction (OBS cut back at the
// cell's own pins).
#include <algorithm>

#include "pa/pa_internal.hpp"

namespace xroute::pa {

namespace {

// Horizontal slabs of a rectilinear polygon; its bounding box when an edge
// is slanted.
void polygonSlabs(const std::vector<Point>& pts, std::vector<Rect>& out) {
  const size_t n = pts.size();
  if (n < 3) return;
  Rect box{pts[0].x, pts[0].y, pts[0].x, pts[0].y};
  bool rectilinear = true;
  for (size_t i = 0; i < n; ++i) {
    const Point a = pts[i], b = pts[(i + 1) % n];
    box.expandToInclude({b.x, b.y, b.x, b.y});
    rectilinear = rectilinear && (a.x == b.x || a.y == b.y);
  }
  if (!rectilinear) {
    out.push_back(box);
    return;
  }
  std::vector<Dbu> ys;
  for (const Point& p : pts) ys.push_back(p.y);
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  std::vector<Dbu> crossings;
  for (size_t k = 0; k + 1 < ys.size(); ++k) {
    // Vertical edges spanning the slab [ys[k], ys[k+1]], paired left to right
    // (even-odd rule).
    crossings.clear();
    for (size_t i = 0; i < n; ++i) {
      const Point a = pts[i], b = pts[(i + 1) % n];
      if (a.x == b.x && std::min(a.y, b.y) <= ys[k] && std::max(a.y, b.y) >= ys[k + 1]) crossings.push_back(a.x);
    }
    std::sort(crossings.begin(), crossings.end());
    for (size_t i = 0; i + 1 < crossings.size(); i += 2) {
      if (crossings[i] < crossings[i + 1]) out.push_back({crossings[i], ys[k], crossings[i + 1], ys[k + 1]});
    }
  }
}

}  // namespace

void placedRects(const MacroShape& shape, const Transform& t, std::vector<Rect>& out) {
  if (shape.polygon.empty()) {
    out.push_back(t.apply(shape.rect));
    return;
  }
  std::vector<Point> pts;
  pts.reserve(shape.polygon.size());
  for (const Point& p : shape.polygon) pts.push_back(t.apply(p));
  polygonSlabs(pts, out);
}

Area uncoveredArea(const std::vector<PinRect>& metal, int32_t z, const Rect& r) {
  // Clip the rects that share area with r; then sum the cells of the grid
  // their edges make inside r that lie in none of them.
  if (r.xlo >= r.xhi || r.ylo >= r.yhi) return 0;
  std::vector<Rect> parts;
  std::vector<Dbu> xs{r.xlo, r.xhi}, ys{r.ylo, r.yhi};
  for (const PinRect& m : metal) {
    if (m.z != z) continue;
    const Rect& a = m.rect;
    if (a.xlo <= r.xlo && a.ylo <= r.ylo && a.xhi >= r.xhi && a.yhi >= r.yhi) return 0;  // one rect covers it
    const Rect c{std::max(a.xlo, r.xlo), std::max(a.ylo, r.ylo), std::min(a.xhi, r.xhi), std::min(a.yhi, r.yhi)};
    if (c.xlo >= c.xhi || c.ylo >= c.yhi) continue;
    parts.push_back(c);
    xs.push_back(c.xlo), xs.push_back(c.xhi);
    ys.push_back(c.ylo), ys.push_back(c.yhi);
  }
  if (parts.empty()) return r.area();
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  Area open = 0;
  for (size_t i = 0; i + 1 < xs.size(); ++i) {
    for (size_t j = 0; j + 1 < ys.size(); ++j) {
      const Rect cell{xs[i], ys[j], xs[i + 1], ys[j + 1]};
      const bool inside = std::any_of(parts.begin(), parts.end(), [&](const Rect& p) {
        return p.xlo <= cell.xlo && p.ylo <= cell.ylo && p.xhi >= cell.xhi && p.yhi >= cell.yhi;
      });
      if (!inside) open += cell.area();
    }
  }
  return open;
}

bool coveredBy(const std::vector<PinRect>& metal, int32_t z, const Rect& r) {
  return r.xlo < r.xhi && r.ylo < r.yhi && uncoveredArea(metal, z, r) == 0;
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

}  // namespace xroute::pa
