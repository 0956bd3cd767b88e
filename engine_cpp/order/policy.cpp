#include "order/policy.hpp"

#include <algorithm>
#include <numeric>
#include <random>
#include <string>

#include "errors/engine_errors.hpp"
#include "region/region_router.hpp"

namespace xroute {

namespace {

class HeuristicPolicy final : public NetOrderPolicy {
 public:
  std::vector<int32_t> order(const RegionInfo&, const std::vector<NetCandidate>& c) override {
    std::vector<int32_t> idx(c.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::stable_sort(idx.begin(), idx.end(), [&](int32_t a, int32_t b) { return heuristicBefore(c[a], c[b]); });
    return idx;
  }
  std::string name() const override { return "heuristic"; }
  bool builtinHeuristic() const override { return true; }
};

class RandomPolicy final : public NetOrderPolicy {
 public:
  explicit RandomPolicy(uint64_t seed) : seed_(seed) {}
  std::vector<int32_t> order(const RegionInfo& r, const std::vector<NetCandidate>& c) override {
    std::vector<int32_t> idx(c.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::seed_seq seq{uint32_t(seed_), uint32_t(seed_ >> 32), uint32_t(r.iteration), uint32_t(r.regionId)};
    std::mt19937_64 rng(seq);
    // Fisher-Yates with our own index draws (std::shuffle's use of the
    // engine is implementation-defined; this keeps orders identical everywhere).
    for (size_t i = idx.size(); i > 1; --i) {
      const size_t j = static_cast<size_t>(rng() % i);
      std::swap(idx[i - 1], idx[j]);
    }
    return idx;
  }
  std::string name() const override { return "random"; }

 private:
  uint64_t seed_;
};

}  // namespace

bool heuristicBefore(const NetCandidate& a, const NetCandidate& b) {
  const int64_t pa = int64_t(a.bbox.width()) + a.bbox.height();
  const int64_t pb = int64_t(b.bbox.width()) + b.bbox.height();
  if (pa != pb) return pa < pb;
  if (a.terminals != b.terminals) return a.terminals > b.terminals;
  return a.net < b.net;
}

std::unique_ptr<NetOrderPolicy> makeHeuristicPolicy() { return std::make_unique<HeuristicPolicy>(); }
std::unique_ptr<NetOrderPolicy> makeRandomPolicy(uint64_t seed) { return std::make_unique<RandomPolicy>(seed); }

bool isPermutation(const std::vector<int32_t>& order, size_t n) {
  if (order.size() != n) return false;
  std::vector<uint8_t> seen(n, 0);
  for (int32_t i : order) {
    if (i < 0 || static_cast<size_t>(i) >= n || seen[i]) return false;
    seen[i] = 1;
  }
  return true;
}

namespace {

// A sequential policy: one net at a time, the candidates' features refreshed after each.
void routeSequential(RegionRouter& router, NetOrderPolicy& policy, MazeWorkspace& ws) {
  const RegionInfo region = router.info();
  std::vector<int32_t> pending;
  for (std::vector<NetCandidate> cands = router.unrouted(pending); !pending.empty();
       cands = router.unrouted(pending)) {
    const int32_t k = policy.next(router, region, cands);
    if (k < 0 || static_cast<size_t>(k) >= cands.size()) {
      throw PolicyOrderError("net-order policy '" + policy.name() + "' chose candidate " + std::to_string(k) +
                             ", outside 0.." + std::to_string(cands.size() - 1));
    }
    if (!router.isRouted(pending[k])) router.routeNet(pending[k], ws);  // the policy may have routed it itself
  }
}

}  // namespace

void routeInOrder(RegionRouter& router, NetOrderPolicy& policy, MazeWorkspace& ws) {
  if (policy.sequential()) {
    routeSequential(router, policy, ws);
    return;
  }
  std::vector<int32_t> pending;
  const std::vector<NetCandidate> cands = router.unrouted(pending);
  if (pending.empty()) return;
  const RegionInfo info = router.info();
  const std::vector<int32_t> order = policy.orderRegion(router, info, cands);
  if (!isPermutation(order, cands.size())) {
    throw PolicyOrderError("net-order policy '" + policy.name() + "' returned an order that is not a permutation of " +
                           std::to_string(cands.size()) + " candidates");
  }
  for (int32_t k : order) {
    if (!router.isRouted(pending[k])) router.routeNet(pending[k], ws);  // the policy may have routed some itself
  }
}

}  // namespace xroute
