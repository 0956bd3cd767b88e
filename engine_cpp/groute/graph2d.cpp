#include "groute/graph2d.hpp"

#include <algorithm>
#include <utility>

namespace xroute {

Graph2d::Graph2d(const GrGrid& grid, int minLayer, int capacityPercent) : nx_(grid.nx()), ny_(grid.ny()) {
  const size_t cells = static_cast<size_t>(nx_) * ny_;
  capacity_.assign(cells * 2, 0);
  usage_.assign(cells * 2, 0);
  history_.assign(cells * 2, 0.0);
  for (int z = minLayer; z < grid.nz(); ++z) {
    const GrLayer& gl = grid.layers[z];
    const int dir = gl.horizontal ? 0 : 1;
    for (size_t c = 0; c < cells; ++c) capacity_[c * 2 + dir] += gl.capacity[c];
  }
  for (int32_t& c : capacity_) c = static_cast<int32_t>(int64_t(c) * capacityPercent / 100);
}

int32_t Graph2d::edgeBetween(int32_t a, int32_t b) const {
  if (a > b) std::swap(a, b);
  return b - a == 1 ? edge(a, 0) : edge(a, 1);
}

void Graph2d::addUsage(const std::vector<int32_t>& edges, int delta) {
  for (int32_t e : edges) usage_[e] += delta;
}

double Graph2d::cost(int32_t e, double presentFactor) const {
  const int32_t over = usage_[e] + 1 - capacity_[e];
  return (1.0 + history_[e]) * (1.0 + (over > 0 ? presentFactor * over : 0.0));
}

void Graph2d::bumpHistory(double step) {
  for (size_t e = 0; e < usage_.size(); ++e) {
    if (usage_[e] > capacity_[e]) history_[e] += step * (usage_[e] - capacity_[e]);
  }
}

int64_t Graph2d::totalOverflow() const {
  int64_t total = 0;
  for (size_t e = 0; e < usage_.size(); ++e) total += std::max(0, usage_[e] - capacity_[e]);
  return total;
}

int64_t Graph2d::overflowedEdges() const {
  int64_t n = 0;
  for (size_t e = 0; e < usage_.size(); ++e) n += usage_[e] > capacity_[e];
  return n;
}

}  // namespace xroute
