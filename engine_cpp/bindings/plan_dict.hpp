// An iteration's plan as the Python dict the iteration planner sees and returns (route()).
#pragma once

#include <nanobind/nanobind.h>

#include <algorithm>
#include <cstdint>
#include <string>

#include "loop/router.hpp"
#include "order/search_policy.hpp"

namespace xroute {

inline nanobind::dict planDict(const IterationPlan& p) {
  nanobind::dict d;
  d["region_size"] = p.regionSize;
  d["offset"] = p.offset;
  d["repair_rounds"] = p.repairRounds;
  d["marker_penalty"] = p.markerPenalty;
  d["history_penalty"] = p.historyPenalty;
  d["use_penalty"] = p.costs.usePenalty;
  d["stop"] = p.stop;
  d["search_budget"] = p.searchBudget;
  return d;
}

// `rule` with the keys of `d` put in; an unknown key or a value of the wrong type is a ValueError
// (the Python side checks ranges before it hands a plan over; the flow clamps what is left).
inline IterationPlan planFromDict(const nanobind::handle& d, IterationPlan rule) {
  namespace nb = nanobind;
  if (!nb::isinstance<nb::dict>(d)) throw nb::value_error("planner: a plan is a dict");
  for (auto [key, value] : nb::borrow<nb::dict>(d)) {
    const std::string k = nb::cast<std::string>(key);
    if (k == "stop") {
      rule.stop = nb::cast<bool>(value);
      continue;
    }
    const int64_t v = nb::cast<int64_t>(value);
    if (k == "region_size") {
      rule.regionSize = static_cast<int>(std::clamp<int64_t>(v, 1, kMaxRegionSize));
    } else if (k == "offset") {
      rule.offset = static_cast<int>(std::clamp<int64_t>(v, 0, kMaxRegionSize));
    } else if (k == "repair_rounds") {
      rule.repairRounds = static_cast<int>(std::clamp<int64_t>(v, 0, kMaxRepairRounds));
    } else if (k == "marker_penalty") {
      rule.markerPenalty = v;
    } else if (k == "history_penalty") {
      rule.historyPenalty = v;
    } else if (k == "use_penalty") {
      rule.costs.usePenalty = v;
    } else if (k == "search_budget") {
      rule.searchBudget = static_cast<int>(std::clamp<int64_t>(v, 0, kMaxSearchBudget));
    } else {
      throw nb::value_error(("planner: unknown plan key '" + k + "'").c_str());
    }
  }
  return rule;
}

}  // namespace xroute
