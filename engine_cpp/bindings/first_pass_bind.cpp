// Python view of the flow's first pass kept for replay (loop/first_pass.hpp):
// route iteration 0 once, then open any of its regions in context, i.e. in
// the state the flow routed it in (the colours before it committed).
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>

#include <memory>
#include <string>

#include "bindings/region_handle.hpp"
#include "bindings/report_dict.hpp"
#include "bindings/settings_check.hpp"
#include "loop/first_pass.hpp"
#include "loop/router.hpp"

namespace nb = nanobind;
using namespace nb::literals;
using namespace xroute;

namespace {

// The pass with the session whose design it routed (the design must stay the session's).
struct FirstPassHandle {
  RoutingSession* session = nullptr;
  std::unique_ptr<FirstPass> pass;

  void restore(int colour) const {
    nb::gil_scoped_release release;
    session->restoreFirstPass(*pass, colour);
  }
};

void initFirstPass(FirstPassHandle* self, RoutingSession& s, int regionSize, const std::string& policy,
                   uint64_t seed, int threads) {
  RouterSettings settings;
  settings.regionSize = regionSize;
  settings.threads = threads;
  checkSettings(settings);
  std::unique_ptr<NetOrderPolicy> p;
  if (policy == "heuristic") p = makeHeuristicPolicy();
  else if (policy == "random") p = makeRandomPolicy(seed);
  else throw nb::value_error(("unknown policy '" + policy + "' (heuristic, random)").c_str());
  std::unique_ptr<FirstPass> pass;
  {
    nb::gil_scoped_release release;
    pass = s.routeFirstPass(settings, *p);
  }
  new (self) FirstPassHandle{&s, std::move(pass)};
}

// Region i of the pass as the flow routed it: the design restored to before its colour.
RegionHandle* openInContext(FirstPassHandle& fp, int32_t i) {
  if (i < 0 || i >= fp.pass->size()) {
    throw nb::index_error(("region index out of range 0.." + std::to_string(fp.pass->size() - 1)).c_str());
  }
  auto h = std::make_unique<RegionHandle>();
  h->session = fp.session;
  nb::gil_scoped_release release;
  h->region = fp.session->openFirstPassRegion(*fp.pass, i);
  h->box = h->region->task.region.box;
  return h.release();
}

nb::tuple regionRow(const RegionTask& t) {
  const Rect& b = t.region.box;
  return nb::make_tuple(nb::make_tuple(t.region.gx0, t.region.gy0), nb::make_tuple(b.xlo, b.ylo, b.xhi, b.yhi),
                        t.region.color, static_cast<int>(t.nets.size()));
}

}  // namespace

void bindFirstPass(nb::module_& m) {
  nb::class_<FirstPassHandle>(m, "FirstPass",
                              "The flow's first pass (iteration 0) of a session's design, kept so that each of its "
                              "regions can be opened again in context (loop/first_pass.hpp).")
      .def("__init__", &initFirstPass,
          "session"_a, "region_size"_a = RouterSettings{}.regionSize, "policy"_a = "heuristic", "seed"_a = 1,
          "threads"_a = 1, nb::keep_alive<1, 2>(),
          "Routes iteration 0 of the session's design as `xroute route` does (regions of region_size GCells, "
          "colour by colour; policy 'heuristic' or 'random' (seeded)), keeping the design's routing and crossing "
          "choices before each colour. The design is left with the whole pass routed.")
      .def_prop_ro(
          "regions",
          [](const FirstPassHandle& fp) {
            nb::list out;
            for (int32_t i = 0; i < fp.pass->size(); ++i) out.append(regionRow(fp.pass->task(i)));
            return out;
          },
          "The regions with work in the flow's order (colour, then row by row): [((gcell column, row), (xlo, ylo, "
          "xhi, yhi) in DBU, colour 0..3, nets), ...]; open_region(i) opens the i-th.")
      .def("open_region", &openInContext, "index"_a, nb::rv_policy::take_ownership, nb::keep_alive<0, 1>(),
           "Region `index` of regions, in context: the design's routing put back to what the pass had before the "
           "region's colour (earlier colours routed and their crossing points chosen, the rest unrouted) and the "
           "region's nets, pins and crossings as the flow gave them. Other open regions of the session become "
           "stale; routing it with route_rest('heuristic') gives what the pass routed there.")
      .def(
          "restore", [](const FirstPassHandle& fp, int colour) { fp.restore(colour); }, "colour"_a,
          "Puts the design's routing back to what it was before the regions of `colour` (0..3) were routed; 4: "
          "after the whole pass.")
      .def_prop_ro(
          "report", [](const FirstPassHandle& fp) { return reportDict(fp.pass->report(), fp.session->database().design.dbuPerMicron); },
          "Iteration 0's report (as route()'s): wirelength, vias and violations of the whole design after the pass.");
}
