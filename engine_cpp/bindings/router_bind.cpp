// Python view of the routing flow: route a loaded Database with a built-in
// or Python net-order policy. The GIL is released while routing and taken
// back only to call a Python policy (once per region) or progress callback
// (once per region batch).
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <type_traits>

#include "bindings/arrays.hpp"
#include "bindings/region_handle.hpp"
#include "bindings/report_dict.hpp"
#include "bindings/settings_check.hpp"
#include "db/database.hpp"
#include "grid/gcell_grid.hpp"
#include "loop/regions.hpp"
#include "loop/router.hpp"
#include "order/policy.hpp"
#include "order/search_policy.hpp"
#include "pa/pin_access.hpp"

namespace nb = nanobind;
using namespace nb::literals;
using namespace xroute;

namespace {

// A policy implemented by a Python callable:
//   fn(region: dict, features: int32[n, 9]) -> sequence of n distinct ints.
// With `needsRegion`, region["engine_region"] is the Region being routed (a
// _engine.Region lent for this call: grid views, route_net...). Its name, in
// errors, is fn.name when the callable has one (the Python policy's), else "python".
// With `next` (not None) the policy is sequential: next(region, features) -> index of the
// net to route next, called after every routed net with the unrouted candidates' rows.
class PythonPolicy final : public NetOrderPolicy {
 public:
  PythonPolicy(nb::object fn, bool needsRegion, nb::object next)
      : fn_(std::move(fn)),
        next_(std::move(next)),
        needsRegion_(needsRegion),
        name_(nb::hasattr(fn_, "name") ? nb::cast<std::string>(nb::str(fn_.attr("name"))) : "python") {}
  ~PythonPolicy() override {
    nb::gil_scoped_acquire gil;
    fn_.reset();
    next_.reset();
  }

  bool sequential() const override { return !next_.is_none(); }
  int32_t next(RegionRouter& router, const RegionInfo& region, const std::vector<NetCandidate>& c) override {
    return call(next_, needsRegion_ ? &router : nullptr, region, c,
                [](const nb::object& r) { return nb::cast<int32_t>(r); });
  }

  std::vector<int32_t> order(const RegionInfo& region, const std::vector<NetCandidate>& c) override {
    return call(fn_, nullptr, region, c, permutation);
  }
  std::vector<int32_t> orderRegion(RegionRouter& router, const RegionInfo& region,
                                   const std::vector<NetCandidate>& c) override {
    return call(fn_, needsRegion_ ? &router : nullptr, region, c, permutation);
  }
  std::string name() const override { return name_; }

 private:
  static std::vector<int32_t> permutation(const nb::object& result) {
    std::vector<int32_t> out;
    for (nb::handle h : result) out.push_back(nb::cast<int32_t>(h));
    return out;
  }

  // Calls fn(region, features) with the GIL held (one call at a time) and converts its result
  // there: `convert` sees the returned object while the GIL is still held.
  template <class Convert>
  std::invoke_result_t<Convert, const nb::object&> call(const nb::object& fn, RegionRouter* router,
                                                        const RegionInfo& region, const std::vector<NetCandidate>& c,
                                                        Convert convert) {
    std::lock_guard<std::mutex> lock(mutex_);
    nb::gil_scoped_acquire gil;
    IntArray features = ownedInt32(featureRows(c), kFeatureCount);
    nb::dict info;
    info["iteration"] = region.iteration;
    info["region"] = region.regionId;
    info["box"] = nb::make_tuple(region.box.xlo, region.box.ylo, region.box.xhi, region.box.yhi);
    RegionHandle* lent = nullptr;
    if (router != nullptr) {
      lent = new RegionHandle();
      lent->region = std::make_unique<SessionRegion>();
      lent->region->router = router;
      lent->box = region.box;
      lent->lent = true;
      info["engine_region"] = nb::cast(lent, nb::rv_policy::take_ownership);
    }
    struct Expire {  // the lent region is gone once the call returns (or raises)
      RegionHandle* h;
      ~Expire() {
        if (h) h->region->router = nullptr;
      }
    } expire{lent};
    return convert(fn(info, features));
  }

