#include "groute/global_router.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>

#include "groute/capacity.hpp"
#include "groute/graph2d.hpp"
#include "groute/layer_assign.hpp"
#include "groute/net_pins.hpp"
#include "groute/tree_route.hpp"
#include "grid/tracks.hpp"

namespace xroute {

namespace {

// Half perimeter of the pins' bounding box, GCells.
int64_t halfPerimeter(const std::vector<int32_t>& pins, int nx) {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
  for (int32_t p : pins) {
    x0 = std::min(x0, p % nx);
    x1 = std::max(x1, p % nx);
    y0 = std::min(y0, p / nx);
    y1 = std::max(y1, p / nx);
  }
  return pins.empty() ? 0 : (x1 - x0) + (y1 - y0);
}

}  // namespace

GlobalRouteResult globalRoute(const Tech& tech, const Design& design, const GlobalRouteSettings& st) {
  const auto t0 = std::chrono::steady_clock::now();
  GlobalRouteResult out;
  GlobalRouteStats& stats = out.stats;
  const TrackSet tracks = buildTracks(tech, design);
  const GrGrid grid = buildGrGrid(tech, design, tracks);
  const std::vector<GrNet> nets = collectGrNets(tech, design, grid);
  const int nx = grid.nx();
  const int minLayer = std::clamp(st.minLayer, 0, std::max(0, grid.nz() - 1));
  stats.nx = nx;
  stats.ny = grid.ny();
  stats.nz = grid.nz();

  // Nets with two or more pin GCells, smaller first.
  std::vector<int32_t> order;
  std::vector<int64_t> size(nets.size(), 0);
  for (size_t n = 0; n < nets.size(); ++n) {
    size[n] = halfPerimeter(nets[n].anchors, nx);
    if (nets[n].anchors.size() >= 2) order.push_back(static_cast<int32_t>(n));
  }
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return size[a] < size[b]; });
  stats.nets = static_cast<int64_t>(order.size());

  Graph2d g(grid, minLayer, st.capacityPercent);
  std::vector<std::vector<int32_t>> routes(nets.size());
  for (int32_t n : order) {
    routes[n] = patternRoute(g, nets[n].anchors, st.presentFactor);
    g.addUsage(routes[n], +1);
  }
  stats.initialOverflow = g.totalOverflow();

  MazeScratch scratch;
  double pf = st.presentFactor;
  for (int round = 0; round < st.iterations && g.totalOverflow() > 0; ++round) {
    g.bumpHistory(st.historyStep);
    pf *= 1.5;
    std::vector<int32_t> redo;
    for (int32_t n : order) {
      for (int32_t e : routes[n]) {
        if (g.overflowed(e)) {
          redo.push_back(n);
          break;
        }
      }
    }
    for (int32_t n : redo) {
      g.addUsage(routes[n], -1);
      routes[n] = mazeRoute(g, nets[n].anchors, pf, st.margin + round / 3, scratch);
      g.addUsage(routes[n], +1);
    }
    stats.reroutes += static_cast<int64_t>(redo.size());
    stats.iterations = round + 1;
  }
  stats.overflow = g.totalOverflow();
  stats.overflowEdges = g.overflowedEdges();
  for (int32_t n : order) stats.wirelength += static_cast<int64_t>(routes[n].size());

  LayerAssignSettings las;
  las.minLayer = minLayer;
  las.viaCost = st.viaCost;
  las.capacityPercent = st.capacityPercent;
  las.congestionCost = st.congestionCost;
  std::vector<int32_t> laOrder = order;
  std::stable_sort(laOrder.begin(), laOrder.end(),
                   [&](int32_t a, int32_t b) { return routes[a].size() < routes[b].size(); });
  const LayerAssignment la = assignLayers(grid, nets, routes, laOrder, las);
  stats.overflow3d = la.overflow;
  out.guides = makeGuides(grid, nets, la, st.slack);
  stats.vias = out.guides.vias;
  stats.guides = static_cast<int64_t>(out.guides.rects.size());
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace xroute
