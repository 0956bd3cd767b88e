// Routing one region: build its grid, mark what is already there, gather
// each candidate net's terminals, then route the nets one at a time in the
// order its caller gives (a net-order policy: order/policy.hpp routeInOrder).
// Steppable (prepare / routeNet / finish) so that a learning environment can
// choose every next net.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "drc/drc.hpp"
#include "grid/region_grid.hpp"
#include "region/candidate.hpp"
#include "region/clip.hpp"
#include "region/crossing_plan.hpp"
#include "region/region.hpp"
#include "region/region_marks.hpp"
#include "region/route_context.hpp"
#include "route/maze.hpp"

namespace xroute {

// What one net does in a region.
struct RegionNetTask {
  int32_t net = -1;
  bool ripup = false;                     // remove its routing inside the box first
  std::vector<int32_t> pins;              // pinRefs whose access points inside the box are terminals
  std::vector<int32_t> crossings;         // iteration 0: CrossingPlan ids touching this region
  // Rip-up: the boxes of the other regions that reroute this net at the same time. Its routing
  // there may change, so it joins none of the terminals here (TermSpec::group).
  std::vector<Rect> reroutedElsewhere;
};

struct RegionTask {
  Region region;
  int32_t iteration = 0;
  std::vector<RegionNetTask> nets;
  std::vector<MarkerCost> markers;
  MazeCosts costs;
  int repairRounds = 0;         // finishWithRepairs: check-and-reroute rounds inside the region before it is committed
  int64_t repairPenalty = 0;    // cost units per node near a marker of a repair round, times the round number
};

struct RegionNetResult {
  int32_t net = -1;
  bool ripup = false;
  NetRouting added;     // new routing inside the box
  int unreached = 0;    // terminals the maze could not reach
  bool routed = false;
};

struct CrossingChoice {
  int32_t crossing = -1;
  Point at;
  int z = -1;
};

struct RegionResult {
  int32_t regionId = -1;
  std::vector<RegionNetResult> nets;
  std::vector<CrossingChoice> crossingChoices;
  int64_t gridNodes = 0;
  int64_t mazeRounds = 0;
  std::vector<int32_t> order;   // candidate indices in the order they were routed
  int repairRounds = 0;         // repair rounds run inside the region
};

// What a repair round starts from: the result of the previous round, the
// candidates whose routing it keeps (their metal becomes other nets' metal),
// and the markers so far as extra node costs.
struct RegionRepairSeed {
  const RegionResult* previous = nullptr;
  std::vector<uint8_t> keep;               // per candidate (task.nets order)
  std::vector<MarkerCost> markers;
};

class RegionRouter {
 public:
  // `plan` is read for iteration 0 crossings (may be null for later iterations).
  RegionRouter(const RouteContext& ctx, const RegionTask& task, const CrossingPlan* plan,
               const RegionRepairSeed* seed = nullptr);
  ~RegionRouter();

  // Builds the grid and the candidates; call once before routing.
  void prepare();
  const RegionGrid& grid() const;
  const std::vector<NetCandidate>& candidates() const;
  bool isRouted(int32_t candidate) const;
  // Candidate indices in the order they were routed so far.
  const std::vector<int32_t>& routedOrder() const;
  // Routes candidate `index` (an index into candidates()).
  void routeNet(int32_t index, MazeWorkspace& ws);
  // Routes candidate `index` along the caller's node paths (each step one
  // edge of the maze's grid graph; throws std::invalid_argument otherwise)
  // through the same commit as the maze's paths: geometry, min-area fix, marks.
  void routeNetPaths(int32_t index, std::vector<std::vector<int32_t>> paths);
  // The node paths a routed candidate's routing was made of (empty before).
  const std::vector<std::vector<int32_t>>& paths(int32_t candidate) const;
  // A candidate's terminals as the maze sees them (grid nodes, joined terminals first).
  std::vector<std::vector<int32_t>> terminalNodes(int32_t candidate) const;
  // Per terminal of terminalNodes: true when its nodes are one conductor (all join the tree once
  // one is reached), false for alternatives (a free crossing: only the node reached joins).
  std::vector<bool> terminalJoined(int32_t candidate) const;
  // The six maze moves from `node` for the candidate's net (see mazeMoves).
  void moves(int32_t candidate, int32_t node, std::array<MazeMove, kMoveCount>& out) const;
  // The candidates not routed yet (their features as they are now) and their indices in candidates().
  std::vector<NetCandidate> unrouted(std::vector<int32_t>& index) const;
  // All candidates with their features as they are now (candidates() has routedNearby = 0).
  std::vector<NetCandidate> candidatesNow() const;
  // An independent copy of the region in its current state (grid, routed nets, choices): a
  // search routes trial orders on copies and keeps the original as it was.
  std::unique_ptr<RegionRouter> clone() const;
  // Takes the state of `other`, a clone of this region routed further (a search's best trial).
  void adopt(std::unique_ptr<RegionRouter> other);
  const RouteContext& context() const;
  RegionInfo info() const;
  // The new routing of a candidate so far (empty until routed).
  const RegionNetResult& result(int32_t candidate) const;
  // Design-rule markers inside the box with the new routing in place of the
  // ripped-up routing (fixed-only markers skipped).
  std::vector<Marker> check() const;
  RegionResult finish();
  // finish() after the task's repair rounds (RegionTask::repairRounds): each round rips up the
  // region's nets named in the markers of the round before and reroutes them (in their first
  // order) around everything else, with the markers found so far as rising node costs; the round
  // with the fewest markers is kept. Call once every candidate is routed.
  RegionResult finishWithRepairs(MazeWorkspace& ws);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Applies a region's result to the design: ripped-up nets lose their routing
// inside the box, every routed net gains its new routing.
void commitRegion(const Tech& tech, Design& design, const Rect& box, const RegionResult& result);

}  // namespace xroute
