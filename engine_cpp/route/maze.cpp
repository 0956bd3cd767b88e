#include "route/maze.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <type_traits>
#include <utility>

namespace xroute {

namespace {

constexpr int64_t kInf = std::numeric_limits<int64_t>::max() / 4;

static_assert(bytesPerNode<decltype(MazeWorkspace::cost), decltype(MazeWorkspace::parent),
                           decltype(MazeWorkspace::visit), decltype(MazeWorkspace::inTree),
                           decltype(MazeWorkspace::terminalSlot)>() == kSearchBytesPerNode,
              "a per-node search array was added or changed: update kSearchBytesPerNode");

// The open list: (cost so far + heuristic, cost so far, node), least first. Among equal
// estimates the node nearer the tree (the lower cost so far) goes first. Which of several
// equal-cost paths a net gets changes the nets after it: with the heuristic's layer term, the node
// index alone (lower layers first) measured 0.75% worse on ispd18_test1 (contest score 294,050
// against 291,944) and the higher cost so far first 0.5% worse (293,405).
//
// A radix heap on the estimate over the workspace's storage (MazeOpenStorage, kept between rounds
// and nets): `least_` is a 4-ary heap, in the whole order, of the entries whose estimate is at most
// `last_` (the least estimate seen when it was last refilled); bucket b holds those above it whose
// highest bit that differs from `last_` is bit b. When `least_` runs dry, the lowest bucket's least
// estimate becomes `last_` and its entries move down (those at `last_` into the heap). Entries above
// `last_` are never less than any in the heap, so it pops the least entry of all, as one heap
// would; with a consistent heuristic the estimates popped never fall, so each entry moves down a
// few buckets at most instead of sifting through a heap of every open node. An estimate below
// `last_` (costs that make the heuristic inconsistent) joins the heap and still pops in order.
// Packed, an entry is 16 bytes: the estimate, then the heuristic's complement (a lower cost so far
// is a higher heuristic at the same estimate), then the node, compared as one 128-bit number; that
// needs the heuristic to fit in 32 bits (Search::run checks the region's bound), else the entries
// are MazeOpenEntry.
template <bool kPacked>
class OpenList {
 public:
  using Entry = std::conditional_t<kPacked, MazeOpenKey, MazeOpenEntry>;
  explicit OpenList(MazeOpenStorage<Entry>& storage) : least_(storage.least), buckets_(storage.buckets) {
    least_.clear();
    for (std::vector<Entry>& b : buckets_) b.clear();
  }
  bool empty() const { return least_.empty() && mask_ == 0; }
  // estimate - cost (the heuristic) is at least 0, and below 2^32 when packed.
  void push(int64_t estimate, int64_t cost, int32_t node) {
    Entry e;
    if constexpr (kPacked) {
      const uint64_t low = (uint64_t(0xFFFFFFFFu - uint32_t(estimate - cost)) << 32) | uint32_t(node);
      e = (MazeOpenKey(biased(estimate)) << 64) | low;
    } else {
      e = MazeOpenEntry{estimate, cost, node};
    }
    place(e);
  }
  // Removes the least entry and returns its node (the list is not empty).
  int32_t pop() {
    if (least_.empty()) refill();
    const int32_t top = nodeOf(least_[0]);
    const Entry last = least_.back();
    least_.pop_back();
    const size_t n = least_.size();
    if (n == 0) return top;
    size_t i = 0;
    while (true) {
      const size_t c = 4 * i + 1;
      if (c >= n) break;
      size_t best = c;
      const size_t end = std::min(c + 4, n);
      for (size_t k = c + 1; k < end; ++k)
        if (less(least_[k], least_[best])) best = k;
      if (!less(least_[best], last)) break;
      least_[i] = least_[best];
      i = best;
    }
    least_[i] = last;
    return top;
  }

