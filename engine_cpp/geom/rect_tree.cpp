#include "geom/rect_tree.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace xroute {

namespace {

constexpr size_t kFanout = 16;  // rects per leaf, children per node

// Sort-tile-recursive order of `entries` (indices into `boxes`): sorted by centre x, cut into
// vertical slices of about sqrt(groups) groups, each slice sorted by centre y; ties by index.
void strOrder(std::vector<int32_t>& entries, const std::vector<Rect>& boxes) {
  auto cx = [&](int32_t i) { return int64_t(boxes[i].xlo) + boxes[i].xhi; };
  auto cy = [&](int32_t i) { return int64_t(boxes[i].ylo) + boxes[i].yhi; };
  std::sort(entries.begin(), entries.end(), [&](int32_t a, int32_t b) {
    return cx(a) != cx(b) ? cx(a) < cx(b) : a < b;
  });
  const size_t groups = (entries.size() + kFanout - 1) / kFanout;
  const size_t slices = size_t(std::ceil(std::sqrt(double(groups))));
  const size_t perSlice = ((groups + slices - 1) / slices) * kFanout;
  for (size_t s = 0; s < entries.size(); s += perSlice) {
    const auto lo = entries.begin() + s, hi = entries.begin() + std::min(entries.size(), s + perSlice);
    std::sort(lo, hi, [&](int32_t a, int32_t b) { return cy(a) != cy(b) ? cy(a) < cy(b) : a < b; });
  }
}

}  // namespace

RectTree::RectTree(std::vector<Rect> rects, const std::vector<int32_t>& tags) : rects_(std::move(rects)), tags_(tags) {
  if (rects_.empty()) return;
  if (tags_.size() != rects_.size()) tags_.clear();
  items_.resize(rects_.size());
  std::iota(items_.begin(), items_.end(), 0);
  strOrder(items_, rects_);
  // Leaves: consecutive runs of kFanout rects in STR order.
  std::vector<Node> level;
  for (size_t k = 0; k < items_.size(); k += kFanout) {
    Node n;
    n.first = int32_t(k);
    n.count = int32_t(std::min(kFanout, items_.size() - k));
    n.box = rects_[items_[k]];
    n.tag = tags_.empty() ? kMixed : tags_[items_[k]];
    for (int32_t j = n.first; j < n.first + n.count; ++j) {
      n.box.expandToInclude(rects_[items_[j]]);
      if (tags_.empty() || tags_[items_[j]] != n.tag) n.tag = kMixed;
    }
    level.push_back(n);
  }
  // Each level above: the level below in STR order (appended to nodes_), grouped by kFanout.
  while (true) {
    std::vector<Rect> boxes;
    for (const Node& n : level) boxes.push_back(n.box);
    std::vector<int32_t> order(level.size());
    std::iota(order.begin(), order.end(), 0);
    if (level.size() > 1) strOrder(order, boxes);
    const int32_t base = int32_t(nodes_.size());
    for (int32_t i : order) nodes_.push_back(level[i]);
    if (level.size() == 1) break;
    std::vector<Node> up;
    for (size_t k = 0; k < order.size(); k += kFanout) {
      Node n;
      n.leaf = false;
      n.first = base + int32_t(k);
      n.count = int32_t(std::min(kFanout, order.size() - k));
      n.box = nodes_[n.first].box;
      n.tag = nodes_[n.first].tag;
      for (int32_t j = n.first; j < n.first + n.count; ++j) {
        n.box.expandToInclude(nodes_[j].box);
        if (nodes_[j].tag != n.tag) n.tag = kMixed;
      }
      up.push_back(n);
    }
    level.swap(up);
  }
}

}  // namespace xroute
