// An iteration's report as the Python dict every binding returns (route, first pass).
#pragma once

#include <nanobind/nanobind.h>

#include <string>

#include "loop/router.hpp"

namespace xroute {

inline nanobind::dict reportDict(const IterationReport& r, int dbuPerMicron) {
  nanobind::dict d;
  d["iteration"] = r.iteration;
  d["region_size"] = r.regionSize;
  d["offset"] = r.offset;
  d["regions"] = r.regions;
  d["net_routes"] = r.netRoutes;
  d["unreached"] = r.unreached;
  d["wirelength_dbu"] = r.wirelength;
  d["wirelength_um"] = dbuPerMicron > 0 ? double(r.wirelength) / dbuPerMicron : 0.0;
  d["vias"] = r.vias;
  nanobind::dict byType;
  for (int t = 0; t < kMarkerTypes; ++t) {
    byType[std::string(markerTypeName(static_cast<MarkerType>(t))).c_str()] = r.markersByType[t];
  }
  d["violations_by_type"] = byType;
  d["violations"] = r.markers;
  d["seconds"] = r.seconds;
  nanobind::dict stages;
  stages["setup"] = r.stages.setup;
  stages["route"] = r.stages.route;
  stages["commit"] = r.stages.commit;
  stages["index"] = r.stages.index;
  stages["trim"] = r.stages.trim;
  stages["check"] = r.stages.check;
  d["stage_seconds"] = stages;
  d["checked_shapes"] = r.checkedShapes;
  d["done"] = r.done;
  if (r.done) d["plan"] = nanobind::cast(r.plan).attr("to_dict")();  // the plan the iteration ran (IterationPlan's fields)
  return d;
}

}  // namespace xroute
