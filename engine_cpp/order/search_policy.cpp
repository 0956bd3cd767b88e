#include "order/search_policy.hpp"

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <iterator>
#include <numeric>
#include <random>
#include <stdexcept>

#include "region/region_router.hpp"

namespace xroute {

double regionCost(const RegionRouter& router, const RegionCostWeights& w) {
  return regionCost(router, w, router.check());
}

double regionCost(const RegionRouter& router, const RegionCostWeights& w, const std::vector<Marker>& markers) {
  int64_t wl = 0, vias = 0;
  for (int32_t i = 0; i < static_cast<int32_t>(router.candidates().size()); ++i) {
    const RegionNetResult& r = router.result(i);
    if (!r.routed) continue;
    wl += r.added.wirelength();
    vias += static_cast<int64_t>(r.added.vias.size());
  }
  const double dbu = std::max(1, router.context().design.dbuPerMicron);
  return w.wirelength * (double(wl) / dbu) + w.via * double(vias) + w.violation * double(markers.size());
}

namespace {

// One search over a region's unrouted candidates: trial orders routed on copies of a start
// state, the cheapest kept (with its routed copy, which the region adopts at the end).
class RegionSearch {
 public:
  RegionSearch(RegionRouter& router, const std::vector<NetCandidate>& cands, const RegionCostWeights& w)
      : router_(router), weights_(w) {
    router.unrouted(pending_);
    if (pending_.size() != cands.size()) throw std::logic_error("search policy: candidates do not match the region");
    for (const NetCandidate& c : cands) nets_.push_back(c.net);
    rank_.resize(cands.size());
    std::iota(rank_.begin(), rank_.end(), 0);
    std::stable_sort(rank_.begin(), rank_.end(),
                     [&](int32_t a, int32_t b) { return heuristicBefore(cands[a], cands[b]); });
  }

  const std::vector<int32_t>& rank() const { return rank_; }  // local indices, heuristic order
  int trials() const { return trials_; }

  // Routes `order` (local indices, after the nets `from` already has) on a copy of `from`;
  // true when it is the cheapest so far (ties: the earlier trial stays).
  // `markers_out` (optional) receives the trial's markers.
  bool trial(const RegionRouter& from, const std::vector<int32_t>& order, std::vector<Marker>* markers_out = nullptr) {
    std::unique_ptr<RegionRouter> t = from.clone();
    for (int32_t k : order) t->routeNet(pending_[k], ws_);
    const std::vector<Marker> markers = t->check();
    if (markers_out) *markers_out = markers;
    const double cost = regionCost(*t, weights_, markers);
    ++trials_;
    if (best_ && cost >= bestCost_) return false;
    bestCost_ = cost;
    best_ = std::move(t);
    bestMarkerNets_.clear();
    for (const Marker& m : markers) bestMarkerNets_.insert(bestMarkerNets_.end(), {m.net1, m.net2});
    std::sort(bestMarkerNets_.begin(), bestMarkerNets_.end());
    return true;
  }

  // Whether the cheapest trial has a marker naming candidate `local`'s net.
  bool inBestMarkers(int32_t local) const {
    return std::binary_search(bestMarkerNets_.begin(), bestMarkerNets_.end(), nets_[local]);
  }

  // The region takes the cheapest trial's routing; returns its order (local indices).
  std::vector<int32_t> finish(const std::vector<int32_t>& order) {
    if (best_) router_.adopt(std::move(best_));
    return order;
  }

  int32_t net(int32_t local) const { return nets_[local]; }
  MazeWorkspace& workspace() { return ws_; }
  int32_t candidate(int32_t local) const { return pending_[local]; }

