// Python view of the built-in global router: route a loaded Database's nets
// on the GCell grid, install the guides in it and optionally write them.
// The GIL is released while routing.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>

#include "bindings/arrays.hpp"
#include "groute/capacity.hpp"
#include "grid/tracks.hpp"

#include "db/database.hpp"
#include "groute/global_router.hpp"
#include "io/atomic_file.hpp"

namespace nb = nanobind;
using namespace nb::literals;
using namespace xroute;

void bindGlobalRouter(nb::module_& m) {
  m.def(
      "gcell_capacity",
      [](const Database& db) {
        GrGrid grid;
        {
          nb::gil_scoped_release release;
          grid = buildGrGrid(db.tech, db.design, buildTracks(db.tech, db.design));
        }
        nb::dict d;
        d["xs"] = ownedInt32(std::vector<int32_t>(grid.gcells.xs.begin(), grid.gcells.xs.end()), 1);
        d["ys"] = ownedInt32(std::vector<int32_t>(grid.gcells.ys.begin(), grid.gcells.ys.end()), 1);
        nb::list layers, horizontal, capacity, tracks;
        for (const GrLayer& gl : grid.layers) {
          layers.append(db.tech.layer(gl.layer).name);
          horizontal.append(gl.horizontal);
          std::vector<int32_t> cap = gl.capacity, tr = gl.tracks;
          capacity.append(ownedInt32(std::move(cap), static_cast<size_t>(grid.nx())));
          tracks.append(ownedInt32(std::move(tr), static_cast<size_t>(grid.nx())));
        }
        d["layers"] = layers;
        d["horizontal"] = horizontal;
        d["capacity"] = capacity;
        d["tracks"] = tracks;
        return d;
      },
      "db"_a,
      "The global router's GCell grid and capacities: xs, ys (GCell lines, DBU), layers (routing layer names), "
      "horizontal (preferred direction per layer), capacity and tracks (per layer, int32[ny, nx]: at [y, x] the "
      "edge from GCell (x, y) to its right neighbour on a horizontal layer, to its upper neighbour on a vertical "
      "one; free tracks after blocking, and all tracks).");
  m.def(
      "global_route",
      [](Database& db, const std::string& out, int iterations, int capacity_percent, int min_layer, int slack,
         double congestion_cost) {
        if (iterations < 0 || iterations > 1000) throw nb::value_error("iterations must be in 0..1000");
        if (capacity_percent < 1 || capacity_percent > 100) throw nb::value_error("capacity_percent must be in 1..100");
        if (min_layer < 0) throw nb::value_error("min_layer must be >= 0");
        if (slack < 0) throw nb::value_error("slack must be >= 0");
        if (!(congestion_cost >= 0)) throw nb::value_error("congestion_cost must be >= 0");
        GlobalRouteSettings s;
        s.iterations = iterations;
        s.capacityPercent = capacity_percent;
        s.minLayer = min_layer;
        s.slack = slack;
        s.congestionCost = congestion_cost;
        GlobalRouteResult r;
        {
          nb::gil_scoped_release release;
          r = globalRoute(db.tech, db.design, s);
          if (!out.empty()) writeFileAtomically(out, guideText(db.tech, db.design, r.guides), "guide file");
          installGuides(db.design, r.guides);
        }
        const GlobalRouteStats& st = r.stats;
        nb::dict d;
        d["gcells"] = nb::make_tuple(st.nx, st.ny);
        d["layers"] = st.nz;
        d["nets"] = st.nets;
        d["initial_overflow"] = st.initialOverflow;
        d["overflow"] = st.overflow;
        d["overflow_edges"] = st.overflowEdges;
        d["overflow_3d"] = st.overflow3d;
        d["wirelength_gcells"] = st.wirelength;
        d["vias"] = st.vias;
        d["guides"] = st.guides;
        d["iterations"] = st.iterations;
        d["reroutes"] = st.reroutes;
        d["seconds"] = st.seconds;
        return d;
      },
      "db"_a, "out"_a = "", "iterations"_a = GlobalRouteSettings{}.iterations,
      "capacity_percent"_a = GlobalRouteSettings{}.capacityPercent, "min_layer"_a = GlobalRouteSettings{}.minLayer,
      "slack"_a = GlobalRouteSettings{}.slack, "congestion_cost"_a = GlobalRouteSettings{}.congestionCost,
      "Global-routes every net of the database and replaces its guides with the result (any guides it had are "
      "dropped). out: also write them to this path in the ISPD guide format (atomically; '' = no file). "
      "iterations: rip-up-and-reroute rounds at most; capacity_percent: share of each GCell edge's free tracks "
      "the router may fill; min_layer: lowest routing-layer index carrying routes (pins get guides on their own "
      "layer and the one above regardless); slack: GCells every guide is grown by; congestion_cost: layer "
      "assignment's cost of one GCell edge at full use (0: only full layers and vias count). Returns statistics: gcells "
      "(nx, ny), layers, nets, initial_overflow, overflow, overflow_edges, overflow_3d (tracks), wirelength_gcells, "
      "vias, guides, iterations, reroutes, seconds.");
}
