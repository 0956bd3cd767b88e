// Python view of the routing flow: route a loaded Database with a built-in
// or Python net-order policy. The GIL is released while routing and taken
// back only to call a Python policy (once per region) or progress callback
// (once per region batch).
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
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
#include "db/database.hpp"
#include "flow/policy.hpp"
#include "flow/router.hpp"
#include "flow/search_policy.hpp"

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

}  // namespace

void bindRouter(nb::module_& m) {
  nb::list columns;
  for (const char* c : kFeatureColumns) columns.append(c);
  m.attr("POLICY_FEATURES") = nb::tuple(columns);
  m.def(
      "route",
      [](Database& db, int region_size, int iterations, int threads, const std::string& policy, uint64_t seed,
         nb::object policy_fn, bool policy_needs_region, nb::object progress, nb::dict costs,
         const std::optional<std::vector<std::pair<int, int>>>& schedule, int search_budget, int search_width,
         nb::object policy_next) {
        if (region_size < 1 || region_size > kMaxRegionSize) {
          throw nb::value_error(("region_size must be in 1.." + std::to_string(kMaxRegionSize)).c_str());
        }
        if (iterations < 1 || iterations > kMaxIterations) {
          throw nb::value_error(("iterations must be in 1.." + std::to_string(kMaxIterations)).c_str());
        }
        if (threads < 1 || threads > kMaxThreads) {
          throw nb::value_error(("threads must be in 1.." + std::to_string(kMaxThreads)).c_str());
        }
        std::unique_ptr<NetOrderPolicy> p;
        if (!policy_fn.is_none() || !policy_next.is_none()) {
          p = std::make_unique<PythonPolicy>(policy_fn, policy_needs_region, policy_next);
        } else {
          SearchSettings search;
          search.budget = search_budget;
          search.width = search_width;
          search.seed = seed;
          try {
            p = makeBuiltinPolicy(policy, search);
          } catch (const std::invalid_argument& e) {
            throw nb::value_error(e.what());
          }
        }
        RouterSettings s;
        s.regionSize = region_size;
        s.iterations = iterations;
        s.threads = threads;
        if (schedule) {
          for (const auto& [size, offset] : *schedule) {
            if (size < 1) throw nb::value_error("schedule: region size must be >= 1");
            if (offset < 0 || offset >= size) throw nb::value_error("schedule: offset must be in 0..region_size-1");
            s.schedule.push_back(ScheduleStep{size, offset});
          }
        }
        for (auto [k, v] : costs) {
          const std::string key = nb::cast<std::string>(k);
          const int64_t val = nb::cast<int64_t>(v);
          if (key == "via_cost") s.costs.viaCost = val;
          else if (key == "wrong_way_factor") s.costs.wrongWayFactor = val;
          else if (key == "out_of_guide_factor") s.costs.outOfGuideFactor = val;
          else if (key == "fixed_penalty") s.costs.fixedPenalty = val;
          else if (key == "use_penalty") s.costs.usePenalty = val;
          else if (key == "bottom_layer_factor") s.costs.bottomLayerFactor = val;
          else if (key == "reserve_penalty") s.costs.reservePenalty = val;
          else if (key == "crossing_pull") s.costs.crossingPull = val;
          else if (key == "use_penalty_step") s.usePenaltyStep = val;
          else if (key == "marker_penalty") s.markerPenalty = val;
          else if (key == "history_penalty") s.historyPenalty = val;
          else if (key == "repair_rounds") s.repairRounds = static_cast<int>(std::clamp<int64_t>(val, 0, kMaxRepairRounds));
          else if (key == "repair_penalty") s.repairPenalty = val;
          else if (key == "first_repair_rounds") s.firstRepairRounds = static_cast<int>(std::clamp<int64_t>(val, 0, kMaxRepairRounds));
          else throw nb::value_error(("unknown cost setting '" + key + "'").c_str());
        }
        const int dbu = db.design.dbuPerMicron;
        RouteProgress cb;
        if (!progress.is_none()) {
          cb = [&progress, dbu](const IterationReport& r, int done, int total) {
            nb::gil_scoped_acquire gil;
            progress(reportDict(r, dbu), done, total);
          };
        }
        RouteOutcome out;
        {
          nb::gil_scoped_release release;
          out = routeDesign(db.tech, db.design, s, *p, cb);
        }
        p.reset();
        nb::list its;
        for (const IterationReport& r : out.iterations) its.append(reportDict(r, dbu));
        nb::dict result;
        result["iterations"] = its;
        result["policy"] = policy_fn.is_none() && policy_next.is_none() ? policy : std::string("python");
        return result;
      },
      "db"_a, "region_size"_a = RouterSettings{}.regionSize, "iterations"_a = RouterSettings{}.iterations, "threads"_a = 1, "policy"_a = "heuristic", "seed"_a = 1,
      "policy_fn"_a = nb::none(), "policy_needs_region"_a = false, "progress"_a = nb::none(), "costs"_a = nb::dict(),
      "schedule"_a = nb::none(), "search_budget"_a = SearchSettings{}.budget, "search_width"_a = SearchSettings{}.width,
      "policy_next"_a = nb::none(),
      "Routes every net of the database in place (its routing is replaced). policy: 'heuristic', 'random' "
      "(seeded), 'rollout' (search_budget trial routings per region, search_width candidates per step, 0: all), "
      "'victims' (at most search_budget trial routings per region: the victims of the markers so far first), "
      "'bestof' (K = search_budget) or 'best-of-K' (K seeded orders, the heuristic's first); or "
      "policy_fn(region: dict, features: int32[n, len(POLICY_FEATURES)]) -> order; or, sequential, "
      "policy_next(region, features) -> index of the next net, called after every routed net with the unrouted "
      "candidates' rows as they are then. With "
      "policy_needs_region, region['engine_region'] is the Region being routed, lent for that call (the policy may "
      "route nets with it; the order applies to the rest). progress(report, "
      "regions_done, regions_total) is called after each batch of regions. costs: overrides of the maze costs by name "
      "(via_cost, wrong_way_factor, out_of_guide_factor, fixed_penalty, use_penalty, bottom_layer_factor, "
      "reserve_penalty, crossing_pull, use_penalty_step, marker_penalty, history_penalty, repair_rounds, first_repair_rounds, repair_penalty). schedule: per-iteration "
      "(region_size, offset) pairs in GCells, cycled over the iterations (None: region_size with offsets 0, C/3, 2C/3). "
      "Returns {'iterations': [report, ...]}.");
}
