#include "flow/regions.hpp"

#include <algorithm>
#include <cmath>

namespace xroute {

namespace {

// The most common guide extent along an axis: the global router's GCell
// pitch (most guides are one GCell wide), or 0 without guides.
Dbu guidePitch(const Design& design, bool isX, Dbu& origin) {
  std::vector<Dbu> sizes;
  for (const Rect& g : design.guideRects) {
    const Dbu s = isX ? g.width() : g.height();
    if (s > 0) sizes.push_back(s);
  }
  if (sizes.empty()) return 0;
  std::sort(sizes.begin(), sizes.end());
  Dbu best = sizes.front();
  size_t bestCount = 0;
  for (size_t i = 0; i < sizes.size();) {
    size_t j = i;
    while (j < sizes.size() && sizes[j] == sizes[i]) ++j;
    if (j - i > bestCount) {
      bestCount = j - i;
      best = sizes[i];
    }
    i = j;
  }
  // Grid origin: the low edge of a guide of exactly that size.
  origin = 0;
  for (const Rect& g : design.guideRects) {
    if ((isX ? g.width() : g.height()) == best) {
      origin = isX ? g.xlo : g.ylo;
      break;
    }
  }
  return best;
}

std::vector<Dbu> derivedLines(const Design& design, const TrackSet& tracks, bool isX) {
  const Dbu lo = isX ? design.dieArea.xlo : design.dieArea.ylo;
  const Dbu hi = isX ? design.dieArea.xhi : design.dieArea.yhi;
  std::vector<Dbu> lines = gcellLines(design, isX);
  if (lines.size() < 2) {
    lines.clear();
    Dbu origin = 0;
    Dbu step = guidePitch(design, isX, origin);
    if (step <= 0) {
      // No grid given: 15 pitches of the lowest layer whose tracks run across this axis.
      for (const LayerTracks& lt : tracks.layers) {
        if (lt.horizontal != isX && lt.pitch > 0) {
          step = lt.pitch * 15;
          break;
        }
      }
      origin = lo;
    }
    if (step <= 0) step = std::max<Dbu>(1, (hi - lo) / 16);
    Dbu first = origin - ((origin - lo) / step) * step;  // first line at or after lo
    if (first < lo) first += step;
    for (Dbu v = first; v < hi; v += step) lines.push_back(v);
    // A last cell shorter than half a pitch joins its neighbour.
    if (!lines.empty() && hi - lines.back() < step / 2 && lines.back() > lo) lines.pop_back();
  }
  lines.push_back(lo);
  lines.push_back(hi);
  std::erase_if(lines, [&](Dbu v) { return v < lo || v > hi; });
  std::sort(lines.begin(), lines.end());
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  return lines;
}

// Region boundaries as GCell indices: 0, offset?, offset + size, ..., n.
std::vector<int> cuts(int n, int size, int offset) {
  std::vector<int> c{0};
  for (int g = (offset > 0 ? offset : size); g < n; g += size) c.push_back(g);
  c.push_back(n);
  return c;
}

}  // namespace

GCellGrid makeGCellGrid(const Design& design, const TrackSet& tracks) {
  return GCellGrid{derivedLines(design, tracks, true), derivedLines(design, tracks, false)};
}

namespace {

// The median of `v` (the lower middle one of an even count); 0 when empty.
Dbu median(std::vector<Dbu> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + (v.size() - 1) / 2, v.end());
  return v[(v.size() - 1) / 2];
}

}  // namespace

int autoRegionSize(const GCellGrid& grid, const TrackSet& tracks, int maxSize) {
  // Tracks per GCell along one axis: the median GCell side over the median pitch of the layers whose
  // tracks cross that axis (vertical layers' tracks are x coordinates); 0 when either is unknown.
  auto tracksPerGCell = [&](const std::vector<Dbu>& lines, bool horizontalLayers) {
    std::vector<Dbu> pitches, sides;
    for (const LayerTracks& t : tracks.layers)
      if (t.horizontal == horizontalLayers && t.pitch > 0) pitches.push_back(t.pitch);
    for (size_t i = 1; i < lines.size(); ++i) sides.push_back(lines[i] - lines[i - 1]);
    const Dbu pitch = median(std::move(pitches)), side = median(std::move(sides));
    return pitch > 0 && side > 0 ? static_cast<double>(side) / static_cast<double>(pitch) : 0.0;
  };
  const double tx = tracksPerGCell(grid.xs, false), ty = tracksPerGCell(grid.ys, true);
  const double perGCell = tx > 0 && ty > 0 ? (tx + ty) / 2 : std::max(tx, ty);
  const double widened = perGCell > 0 ? std::round(kRegionTracks / perGCell) : 0.0;
  const double size = std::max(static_cast<double>(kRegionGCells), widened);
  return static_cast<int>(std::clamp(size, 1.0, static_cast<double>(maxSize)));
}

std::vector<Region> partitionRegions(const GCellGrid& grid, int size, int offset) {
  size = std::max(1, size);
  offset = ((offset % size) + size) % size;
  const std::vector<int> cx = cuts(grid.nx(), size, offset), cy = cuts(grid.ny(), size, offset);
  std::vector<Region> regions;
  for (size_t j = 0; j + 1 < cy.size(); ++j) {
    for (size_t i = 0; i + 1 < cx.size(); ++i) {
      Region r;
      r.id = static_cast<int32_t>(regions.size());
      r.gx0 = cx[i];
      r.gx1 = cx[i + 1];
      r.gy0 = cy[j];
      r.gy1 = cy[j + 1];
      r.rx = static_cast<int>(i);
      r.ry = static_cast<int>(j);
      r.box = {grid.xs[r.gx0], grid.ys[r.gy0], grid.xs[r.gx1], grid.ys[r.gy1]};
      r.color = (r.rx % 2) + 2 * (r.ry % 2);
      regions.push_back(r);
    }
  }
  return regions;
}

int32_t regionAt(const std::vector<Region>& regions, const GCellGrid& grid, int size, int offset, Point p) {
  size = std::max(1, size);
  offset = ((offset % size) + size) % size;
  auto colOf = [&](const std::vector<Dbu>& lines, Dbu v) {
    int g = static_cast<int>(std::upper_bound(lines.begin(), lines.end(), v) - lines.begin()) - 1;
    g = std::clamp(g, 0, static_cast<int>(lines.size()) - 2);
    // Region column of GCell g.
    if (offset == 0) return g / size;
    return g < offset ? 0 : 1 + (g - offset) / size;
  };
  const int ncols = static_cast<int>(cuts(grid.nx(), size, offset).size()) - 1;
  const int rx = colOf(grid.xs, p.x), ry = colOf(grid.ys, p.y);
  const int32_t id = ry * ncols + rx;
  return (id >= 0 && id < static_cast<int32_t>(regions.size())) ? id : -1;
}

}  // namespace xroute
