// The flow's first pass (iteration 0), kept so that any of its regions can be
// opened again in the state the flow routed it in: the regions of the colours
// before its own committed, their crossing choices made, the rest unrouted.
// The pass runs once through routeDesign (so it is the flow's own, threads
// included); a snapshot of the design's routing and of the crossing choices
// is taken before each colour, and restoring one is a copy.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "db/design.hpp"
#include "loop/router.hpp"
#include "order/policy.hpp"
#include "region/crossing_plan.hpp"
#include "region/region_router.hpp"

namespace xroute {

inline constexpr int kColours = 4;  // regions of one colour never touch (regions.hpp)

class FirstPass {
 public:
  // Routes iteration 0 of `settings` (only that iteration) over `design` with `policy`.
  FirstPass(const Tech& tech, Design& design, const RouterSettings& settings, NetOrderPolicy& policy);

  // The regions with work, in the flow's order (colour, then region id), as the flow's tasks.
  int32_t size() const { return static_cast<int32_t>(tasks_.size()); }
  const RegionTask& task(int32_t i) const { return tasks_.at(i); }
  // Puts the design's routing back to what it was before regions of `colour` were routed
  // (0..3; kColours: after the whole pass). The caller rebuilds its routed indexes.
  void restore(Design& design, int colour) const;
  // The crossing plan as the regions of `colour` saw it (the choices of the colours before).
  CrossingPlan plan(int colour) const;
  // Iteration 0's report (wirelength, vias, markers of the whole design after the pass).
  const IterationReport& report() const { return report_; }

 private:
  void snapshot(const Design& design, int colour, const CrossingPlan& plan, const std::vector<RegionTask>& tasks);

  std::vector<RegionTask> tasks_;
  std::array<std::vector<NetRouting>, kColours + 1> routing_;  // per net, before each colour; [kColours] after
  std::array<std::vector<Crossing>, kColours> crossings_;     // the plan's crossings before each colour
  CrossingPlan layout_;                                        // the plan's region tables (crossings empty)
  IterationReport report_;
};

}  // namespace xroute
