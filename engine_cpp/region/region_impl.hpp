// Internal to RegionRouter (region_router.cpp: the public steps and the
// region's check; region_prepare.cpp: terminals, grid, marks, candidates;
// region_paths.cpp: routing a net, by the maze or along given paths).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "region/region_marks.hpp"
#include "region/region_router.hpp"

namespace xroute {

// One terminal of a candidate: a pin's access points in the box, a boundary
// terminal (both layers of a cut via), a chosen crossing, or a free crossing.
struct TermSpec {
  std::vector<Point> points;  // DBU
  std::vector<int> zs;        // routing index per point
  std::vector<int64_t> exitCost;  // free crossings: per point, distance from where the far side wants it
  bool joined = true;
  int32_t pinRef = -1;        // pin terminals
  // A pin's metal on other layers than its access points': nodes at an access point's x, y on a
  // layer where a rect of the pin holds a wire ending there (along the layer). Reaching one
  // reaches the pin; they are no access points (no flags, no owner): the maze judges them like
  // any node.
  std::vector<Point> touch;   // DBU
  std::vector<int> touchZs;   // routing index per point
  int32_t crossing = -1;      // free crossing terminals (iteration 0)
  // Rip-up: the conductor of the kept routing (or pin) the terminal lies on (keptConductors); -1
  // none. Terminals of one conductor are joined outside the box already (MazeTerminal::group).
  int32_t group = -1;
};

// A NONDEFAULTRULE net's extra node costs, cost units per node (MazeNet::ruleWire / ruleVia).
struct RuleCosts {
  NodeArray<int32_t> wire, via;
};

struct NetState {
  RegionNetTask task;
  std::vector<TermSpec> terms;
  NetRouting kept;  // rip-up: routing outside the box
  bool routed = false;
  RegionNetResult result;
  std::vector<std::vector<int32_t>> paths;  // the node paths its routing was made of
  NodeArray<uint8_t> guide;                 // guideMask, built on first use by moves()
  RuleCosts rule;                           // ruleCosts for moves(), as of ruleAt routed nets
  bool hasRule = false;
  std::vector<std::pair<int32_t, int64_t>> accessVia;  // accessViaCosts for moves(), as of ruleAt
  size_t ruleAt = std::numeric_limits<size_t>::max();
};

struct RegionRouter::Impl {
  const RouteContext& ctx;
  const RegionTask& task;
  const CrossingPlan* plan;
  const RegionRepairSeed* seed;
  std::unique_ptr<RegionGrid> grid;
  std::vector<NetState> nets;
  std::vector<NetCandidate> candidates;
  std::unordered_map<int32_t, ViaId> apVia;  // access node -> via the pin access chose
  std::vector<CrossingChoice> choices;
  int64_t rounds = 0;
  std::vector<int32_t> order;
  RoutedMetal routedMetal;

  Impl(const RouteContext& c, const RegionTask& t, const CrossingPlan* p, const RegionRepairSeed* s)
      : ctx(c), task(t), plan(p), seed(s) {}

  // region_prepare.cpp
  void prepare();
  void groupKeptTerminals(NetState& ns) const;
  // routedNearby of each candidate: nodes in its terminal box that new routing uses.
  void refreshNearby(std::vector<NetCandidate>& cands) const;

  // region_paths.cpp
  // The maze's view of a net: its terminals (joined ones first, so the tree
  // starts on metal) as grid nodes; termOfSpec maps them back to ns.terms.
  MazeNet mazeNet(const NetState& ns, std::vector<int32_t>& termOfSpec) const;
  void routeNet(int32_t index, MazeWorkspace& ws);
  void routeNetPaths(int32_t index, std::vector<std::vector<int32_t>> paths);
  void moves(int32_t index, int32_t node, std::array<MazeMove, kMoveCount>& out);

  // region_rule.cpp
  // Fills `out` for a net of a NONDEFAULTRULE from the metal marked around the box now; false
  // (nothing filled) for a net of the default rule.
  bool ruleCosts(int32_t net, RuleCosts& out) const;

 private:
  bool kept(size_t i) const { return seed && i < seed->keep.size() && seed->keep[i]; }
  const Rect& box() const { return task.region.box; }
  int routingIndex(LayerId l) const { return ctx.tech.layer(l).routingIndex; }
  int32_t nodeAt(Point p, int z) const;

  // region_prepare.cpp
  void gatherTerminals(std::vector<Dbu>& xs, std::vector<Dbu>& ys);
  void takeSeed();
  void freeCrossingNodes(const Crossing& c, TermSpec& spec);
  void pinTouches(TermSpec& spec) const;
  void markRouted();
  void markMarkers();
  void markTerminals(NetState& ns);
  NetCandidate makeCandidate(const NetState& ns) const;
  Rect guideSpan(int32_t net) const;

  // region_paths.cpp
  NodeArray<uint8_t> guideMask(int32_t net) const;
  // The net's access vias of another variant than the cut's default via, priced against other
  // nets' routed metal as they are (MazeNet::accessVia).
  std::vector<std::pair<int32_t, int64_t>> accessViaCosts(const NetState& ns) const;
  void addPathGeometry(int32_t net, const std::vector<int32_t>& path, NetRouting& out);
  void releaseLandings(const NetState& ns);
  // True when a wire end at `at` (a wire of width `width` along x when `alongX`, ending towards
  // `sign` = +1 / -1) should stop there: a rect of pin `pinRef` on `layer` holds `at` and reaches
  // from it into the wire's body, and no rect of it holds the end's usual half-width extension
  // (which then sticks out of the pin).
  bool pinHoldsEnd(int32_t pinRef, LayerId layer, Point at, bool alongX, int sign, Dbu width) const;
  void markNewRouting(int32_t net, const NetRouting& added);
  void applyPaths(NetState& ns, const MazeNet& mn, const std::vector<int32_t>& termOfSpec,
                  std::vector<std::vector<int32_t>> paths);
};

}  // namespace xroute
