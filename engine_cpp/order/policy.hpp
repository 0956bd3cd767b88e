// The net-order seam: in every region the flow asks a policy in which order
// to route the region's nets (routeInOrder, below). A policy sees the region
// and one feature row per candidate net (region/candidate.hpp), and returns a
// permutation (the fast path), or, when sequential(), is asked for the next
// net after every routed net with the candidates still unrouted and their
// updated features (the MDP).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "region/candidate.hpp"

namespace xroute {

class RegionRouter;
struct MazeWorkspace;

class NetOrderPolicy {
 public:
  virtual ~NetOrderPolicy() = default;
  // A permutation of 0..candidates.size()-1 (indices into `candidates`).
  virtual std::vector<int32_t> order(const RegionInfo& region, const std::vector<NetCandidate>& candidates) = 0;
  // The same, for a policy that needs the whole region (its grid): `router` is the region being
  // routed and `candidates` its unrouted ones. Such a policy may also route nets itself through
  // `router`; the returned order then applies to those still unrouted. Default: order().
  virtual std::vector<int32_t> orderRegion(RegionRouter& router, const RegionInfo& region,
                                           const std::vector<NetCandidate>& candidates) {
    (void)router;
    return order(region, candidates);
  }
  // A sequential policy is asked for one net at a time (next()) instead of a whole order.
  virtual bool sequential() const { return false; }
  // The index (into `unrouted`) of the net to route next; `unrouted` holds the candidates not
  // routed yet with their features as they are now. Default: the first of order().
  virtual int32_t next(RegionRouter& router, const RegionInfo& region, const std::vector<NetCandidate>& unrouted) {
    const std::vector<int32_t> o = orderRegion(router, region, unrouted);
    return o.empty() ? -1 : o.front();
  }
  virtual std::string name() const = 0;
  // The built-in heuristic order, which the flow's late search may stand in for
  // (RouterSettings::lateSearchBudget); every other policy orders every iteration itself.
  virtual bool builtinHeuristic() const { return false; }
};

// Smallest terminal bounding box (half perimeter) first, then more
// terminals first, then net id: short, constrained nets take the scarce
// tracks before long flexible ones detour around them.
std::unique_ptr<NetOrderPolicy> makeHeuristicPolicy();

// A uniformly random order, reproducible: seeded from (seed, iteration, region).
std::unique_ptr<NetOrderPolicy> makeRandomPolicy(uint64_t seed);

// The heuristic's comparison: true when candidate a goes before b.
bool heuristicBefore(const NetCandidate& a, const NetCandidate& b);

// Checks that `order` is a permutation of 0..n-1.
bool isPermutation(const std::vector<int32_t>& order, size_t n);

// Routes every candidate of `router` (prepared) not yet routed in the policy's order (a sequential
// policy: one net at a time, asked again after each with the unrouted candidates' updated
// features). Throws PolicyOrderError (errors/engine_errors.hpp) for an answer that is no order.
void routeInOrder(RegionRouter& router, NetOrderPolicy& policy, MazeWorkspace& ws);

}  // namespace xroute
