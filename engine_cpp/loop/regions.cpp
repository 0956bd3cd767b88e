#include "loop/regions.hpp"

#include <algorithm>

#include "grid/region_grid.hpp"

namespace xroute {

namespace {

// Region boundaries as GCell indices: 0, offset?, offset + size, ..., n.
std::vector<int> cuts(int n, int size, int offset) {
  std::vector<int> c{0};
  for (int g = (offset > 0 ? offset : size); g < n; g += size) c.push_back(g);
  c.push_back(n);
  return c;
}

}  // namespace

double regionGridNodes(const GCellGrid& grid, const TrackSet& tracks, const std::vector<AccessPoint>& terminals,
                       int size) {
  // Per region with a terminal: the lines RegionGrid lays for it (without the crossings a run adds).
  const std::vector<Region> regions = partitionRegions(grid, size, 0);
  std::vector<std::vector<Dbu>> xs(regions.size()), ys(regions.size());
  for (const AccessPoint& ap : terminals) {
    const int32_t r = regionAt(regions, grid, size, 0, ap.at);
    xs[r].push_back(ap.at.x);
    ys[r].push_back(ap.at.y);
  }
  std::vector<double> nodes;
  for (const Region& r : regions) {
    if (xs[r.id].empty()) continue;
    regionGridLines(tracks, r.box, xs[r.id], ys[r.id]);
    nodes.push_back(static_cast<double>(xs[r.id].size()) * static_cast<double>(ys[r.id].size()));
  }
  if (nodes.empty()) return 0;
  const size_t q = nodes.size() * 3 / 4;  // the upper quartile
  std::nth_element(nodes.begin(), nodes.begin() + q, nodes.end());
  return nodes[q];
}

int autoRegionSize(const GCellGrid& grid, const TrackSet& tracks, const std::vector<AccessPoint>& terminals,
                   int maxSize) {
  int size = std::clamp(kRegionGCells, 1, maxSize);
  // Fine tracks over large GCells (asap7, sky130): shrink while this size's grids are over the budget.
  const int least = std::min(size, kLeastRegionGCells);
  if (size > least && regionGridNodes(grid, tracks, terminals, size) > kRegionGridNodes) {
    do --size;
    while (size > least && regionGridNodes(grid, tracks, terminals, size) > kRegionGridNodes);
    return size;
  }
  // Grow while the next size's grid stays within the budget and this one leaves the die uncovered.
  while (size < maxSize && (size < grid.nx() || size < grid.ny()) &&
         regionGridNodes(grid, tracks, terminals, size + 1) <= kRegionGridNodes)
    ++size;
  return size;
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
