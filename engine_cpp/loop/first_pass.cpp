#include "loop/first_pass.hpp"

#include <stdexcept>
#include <string>

namespace xroute {

FirstPass::FirstPass(const Tech& tech, Design& design, const RouterSettings& settings, NetOrderPolicy& policy) {
  RouterSettings s = settings;
  s.iterations = 1;
  s.stopAtZero = true;
  const ColourHook hook = [&](int colour, const CrossingPlan& plan, const std::vector<RegionTask>& tasks) {
    snapshot(design, colour, plan, tasks);
  };
  RouteOutcome out = routeDesign(tech, design, s, policy, {}, hook);
  if (!out.iterations.empty()) report_ = out.iterations.front();
  std::vector<NetRouting>& after = routing_[kColours];
  after.reserve(design.nets.size());
  for (const Net& n : design.nets) after.push_back(n.routing);
}

void FirstPass::snapshot(const Design& design, int colour, const CrossingPlan& plan,
                         const std::vector<RegionTask>& tasks) {
  if (colour < 0 || colour >= kColours) throw std::logic_error("first pass: colour out of range");
  if (colour == 0) {
    layout_.regionParts = plan.regionParts;
  }
  std::vector<NetRouting>& r = routing_[colour];
  r.clear();
  r.reserve(design.nets.size());
  for (const Net& n : design.nets) r.push_back(n.routing);
  crossings_[colour] = plan.crossings;
  tasks_.insert(tasks_.end(), tasks.begin(), tasks.end());
}

void FirstPass::restore(Design& design, int colour) const {
  if (colour < 0 || colour > kColours) throw std::out_of_range("colour must be in 0.." + std::to_string(kColours));
  const std::vector<NetRouting>& r = routing_[colour];
  if (r.size() != design.nets.size()) throw std::logic_error("first pass: the design's nets changed");
  for (size_t n = 0; n < r.size(); ++n) design.nets[n].routing = r[n];
}

CrossingPlan FirstPass::plan(int colour) const {
  if (colour < 0 || colour >= kColours) throw std::out_of_range("colour must be in 0.." + std::to_string(kColours - 1));
  CrossingPlan p = layout_;
  p.crossings = crossings_[colour];
  return p;
}

}  // namespace xroute
