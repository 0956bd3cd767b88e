// Routing one design region by region for a caller (the learning
// environments, `_engine.RoutingSession`): what every region shares (the
// route context, the maze costs, region ids), regions opened on a box or
// again from a kept first pass, each routed net by net, and their commit.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "db/database.hpp"
#include "loop/first_pass.hpp"
#include "region/crossing_plan.hpp"
#include "region/region_router.hpp"
#include "region/route_context.hpp"

namespace xroute {

// A region its caller routes net by net: one a session opened (it owns its
// task, crossings and router) or one the router lends to a policy for one
// call (the router only).
struct SessionRegion {
  RegionTask task;                       // an opened region's task
  CrossingPlan plan;                     // its free crossings
  std::unique_ptr<RegionRouter> owned;   // an opened region's router
  RegionRouter* router = nullptr;        // owned.get() or the lent router
  MazeWorkspace ws;                      // the maze's buffers for the caller's route calls
  bool committed = false;
};

class RoutingSession {
 public:
  // Prepares routing of `db` (pin access is computed here, once) with the maze's `costs` for the
  // regions it opens; db must outlive the session.
  RoutingSession(Database& db, int threads, const MazeCosts& costs = {});

  Database& database() const { return db_; }
  const GCellGrid& gcells() const { return ctx_->gcells; }
  // The router's partition into regions of size x size GCells.
  std::vector<Region> regions(int size, int offset) const;
  // Opens `box` on its own (region/standalone.hpp), prepared for routing.
  std::unique_ptr<SessionRegion> openRegion(const Rect& box, int iteration);
  // Routes iteration 0 of the design as the flow does, keeping what reopens its regions.
  std::unique_ptr<FirstPass> routeFirstPass(const RouterSettings& settings, NetOrderPolicy& policy);
  // Region i of `pass` in context: the design restored to before its colour.
  std::unique_ptr<SessionRegion> openFirstPassRegion(const FirstPass& pass, int32_t i);
  // The design's routing as `pass` had it before `colour` (kColours: after the pass).
  void restoreFirstPass(const FirstPass& pass, int colour);
  // Writes an opened region's new routing into the design (other open regions become stale).
  void commit(SessionRegion& region);

 private:
  Database& db_;
  std::unique_ptr<RouteContext> ctx_;
  MazeCosts costs_;
  int32_t regionsOpened_ = 0;  // the next opened region's id
};

}  // namespace xroute