 private:
  RegionRouter& router_;
  RegionCostWeights weights_;
  std::vector<int32_t> pending_;  // local index -> the router's candidate index
  std::vector<int32_t> nets_;     // local index -> net id
  std::vector<int32_t> bestMarkerNets_;  // nets named by the cheapest trial's markers, sorted
  std::vector<int32_t> rank_;
  MazeWorkspace ws_;
  std::unique_ptr<RegionRouter> best_;
  double bestCost_ = 0;
  int trials_ = 0;
};

class RolloutPolicy final : public NetOrderPolicy {
 public:
  explicit RolloutPolicy(const SearchSettings& s) : s_(s) {}
  std::vector<int32_t> order(const RegionInfo&, const std::vector<NetCandidate>& c) override {
    std::vector<int32_t> idx(c.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::stable_sort(idx.begin(), idx.end(), [&](int32_t a, int32_t b) { return heuristicBefore(c[a], c[b]); });
    return idx;  // without the region there is nothing to try: the heuristic's order
  }
  // The incumbent (cheapest trial) is the order prefix + rest, rest in heuristic rank; trying
  // rest[0] next would route it again. Each step tries as the next net the nets of rest[1..]
  // that the incumbent's markers name (the last-ranked first: the nets routed latest, the ones
  // the earlier routing squeezed; at most width - 1 of them), each trial finishing the region in
  // heuristic rank, and commits the cheapest first choice; it stops when no such net is left
  // (the incumbent has no marker a different next net could mend) or the budget is spent, the
  // rest then in the incumbent's (heuristic) order. Budget: see SearchSettings.
  std::vector<int32_t> orderRegion(RegionRouter& router, const RegionInfo&, const std::vector<NetCandidate>& c) override {
    if (c.size() < 2 || s_.budget < 2) return order(RegionInfo{}, c);
    RegionSearch search(router, c, s_.weights);
    std::unique_ptr<RegionRouter> state = router.clone();  // the committed prefix
    std::vector<int32_t> prefix, rest = search.rank();
    search.trial(*state, rest);
    while (rest.size() > 1 && search.trials() < s_.budget) {
      std::vector<size_t> tries;
      for (size_t j = rest.size() - 1; j >= 1; --j) {
        if (search.inBestMarkers(rest[j])) tries.push_back(j);
        if (s_.width > 0 && tries.size() + 1 >= static_cast<size_t>(s_.width)) break;
      }
      if (tries.empty()) break;
      size_t pick = 0;
      for (size_t j : tries) {
        if (search.trials() >= s_.budget) break;
        std::vector<int32_t> trial{rest[j]};
        for (size_t k = 0; k < rest.size(); ++k)
          if (k != j) trial.push_back(rest[k]);
        if (search.trial(*state, trial)) pick = j;
      }
      state->routeNet(search.candidate(rest[pick]), search.workspace());
      prefix.push_back(rest[pick]);
      rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(pick));
    }
    prefix.insert(prefix.end(), rest.begin(), rest.end());
    return search.finish(prefix);
  }
  std::string name() const override { return "rollout"; }

 private:
  SearchSettings s_;
};

// A random permutation of 0..n-1 from (seed, iteration, region, trial), drawn as the random
// policy draws (our own Fisher-Yates, so the same everywhere).
std::vector<int32_t> seededOrder(size_t n, uint64_t seed, const RegionInfo& r, int trial) {
  std::vector<int32_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  std::seed_seq seq{uint32_t(seed), uint32_t(seed >> 32), uint32_t(r.iteration), uint32_t(r.regionId), uint32_t(trial)};
  std::mt19937_64 rng(seq);
  for (size_t i = idx.size(); i > 1; --i) std::swap(idx[i - 1], idx[static_cast<size_t>(rng() % i)]);
  return idx;
}

class BestOfPolicy final : public NetOrderPolicy {
 public:
  BestOfPolicy(int k, const SearchSettings& s) : k_(k), s_(s) {}
  std::vector<int32_t> order(const RegionInfo& r, const std::vector<NetCandidate>& c) override {
    return RolloutPolicy(s_).order(r, c);
  }
  std::vector<int32_t> orderRegion(RegionRouter& router, const RegionInfo& r, const std::vector<NetCandidate>& c) override {
    if (c.size() < 2 || k_ < 2) return order(r, c);
    RegionSearch search(router, c, s_.weights);
    std::vector<int32_t> best = search.rank();
    search.trial(router, best);
    for (int t = 1; t < k_; ++t) {
      std::vector<int32_t> o = seededOrder(c.size(), s_.seed, r, t);
      if (search.trial(router, o)) best = std::move(o);
    }
    return search.finish(best);
  }
  std::string name() const override { return "best-of-" + std::to_string(k_); }