  nb::object fn_;
  nb::object next_;
  bool needsRegion_ = false;
  std::string name_;  // in error messages
  std::mutex mutex_;
};

// A Python policy when policy_fn or policy_next is given, else the built-in named `policy`.
std::unique_ptr<NetOrderPolicy> routePolicy(const std::string& policy, uint64_t seed, nb::object policyFn,
                                            bool needsRegion, nb::object policyNext, int searchBudget,
                                            int searchWidth) {
  if (!policyFn.is_none() || !policyNext.is_none()) {
    return std::make_unique<PythonPolicy>(policyFn, needsRegion, policyNext);
  }
  SearchSettings search;
  search.budget = searchBudget;
  search.width = searchWidth;
  search.seed = seed;
  try {
    return makeBuiltinPolicy(policy, search);
  } catch (const std::invalid_argument& e) {
    throw nb::value_error(e.what());
  }
}

nb::dict route(Database& db, const RouterSettings* settings, const std::string& policy, uint64_t seed,
               nb::object policyFn, bool needsRegion, nb::object progress, int searchBudget, int searchWidth,
               nb::object policyNext, nb::object planner) {
  RouterSettings s = settings ? *settings : RouterSettings{};
  checkSettings(s);
  std::unique_ptr<NetOrderPolicy> p =
      routePolicy(policy, seed, policyFn, needsRegion, policyNext, searchBudget, searchWidth);
  s.searchSeed = seed;
  const int dbu = db.design.dbuPerMicron;
  RouteProgress cb;
  if (!progress.is_none()) {
    cb = [&progress, dbu](const IterationReport& r, int done, int total) {
      nb::gil_scoped_acquire gil;
      progress(reportDict(r, dbu), done, total);
    };
  }
  IterationPlanner plan;
  if (!planner.is_none()) {
    plan = [&planner, dbu](const std::vector<IterationReport>& done, const IterationPlan& rule) {
      nb::gil_scoped_acquire gil;
      nb::list history;
      for (const IterationReport& r : done) history.append(reportDict(r, dbu));
      IterationPlan p = nb::cast<IterationPlan>(planner(history, nb::cast(rule, nb::rv_policy::copy)));
      checkPlan(p);
      const int64_t usePenalty = p.costs.usePenalty;  // the one cost a plan sets; the others are the run's
      p.costs = rule.costs;
      p.costs.usePenalty = usePenalty;
      return p;
    };
  }
  RouteOutcome out;
  {
    nb::gil_scoped_release release;
    out = routeDesign(db.tech, db.design, s, *p, cb, {}, plan);
  }
  p.reset();
  nb::list its;
  for (const IterationReport& r : out.iterations) its.append(reportDict(r, dbu));
  nb::dict result;
  result["iterations"] = its;
  result["policy"] = policyFn.is_none() && policyNext.is_none() ? policy : std::string("python");
  result["sole_landing_penalty"] = out.costs.soleLandingPenalty;
  return result;
}

// GCells per region side of a run whose region size is 0 (loop/regions.hpp autoRegionSize).
int autoRegionSizeOf(const Database& db) {
  const TrackSet tracks = buildTracks(db.tech, db.design);
  const PinAccessTable access = computePinAccess(db.tech, db.design, tracks, PinAccessSettings{});
  return autoRegionSize(makeGCellGrid(db.design, tracks), tracks, access.points, kMaxRegionSize);
}

// regionGridNodes of regions `size` GCells a side (loop/regions.hpp).
double regionGridNodesOf(const Database& db, int size) {
  if (size < 1 || size > kMaxRegionSize) throw nb::value_error("size must be in 1..1000");
  const TrackSet tracks = buildTracks(db.tech, db.design);
  const PinAccessTable access = computePinAccess(db.tech, db.design, tracks, PinAccessSettings{});
  return regionGridNodes(makeGCellGrid(db.design, tracks), tracks, access.points, size);
}

}  // namespace

void bindRouter(nb::module_& m) {
  m.def("region_grid_nodes", &regionGridNodesOf, "db"_a, "size"_a,
        "The upper quartile, over the regions of `size` GCells a side (offset 0) that hold an access point, of "
        "a region grid's nodes a layer (lines in x times lines in y), as auto_region_size weighs them.");
  m.def("auto_region_size", &autoRegionSizeOf, "db"_a,
        "GCells per region side of a run whose region_size is 0: DEFAULTS['region_gcells'], or more while three in "
        "four regions' grids (lines at every track and access point in the region) stay within "
        "DEFAULTS['region_grid_nodes'] nodes a layer and a region does not cover the die; or fewer, down to "
        "DEFAULTS['least_region_gcells'], while they are over it at the first. Computes the design's "
        "pin access (the default access points per pin, as a run does).");
  nb::list columns;
  for (const char* c : kFeatureColumns) columns.append(c);
  m.attr("POLICY_FEATURES") = nb::tuple(columns);
  m.def(
      "route", &route, "db"_a, "settings"_a = nb::none(), "policy"_a = "heuristic", "seed"_a = 1,
      "policy_fn"_a = nb::none(), "policy_needs_region"_a = false, "progress"_a = nb::none(),
      "search_budget"_a = SearchSettings{}.budget, "search_width"_a = SearchSettings{}.width,
      "policy_next"_a = nb::none(), "planner"_a = nb::none(),
      "Routes every net of the database in place (its routing is replaced). policy: 'heuristic', 'random' "
      "(seeded), 'rollout' (search_budget trial routings per region, search_width candidates per step, 0: all), "
      "'victims' (at most search_budget trial routings per region: the victims of the markers so far first), "
      "'bestof' (K = search_budget) or 'best-of-K' (K seeded orders, the heuristic's first); or "
      "policy_fn(region: dict, features: int32[n, len(POLICY_FEATURES)]) -> order; or, sequential, "
      "policy_next(region, features) -> index of the next net, called after every routed net with the unrouted "
      "candidates' rows as they are then. With "
      "policy_needs_region, region['engine_region'] is the Region being routed, lent for that call (the policy may "
      "route nets with it; the order applies to the rest). progress(report, "
      "regions_done, regions_total) is called after each batch of regions. settings: a RouterSettings (region "
      "size, iterations, threads, schedule, costs, penalties, repair rounds; None: the defaults); a field out of "
      "the engine's limits is a RouteArgumentError. "
      "planner(history: [report, ...], rule: IterationPlan) -> IterationPlan is asked before each iteration, with "
      "the reports of the iterations done and the rule's plan; the iteration runs the plan it returns (stop: end "
      "the run, from iteration 1 on; search_budget B >= 1: the victims search with that budget in this iteration; "
      "a field out of the engine's limits is a RouteArgumentError). "
      "Returns {'iterations': [report, ...], 'policy': name, 'sole_landing_penalty': the maze's, as the run "
      "resolved it}; a report's plan is its IterationPlan's to_dict().");
}
