#include "loop/session.hpp"

#include <algorithm>

#include "loop/regions.hpp"
#include "region/standalone.hpp"

namespace xroute {

RoutingSession::RoutingSession(Database& db, int threads, const MazeCosts& costs)
    : db_(db), ctx_(std::make_unique<RouteContext>(db.tech, db.design, std::max(1, threads))), costs_(costs) {}

std::vector<Region> RoutingSession::regions(int size, int offset) const {
  return partitionRegions(ctx_->gcells, size, offset);
}

std::unique_ptr<SessionRegion> RoutingSession::openRegion(const Rect& box, int iteration) {
  auto r = std::make_unique<SessionRegion>();
  r->task = makeStandaloneTask(*ctx_, box, regionsOpened_++, iteration, designCosts(costs_, *ctx_),
                               r->plan);
  r->owned = std::make_unique<RegionRouter>(*ctx_, r->task, &r->plan);
  r->router = r->owned.get();
  r->router->prepare();
  return r;
}

std::unique_ptr<FirstPass> RoutingSession::routeFirstPass(const RouterSettings& settings, NetOrderPolicy& policy) {
  auto pass = std::make_unique<FirstPass>(db_.tech, db_.design, settings, policy);
  ctx_->rebuildRoutedIndex();
  return pass;
}

std::unique_ptr<SessionRegion> RoutingSession::openFirstPassRegion(const FirstPass& pass, int32_t i) {
  auto r = std::make_unique<SessionRegion>();
  const RegionTask& task = pass.task(i);
  pass.restore(ctx_->design, task.region.color);
  ctx_->rebuildRoutedIndex();
  r->task = task;
  r->plan = pass.plan(task.region.color);
  r->owned = std::make_unique<RegionRouter>(*ctx_, r->task, &r->plan);
  r->router = r->owned.get();
  r->router->prepare();
  return r;
}

void RoutingSession::restoreFirstPass(const FirstPass& pass, int colour) {
  pass.restore(ctx_->design, colour);
  ctx_->rebuildRoutedIndex();
}

void RoutingSession::commit(SessionRegion& region) {
  RegionResult res = region.router->finish();
  commitRegion(ctx_->tech, ctx_->design, region.task.region.box, res);
  ctx_->rebuildRoutedIndex();
  region.committed = true;
}

}  // namespace xroute
