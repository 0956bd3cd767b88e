// The 2D routing graph the nets are routed on first: one node per GCell, an
// edge to the right (+x) and one upward (+y) of each, the capacity of an
// edge being the sum over the layers of that direction (from `minLayer` up)
// of their track capacities. Usage counts nets (a net pays once per edge);
// history grows on edges that stay overflowed (negotiated congestion).
#pragma once

#include <cstdint>
#include <vector>

#include "groute/capacity.hpp"

namespace xroute {

class Graph2d {
 public:
  // capacityPercent scales every capacity (100 = all free tracks).
  Graph2d(const GrGrid& grid, int minLayer, int capacityPercent);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  // Edge id of the edge leaving `cell` toward +x (dir 0) or +y (dir 1).
  static int32_t edge(int32_t cell, int dir) { return cell * 2 + dir; }
  static int32_t edgeCell(int32_t e) { return e / 2; }
  static int edgeDir(int32_t e) { return e % 2; }
  // The edge between two neighbouring cells.
  int32_t edgeBetween(int32_t a, int32_t b) const;
  size_t edgeCount() const { return capacity_.size(); }

  int32_t capacity(int32_t e) const { return capacity_[e]; }
  int32_t usage(int32_t e) const { return usage_[e]; }
  void addUsage(const std::vector<int32_t>& edges, int delta);

  // Cost of one more net on edge e: (1 + history) * (1 + presentFactor * overflow it would add).
  double cost(int32_t e, double presentFactor) const;
  // Adds `step` to the history of every overflowed edge.
  void bumpHistory(double step);
  int64_t totalOverflow() const;   // sum over edges of max(0, usage - capacity), in tracks
  int64_t overflowedEdges() const;
  bool overflowed(int32_t e) const { return usage_[e] > capacity_[e]; }

 private:
  int nx_ = 0, ny_ = 0;
  std::vector<int32_t> capacity_;  // tracks, per edge id
  std::vector<int32_t> usage_;     // nets, per edge id
  std::vector<double> history_;    // cost units, per edge id
};

}  // namespace xroute