 private:
  int k_;
  SearchSettings s_;
};

// The nets that `markers` leave in violation after routing `order` (local indices): of a two-net
// marker the net routed later (a net routed before the region, or not a candidate, counts as
// earliest); a one-net marker (minimum area, an obstruction) names its own net.
std::vector<int32_t> victimNets(const RegionSearch& search, const std::vector<int32_t>& order,
                                const std::vector<Marker>& markers) {
  std::vector<std::pair<int32_t, int32_t>> first;  // (net, position of its first part)
  for (size_t p = 0; p < order.size(); ++p) first.emplace_back(search.net(order[p]), static_cast<int32_t>(p));
  std::stable_sort(first.begin(), first.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  auto position = [&](int32_t net) {
    auto it = std::lower_bound(first.begin(), first.end(), std::make_pair(net, INT32_MIN));
    return it != first.end() && it->first == net ? it->second : -1;
  };
  std::vector<int32_t> out;
  for (const Marker& m : markers) {
    if (m.net1 >= 0 && m.net2 >= 0 && m.net1 != m.net2) {
      out.push_back(position(m.net1) > position(m.net2) ? m.net1 : m.net2);
    } else {
      for (int32_t n : {m.net1, m.net2})
        if (n >= 0) out.push_back(n);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

class VictimsPolicy final : public NetOrderPolicy {
 public:
  static constexpr int kMaxRedraws = 64;  // draws of a victims' order over a whole search
  explicit VictimsPolicy(const SearchSettings& s) : s_(s) {}
  std::vector<int32_t> order(const RegionInfo& r, const std::vector<NetCandidate>& c) override {
    return RolloutPolicy(s_).order(r, c);
  }
  // Trial 1 routes the heuristic order. Each later trial routes the victims of every trial so far
  // first and the other nets after them, both parts in heuristic rank, until a trial names no new
  // victim. Trials left in the budget then route the victims (of every trial so far) first in a
  // seeded random order, the rest in heuristic rank; a drawn order tried before is drawn again
  // (kMaxRedraws times at most, then the search stops). The cheapest trial is kept.
  std::vector<int32_t> orderRegion(RegionRouter& router, const RegionInfo& r, const std::vector<NetCandidate>& c) override {
    if (c.size() < 2 || s_.budget < 2) return order(r, c);
    RegionSearch search(router, c, s_.weights);
    std::vector<int32_t> best = search.rank(), current = best, victims;
    std::vector<std::vector<int32_t>> tried{current};
    std::vector<Marker> markers;
    search.trial(router, current, &markers);
    bool shuffling = false;
    int draws = 0;
    while (search.trials() < s_.budget) {
      std::vector<int32_t> found = victimNets(search, current, markers), merged;
      std::set_union(victims.begin(), victims.end(), found.begin(), found.end(), std::back_inserter(merged));
      shuffling = shuffling || merged.size() == victims.size();
      victims = std::move(merged);
      std::vector<int32_t> early, late;
      for (int32_t k : search.rank())
        (std::binary_search(victims.begin(), victims.end(), search.net(k)) ? early : late).push_back(k);
      if (shuffling) {
        if (early.size() < 2) break;
        std::vector<int32_t> drawn;
        do {
          if (draws == kMaxRedraws) break;
          drawn.clear();
          for (int32_t i : seededOrder(early.size(), s_.seed, r, ++draws)) drawn.push_back(early[i]);
          drawn.insert(drawn.end(), late.begin(), late.end());
        } while (std::find(tried.begin(), tried.end(), drawn) != tried.end());
        if (std::find(tried.begin(), tried.end(), drawn) != tried.end() || drawn.empty()) break;
        current = std::move(drawn);
      } else {
        early.insert(early.end(), late.begin(), late.end());
        current = std::move(early);
      }
      tried.push_back(current);
      if (search.trial(router, current, &markers)) best = current;
    }
    return search.finish(best);
  }
  std::string name() const override { return "victims"; }

 private:
  SearchSettings s_;
};

void checkBudget(const char* what, int64_t v) {
  if (v < 1 || v > kMaxSearchBudget)
    throw std::invalid_argument(std::string(what) + " must be in 1.." + std::to_string(kMaxSearchBudget) + ", got " +
                                std::to_string(v));
}

}  // namespace

std::unique_ptr<NetOrderPolicy> makeRolloutPolicy(const SearchSettings& s) {
  checkBudget("search budget", s.budget);
  if (s.width < 0) throw std::invalid_argument("search width must be >= 0 (0: every candidate), got " + std::to_string(s.width));
  return std::make_unique<RolloutPolicy>(s);
}

std::unique_ptr<NetOrderPolicy> makeBestOfPolicy(int k, const SearchSettings& s) {
  checkBudget("best-of-K: K", k);
  return std::make_unique<BestOfPolicy>(k, s);
}

std::unique_ptr<NetOrderPolicy> makeBuiltinPolicy(const std::string& name, const SearchSettings& s) {
  if (name == "heuristic") return makeHeuristicPolicy();
  if (name == "random") return makeRandomPolicy(s.seed);
  if (name == "rollout") return makeRolloutPolicy(s);
  if (name == "victims") {
    checkBudget("search budget", s.budget);
    return std::make_unique<VictimsPolicy>(s);
  }
  if (name == "bestof") {
    checkBudget("search budget", s.budget);
    return makeBestOfPolicy(s.budget, s);
  }
  const std::string prefix = "best-of-";
  if (name.compare(0, prefix.size(), prefix) == 0 && name.size() > prefix.size() && name.size() <= prefix.size() + 6 &&
      std::all_of(name.begin() + prefix.size(), name.end(), [](char ch) { return ch >= '0' && ch <= '9'; })) {
    return makeBestOfPolicy(std::stoi(name.substr(prefix.size())), s);
  }
  throw std::invalid_argument("unknown policy '" + name + "' (heuristic, random, rollout, victims, bestof, best-of-K)");
}

}  // namespace xroute
