// A static R-tree of rectangles for window queries, packed sort-tile-recursive
// (STR): leaves of kFanout rects, each level tiled by centre x, then y. Unlike
// BoxIndex's uniform grid, a query stays output-sensitive when many long rects
// crowd one place (thousands of overlapping copies of a wire, each shifted by
// one DBU): it visits only the nodes whose box meets the window. Each node also
// keeps the tag its rects share (a net id), if they all share one, so that a
// query can skip whole subtrees of one tag. Queries are const and keep no
// state: they may run concurrently.
#pragma once

#include <cstdint>
#include <vector>

#include "geom/geom.hpp"

namespace xroute {

class RectTree {
 public:
  RectTree() = default;
  // `tags`, when given, has one value per rect (see queryExcept).
  explicit RectTree(std::vector<Rect> rects, const std::vector<int32_t>& tags = {});

  size_t size() const { return rects_.size(); }

  // Calls visit(id) once for every rect that intersects `window` (closed
  // rects: touching counts), in no particular order.
  template <class Visit>
  void query(const Rect& window, Visit&& visit) const {
    walk(window, kNoTag, visit);
  }
  // The same, leaving out the rects tagged `tag` (all of them, whatever
  // subtree they are in); a subtree all of whose rects carry `tag` is skipped whole.
  template <class Visit>
  void queryExcept(const Rect& window, int32_t tag, Visit&& visit) const {
    walk(window, tag, visit);
  }

 private:
  static constexpr int32_t kNoTag = INT32_MIN;      // a tag no rect has: nothing left out
  static constexpr int32_t kMixed = INT32_MIN + 1;  // a node whose rects carry several tags
  struct Node {
    Rect box;                 // DBU, the bounding box of the node's rects
    int32_t first = 0;        // a leaf: its rect ids are items_[first, first + count); else child nodes
    int32_t count = 0;
    int32_t tag = kMixed;     // the tag all its rects share, or kMixed
    bool leaf = true;
  };

  template <class Visit>
  void walk(const Rect& w, int32_t except, Visit& visit) const;

  std::vector<Rect> rects_;     // DBU, by id
  std::vector<int32_t> tags_;   // by id; empty: every rect kMixed
  std::vector<int32_t> items_;  // rect ids in leaf order
  std::vector<Node> nodes_;     // leaves first, then each level above; the root last
};

template <class Visit>
void RectTree::walk(const Rect& w, int32_t except, Visit& visit) const {
  if (nodes_.empty()) return;
  int32_t stack[64 * 16];  // depth <= log16(2^31) < 8 levels of at most kFanout children each
  int top = 0;
  stack[top++] = int32_t(nodes_.size()) - 1;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!n.box.overlaps(w) || (except != kNoTag && n.tag == except)) continue;
    if (n.leaf) {
      for (int32_t k = n.first; k < n.first + n.count; ++k) {
        const int32_t id = items_[k];
        if (rects_[id].overlaps(w) && (except == kNoTag || tags_.empty() || tags_[id] != except)) visit(id);
      }
    } else {
      for (int32_t k = n.first; k < n.first + n.count; ++k) stack[top++] = k;
    }
  }
}

}  // namespace xroute
