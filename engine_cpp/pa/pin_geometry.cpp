// Pin metal coverage: the test used for via cuts.
#include <algorithm>

#include "pa/pa_internal.hpp"

namespace xroute::pa {

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


}  // namespace xroute::pa