 private:
  static uint64_t biased(int64_t estimate) { return uint64_t(estimate) ^ (uint64_t(1) << 63); }  // order kept
  static uint64_t keyOf(const Entry& e) {
    if constexpr (kPacked) return static_cast<uint64_t>(e >> 64);
    else return biased(e.estimate);
  }
  static int32_t nodeOf(const Entry& e) {
    if constexpr (kPacked) return static_cast<int32_t>(static_cast<uint32_t>(e));
    else return e.node;
  }
  static bool less(const Entry& a, const Entry& b) {
    if constexpr (kPacked) {
      return a < b;
    } else {
      if (a.estimate != b.estimate) return a.estimate < b.estimate;
      if (a.cost != b.cost) return a.cost < b.cost;
      return a.node < b.node;
    }
  }
  void place(const Entry& e) {
    const uint64_t k = keyOf(e);
    if (k <= last_) {
      heapPush(e);
      return;
    }
    const int b = 63 - __builtin_clzll(k ^ last_);
    buckets_[b].push_back(e);
    mask_ |= uint64_t(1) << b;
  }
  void heapPush(const Entry& e) {
    size_t i = least_.size();
    least_.push_back(e);
    while (i > 0) {
      const size_t p = (i - 1) / 4;
      if (!less(e, least_[p])) break;
      least_[i] = least_[p];
      i = p;
    }
    least_[i] = e;
  }
  void refill() {
    const int b = __builtin_ctzll(mask_);
    std::vector<Entry>& from = buckets_[b];
    mask_ &= ~(uint64_t(1) << b);
    uint64_t m = keyOf(from[0]);
    for (const Entry& e : from) m = std::min(m, keyOf(e));
    last_ = m;
    // Every entry lands in a lower bucket than b, or in the heap: `from` is not written meanwhile.
    for (const Entry& e : from) place(e);
    from.clear();
  }

  std::vector<Entry>& least_;
  std::array<std::vector<Entry>, 64>& buckets_;
  uint64_t mask_ = 0;  // bit b: buckets_[b] holds entries
  uint64_t last_ = 0;
};

// A terminal node of the net being routed: its terminal and the cost of ending there.
struct TerminalSlot {
  int32_t terminal;
  int64_t exitCost;
};

using Sparse = RegionGrid::Sparse;

class Search {
 public:
  Search(const RegionGrid& g, const MazeCosts& c, const MazeNet& net, MazeWorkspace& ws)
      : g_(g), c_(c), net_(net), ws_(ws) {}

  int run(std::vector<std::vector<int32_t>>& paths);

  // Every edge leaving u: fn(v, step cost, direction, v's point, v's layer) with direction a
  // MazeDirection.
  template <class Fn>
  void forEachEdge(int32_t u, Fn&& fn) const;

 private:
  // sv: v's sparse fields.
  int64_t wireNodeCost(int32_t v, const Sparse& sv) const;
  int64_t viaNodeCost(int32_t v, const Sparse& sv) const;
  // Entering v, a landing reserved for another net's access via: the sole-landing penalty where it
  // is its pin's only via point (kSoleLanding) and larger, else the landing penalty.
  int64_t landingCost(int32_t v) const {
    return (g_.flags[v] & kSoleLanding) ? std::max(c_.landingPenalty, c_.soleLandingPenalty) : c_.landingPenalty;
  }
  int64_t guideFactor(int32_t v) const {
    return (net_.inGuide && !(*net_.inGuide)[v]) ? c_.outOfGuideFactor : 1;
  }
  // As the contest scorer counts them: a wire step is out of its layer's guide
  // for the part beyond the guide's edge (half when one end is out, the same
  // either way), a via when its centre is out on either of its layers.
  int64_t wireGuideLength(int64_t len, int32_t u, int32_t v) const {
    return len * (guideFactor(u) + guideFactor(v)) / 2;
  }
  int64_t viaGuideFactor(int32_t u, int32_t v) const { return std::max(guideFactor(u), guideFactor(v)); }
  // A planar step u -> v in direction `dir` leaves u that way and v the
  // opposite way: at the net's own access points, a way pin access did not
  // find legal (its stub that way adds a marker) costs like a fixed shape.
  // su, sv: u's and v's sparse fields.
  int64_t exitCost(const Sparse& su, const Sparse& sv, int dir) const {
    static constexpr uint8_t kOut[kMoveCount] = {0, 0, 8, 16, 2, 4};   // AccessDir bit leaving that way
    static constexpr uint8_t kBack[kMoveCount] = {0, 0, 16, 8, 4, 2};  // ... and arriving from it
    int64_t cost = 0;
    if (su.net == net_.net && !(su.exits & kOut[dir])) cost += c_.fixedPenalty;
    if (sv.net == net_.net && !(sv.exits & kBack[dir])) cost += c_.fixedPenalty;
    return cost;
  }
  // At the node at point p on layer z.
  int64_t heuristic(Point p, int z) const;
  // One round: from the tree to the nearest unreached terminal node, or -1.
  template <bool kPacked>
  int32_t searchRound(const std::vector<int32_t>& sources, bool withExitCost);
  // Joined terminals (one conductor: a pin, the end of kept routing) with a node
  // on the tree are reached and bring all their nodes along, whether a path hit
  // them or they share a node with another terminal (terminalOf names one owner
  // per node, so a search never hits the second). A free crossing's
  // alternatives are reached only by the path node that hits one of them. So are the other
  // terminals of a reached terminal's group (MazeTerminal::group).
  void reachShared(std::vector<int32_t>& tree);
  bool groupReached(int32_t group) const {
    for (size_t t = 0; t < net_.terminals.size(); ++t) {
      const MazeTerminal& term = net_.terminals[t];
      if (reached_[t] && term.joined && term.group == group && !term.nodes.empty()) return true;
    }
    return false;
  }
  template <class Open>
  void relax(int32_t u, int32_t v, int64_t step, Point q, int z, Open& open);

  const RegionGrid& g_;
  const MazeCosts& c_;
  const MazeNet& net_;
  MazeWorkspace& ws_;
  bool seen(int32_t v) const { return ws_.visit[v] >= ws_.stamp; }
  bool closed(int32_t v) const { return ws_.visit[v] == ws_.stamp + 1; }
  // The terminal whose node v is (-1: none) and the cost of ending there.
  int32_t terminalOf(int32_t v) const {
    const int32_t k = ws_.terminalSlot[v];
    return k < 0 ? -1 : slots_[k].terminal;
  }
  int64_t exitCostAt(int32_t v) const {
    const int32_t k = ws_.terminalSlot[v];
    return k < 0 ? 0 : slots_[k].exitCost;
  }

  std::vector<uint8_t> reached_;     // per terminal
  std::vector<TerminalSlot> slots_;  // per node of a terminal (terminalSlot): the first terminal naming it
  std::vector<Rect> termBox_;        // per terminal, DBU
  std::vector<std::pair<int, int>> termLayers_;  // per terminal, its nodes' lowest and highest layer
  struct LiveTerminal {
    Rect box;
    int zlo, zhi;
  };
  std::vector<LiveTerminal> live_;  // the round's unreached terminals with nodes: box and layers
};

template <class Fn>
void Search::forEachEdge(int32_t u, Fn&& fn) const {
  const int nx = g_.nx(), ny = g_.ny(), nz = g_.nz();
  const int32_t plane = nx * ny;
  const int z = u / plane;
  const int y = (u - z * plane) / nx;
  const int x = u - z * plane - y * nx;
  const Point p{g_.xs()[x], g_.ys()[y]};
  const bool h = g_.horizontal(z);
  const Sparse& su = g_.sparse(u);
  // Along the preferred direction (both ends on the track).
  if (g_.flags[u] & kOnTrack) {
    for (int d = -1; d <= 1; d += 2) {
      const int xx = h ? x + d : x, yy = h ? y : y + d;
      if (xx < 0 || xx >= nx || yy < 0 || yy >= ny) continue;
      const int32_t v = h ? u + d : u + d * nx;
      if (!(g_.flags[v] & kOnTrack)) continue;
      const Point q{g_.xs()[xx], g_.ys()[yy]};
      const int64_t len = (std::abs(int64_t(q.x) - p.x) + std::abs(int64_t(q.y) - p.y)) * c_.wireUnit;
      const int dir = h ? (d > 0 ? kMoveEast : kMoveWest) : (d > 0 ? kMoveNorth : kMoveSouth);
      const Sparse& sv = g_.sparse(v);
      fn(v, wireGuideLength(len, u, v) * (z == 0 ? c_.bottomLayerFactor : 1) + wireNodeCost(v, sv) + exitCost(su, sv, dir),
         dir, q, z);
    }
  }
  // Against it, to the next existing node.
  for (int d = -1; d <= 1; d += 2) {
    int xx = x, yy = y;
    const int32_t v = g_.wrongWayNeighbour(xx, yy, z, d);
    if (v < 0) continue;
    const Point q{g_.xs()[xx], g_.ys()[yy]};
    const int64_t len = (std::abs(int64_t(q.x) - p.x) + std::abs(int64_t(q.y) - p.y)) * c_.wireUnit;
    const int dir = h ? (d > 0 ? kMoveNorth : kMoveSouth) : (d > 0 ? kMoveEast : kMoveWest);
    const Sparse& sv = g_.sparse(v);
    fn(v, wireGuideLength(len, u, v) * c_.wrongWayFactor * (z == 0 ? c_.bottomLayerFactor : 1) + wireNodeCost(v, sv) +
              exitCost(su, sv, dir),
       dir, q, z);
  }
  // Vias.
  for (int d = -1; d <= 1; d += 2) {
    const int zz = z + d;
    if (zz < 0 || zz >= nz) continue;
    const int32_t v = u + d * plane;
    if (!g_.flags[v]) continue;
    const Sparse& sv = g_.sparse(v);
    const int32_t lower = d > 0 ? u : v;
    const Sparse& sl = d > 0 ? su : sv;
    int64_t cut = 0;
    if (g_.cutUse[lower] && g_.cutUseOwner[lower] != net_.net && sl.net != net_.net) {
      cut = int64_t(g_.cutUse[lower]) * c_.usePenalty;
    }
    fn(v, c_.viaCost * viaGuideFactor(u, v) + viaNodeCost(u, su) + viaNodeCost(v, sv) + cut, d > 0 ? kMoveUp : kMoveDown,
       p, zz);
  }
}

int64_t Search::wireNodeCost(int32_t v, const Sparse& sv) const {
  int64_t cost = int64_t(g_.markerCost[v]) * c_.markerUnit;
  if (net_.ruleWire) cost += (*net_.ruleWire)[v];
  if (sv.net == net_.net) {
    // The net's own access point: pin access checked it against fixed
    // shapes only; other nets' routing (their access vias) still counts.
    if (g_.wireUse[v] && g_.wireUseOwner[v] != net_.net) cost += int64_t(g_.wireUse[v]) * c_.usePenalty;
    return cost;
  }
  if (sv.net >= 0) cost += c_.reservePenalty;
  const int32_t reserved = sv.reserved;
  if (reserved >= 0 && reserved != net_.net && !(g_.flags[v] & kReleased)) cost += landingCost(v);
  // The landing of the net's own access via: pin access checked the via's metal there exactly; a
  // wire reaching it ends on that metal, and the nodes it passed paid their own footprint. The
  // footprint's estimate for a wire along the track (beside a wide stripe, a long parallel run)
  // made a one-track jog into the landing cost like a short, so the route went up a layer and
  // down again (ispd19_test1: 2 vias a pin on the big nets where TritonRoute jogs).
  const int32_t fo = g_.fixedOwner[v];
  if (fo != kOwnerNone && fo != net_.net && reserved != net_.net) cost += c_.fixedPenalty;
  if (g_.wireUse[v] && g_.wireUseOwner[v] != net_.net) cost += int64_t(g_.wireUse[v]) * c_.usePenalty;
  return cost;
}

int64_t Search::viaNodeCost(int32_t v, const Sparse& sv) const {
  int64_t cost = int64_t(g_.markerCost[v]) * c_.markerUnit;
  if (net_.ruleVia) cost += (*net_.ruleVia)[v];
  if (net_.accessVia && (g_.flags[v] & kAccessVia)) {
    for (const auto& [node, extra] : *net_.accessVia)
      if (node == v) cost += extra;
  }
  if (sv.net == net_.net) {
    if (g_.viaUse[v] && g_.viaUseOwner[v] != net_.net) cost += int64_t(g_.viaUse[v]) * c_.usePenalty;
    // Pin access checked the via only where it offers one (kAccessVia); a
    // via at a point it left planar-only meets the footprint like any via.
    const int32_t fo = g_.viaFixedOwner[v];
    if (!(g_.flags[v] & kAccessVia) && fo != kOwnerNone && fo != net_.net) cost += c_.fixedPenalty;
    return cost;
  }
  if (sv.net >= 0) cost += c_.reservePenalty;
  const int32_t reserved = sv.reserved;
  if (reserved >= 0 && reserved != net_.net) cost += landingCost(v);
  // Above the net's own access point, pin access has checked the via
  // exactly; the footprint's bloated estimate would only forbid it.
  const int32_t fo = g_.viaFixedOwner[v];
  if (fo != kOwnerNone && fo != net_.net && reserved != net_.net) cost += c_.fixedPenalty;
  if (g_.viaUse[v] && g_.viaUseOwner[v] != net_.net) cost += int64_t(g_.viaUse[v]) * c_.usePenalty;
  return cost;
}

// A lower bound on the cost from v to the nearest unreached terminal: the planar distance to its
// nodes' box and a via for each layer between v and its nodes' layers (a wire step costs at least
// its length in wire units, a via at least viaCost). It is consistent, so the search stays exact; the layer term
// cuts the nodes expanded (2 threads, paired runs, median wall: ispd18_test1 0.89x of 17.1 s,
// ispd19_test1 0.91x of 121.7 s).
int64_t Search::heuristic(Point p, int z) const {
  int64_t best = kInf;
  for (const LiveTerminal& t : live_) {
    const Rect& b = t.box;
    const int64_t dx = p.x < b.xlo ? b.xlo - p.x : (p.x > b.xhi ? p.x - b.xhi : 0);
    const int64_t dy = p.y < b.ylo ? b.ylo - p.y : (p.y > b.yhi ? p.y - b.yhi : 0);
    const int64_t dz = z < t.zlo ? t.zlo - z : (z > t.zhi ? z - t.zhi : 0);
    best = std::min(best, (dx + dy) * c_.wireUnit + dz * c_.viaCost);
  }
  return best == kInf ? 0 : best;
}

template <class Open>
void Search::relax(int32_t u, int32_t v, int64_t step, Point q, int z, Open& open) {
  if (closed(v)) return;
  int64_t nc = ws_.cost[u] + step;
  const int32_t k = ws_.terminalSlot[v];
  if (k >= 0 && !reached_[slots_[k].terminal]) nc += slots_[k].exitCost;
  if (seen(v) && ws_.cost[v] <= nc) return;
  ws_.visit[v] = ws_.stamp;
  ws_.cost[v] = nc;
  ws_.parent[v] = u;
  open.push(nc + heuristic(q, z), nc, v);
}

template <bool kPacked>
int32_t Search::searchRound(const std::vector<int32_t>& sources, bool withExitCost) {
  if (ws_.stamp >= std::numeric_limits<uint32_t>::max() - 2) {  // stamps used up: start again
    std::fill(ws_.visit.begin(), ws_.visit.end(), 0);
    ws_.stamp = 0;
  }
  ws_.stamp += 2;
  live_.clear();
  for (size_t t = 0; t < termBox_.size(); ++t)
    if (!reached_[t]) live_.push_back({termBox_[t], termLayers_[t].first, termLayers_[t].second});
  OpenList<kPacked> open([this]() -> auto& {
    if constexpr (kPacked) return ws_.packedOpen;
    else return ws_.open;
  }());
  for (int32_t s : sources) {
    ws_.visit[s] = ws_.stamp;
    ws_.cost[s] = withExitCost ? exitCostAt(s) : 0;
    ws_.parent[s] = -1;
    open.push(ws_.cost[s] + heuristic(g_.point(s), g_.zOf(s)), ws_.cost[s], s);
  }
  while (!open.empty()) {
    const int32_t u = open.pop();
    if (closed(u)) continue;
    ws_.visit[u] = ws_.stamp + 1;
    const int32_t t = terminalOf(u);
    if (t >= 0 && !reached_[t]) return u;

    forEachEdge(u, [&](int32_t v, int64_t step, int, Point q, int z) { relax(u, v, step, q, z, open); });
  }
  return -1;
}

void Search::reachShared(std::vector<int32_t>& tree) {
  for (bool grew = true; grew;) {
    grew = false;
    for (size_t t = 0; t < net_.terminals.size(); ++t) {
      const MazeTerminal& term = net_.terminals[t];
      if (reached_[t] || !term.joined) continue;
      bool touches = term.group >= 0 && groupReached(term.group);
      for (int32_t v : term.nodes) touches = touches || ws_.inTree[v] == ws_.treeStamp;
      if (!touches) continue;
      reached_[t] = 1;
      grew = true;  // a terminal of its group before it in the list is reached now too
      for (int32_t w : term.nodes) {
        if (ws_.inTree[w] == ws_.treeStamp) continue;
        ws_.inTree[w] = ws_.treeStamp;
        tree.push_back(w);
      }
    }
  }
}

int Search::run(std::vector<std::vector<int32_t>>& paths) {
  const size_t n = g_.size();
  if (ws_.cost.size() != n) {
    // A bigger region: the old arrays go first (two generations at once would double them).
    // A smaller one reuses them, which spares the kernel mapping and clearing new pages.
    if (n > ws_.cost.capacity()) ws_ = MazeWorkspace{};
    ws_.cost.assign(n, 0);
    ws_.parent.assign(n, -1);
    ws_.visit.assign(n, 0);
    ws_.inTree.assign(n, 0);
    ws_.terminalSlot.assign(n, -1);
    ws_.stamp = 0;
    ws_.treeStamp = 0;
  }
  const size_t nt = net_.terminals.size();
  if (nt < 2) return 0;
  reached_.assign(nt, 0);
  termBox_.assign(nt, Rect{});
  termLayers_.assign(nt, {0, 0});
  slots_.clear();
  for (size_t t = 0; t < nt; ++t) {
    bool first = true;
    const MazeTerminal& term = net_.terminals[t];
    for (size_t k = 0; k < term.nodes.size(); ++k) {
      const int32_t v = term.nodes[k];
      if (ws_.terminalSlot[v] < 0) {
        ws_.terminalSlot[v] = static_cast<int32_t>(slots_.size());
        slots_.push_back({static_cast<int32_t>(t), k < term.exitCost.size() ? term.exitCost[k] : 0});
      }
      const Point p = g_.point(v);
      const Rect r{p.x, p.y, p.x, p.y};
      const int z = g_.zOf(v);
      if (first) {
        termBox_[t] = r;
        termLayers_[t] = {z, z};
      } else {
        termBox_[t].expandToInclude(r);
        termLayers_[t] = {std::min(termLayers_[t].first, z), std::max(termLayers_[t].second, z)};
      }
      first = false;
    }
    if (net_.terminals[t].nodes.empty()) reached_[t] = 1;  // nothing to reach
  }
  // The heuristic's largest value in this region: the box's half perimeter and a via a layer.
  const Rect& box = g_.box();
  const double bound = (double(box.xhi) - box.xlo + double(box.yhi) - box.ylo) * double(c_.wireUnit) +
                       double(g_.nz()) * double(c_.viaCost);
  const bool packed = c_.wireUnit >= 0 && c_.viaCost >= 0 && bound < double(0xFFFFFFFFu);
  ++ws_.treeStamp;
  std::vector<int32_t> tree;
  // The first terminal with nodes starts the tree.
  size_t start = 0;
  while (start < nt && net_.terminals[start].nodes.empty()) ++start;
  int unreached = 0;
  if (start < nt) {
    reached_[start] = 1;
    tree = net_.terminals[start].nodes;
    const bool alternatives = !net_.terminals[start].joined;
    if (!alternatives) {
      for (int32_t v : tree) ws_.inTree[v] = ws_.treeStamp;
      reachShared(tree);
    }
    bool firstRound = true;
    while (std::find(reached_.begin(), reached_.end(), 0) != reached_.end()) {
      const bool withExit = firstRound && alternatives;
      const int32_t hit = packed ? searchRound<true>(tree, withExit) : searchRound<false>(tree, withExit);
      if (hit < 0) break;
      std::vector<int32_t> path;
      for (int32_t v = hit; v >= 0; v = ws_.parent[v]) path.push_back(v);
      std::reverse(path.begin(), path.end());
      if (firstRound && alternatives) tree.clear();  // keep only the alternative actually used
      firstRound = false;
      for (int32_t v : path) {
        if (ws_.inTree[v] != ws_.treeStamp) {
          ws_.inTree[v] = ws_.treeStamp;
          tree.push_back(v);
        }
        const int32_t t = terminalOf(v);
        if (t >= 0 && !net_.terminals[t].joined) reached_[t] = 1;  // a free crossing: this alternative
      }
      reachShared(tree);
      paths.push_back(std::move(path));
    }
  }
  for (size_t t = 0; t < nt; ++t) {
    if (!reached_[t]) ++unreached;
    for (int32_t v : net_.terminals[t].nodes) ws_.terminalSlot[v] = -1;
  }
  return unreached;
}

}  // namespace

void mazeMoves(const RegionGrid& grid, const MazeCosts& costs, const MazeNet& net, int32_t node,
               std::array<MazeMove, kMoveCount>& out) {
  MazeWorkspace unused;
  out.fill(MazeMove{});
  Search(grid, costs, net, unused).forEachEdge(node, [&](int32_t v, int64_t step, int dir, Point, int) {
    out[dir] = MazeMove{v, step};
  });
}

int routeMaze(const RegionGrid& grid, const MazeCosts& costs, const MazeNet& net, MazeWorkspace& ws,
              std::vector<std::vector<int32_t>>& paths) {
  return Search(grid, costs, net, ws).run(paths);
}

}  // namespace xroute
