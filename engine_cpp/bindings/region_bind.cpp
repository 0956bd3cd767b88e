// Python view of one routing region, steppable net by net: what a learning
// environment drives. A RoutingSession (loop/session.hpp) holds what every
// region of a design shares (tracks, pin access, fixed shapes); a Region
// routes the nets of one box in the order the caller chooses and can be
// committed to the design.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <array>
#include <memory>
#include <stdexcept>

#include "bindings/arrays.hpp"
#include "bindings/marker_list.hpp"
#include "bindings/region_handle.hpp"
#include "db/database.hpp"
#include "loop/regions.hpp"
#include "loop/router.hpp"
#include "loop/session.hpp"
#include "order/search_policy.hpp"
#include "region/region_router.hpp"

namespace nb = nanobind;
using namespace nb::literals;
using namespace xroute;

namespace {

// Views into the grid owned by the Region object `owner` (kept alive by them).
template <class T>
nb::object gridView(const RegionGrid& g, NodeArray<T>& v, nb::handle owner) {
  const size_t shape[3] = {size_t(g.nz()), size_t(g.ny()), size_t(g.nx())};
  return nb::cast(nb::ndarray<nb::numpy, T>(v.data(), 3, shape, owner), nb::rv_policy::reference);
}

// A copy of `at(node)` at every node (a sparse field, a derived one), shaped like gridView's.
template <class T, class At>
nb::ndarray<nb::numpy, T> gridCopy(const RegionGrid& g, At&& at) {
  auto* data = new std::vector<T>(g.size());
  for (size_t n = 0; n < g.size(); ++n) (*data)[n] = at(static_cast<int32_t>(n));
  nb::capsule owner(data, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  const size_t shape[3] = {size_t(g.nz()), size_t(g.ny()), size_t(g.nx())};
  return nb::ndarray<nb::numpy, T>(data->data(), 3, shape, owner);
}

nb::object coordView(const std::vector<Dbu>& v, nb::handle owner) {
  const size_t shape[1] = {v.size()};
  return nb::cast(nb::ndarray<nb::numpy, int32_t>(const_cast<Dbu*>(v.data()), 1, shape, owner),
                  nb::rv_policy::reference);
}

nb::dict netResultDict(const RegionNetResult& r) {
  nb::dict d;
  d["net"] = r.net;
  d["routed"] = r.routed;
  d["wirelength_dbu"] = r.added.wirelength();
  d["vias"] = r.added.vias.size();
  d["unreached"] = r.unreached;
  return d;
}

}  // namespace

namespace {

using RegionClass = nb::class_<RegionHandle>;

void bindRoutingSession(nb::module_& m) {
  nb::class_<RoutingSession>(m, "RoutingSession",
                             "What every region of one design shares: tracks, vias, pin access, fixed shapes.")
      .def(
          "__init__",
          [](RoutingSession* self, Database& db, int threads, const MazeCosts& costs) {
            nb::gil_scoped_release release;
            new (self) RoutingSession(db, threads, costs);
          },
          "db"_a, "threads"_a = 1, "costs"_a = MazeCosts(), nb::keep_alive<1, 2>(),
          "Prepares routing of a loaded Database (pin access is computed here, once); the regions it opens "
          "route with the maze's costs (default: the engine's).")
      .def_prop_ro(
          "gcell_lines",
          [](const RoutingSession& s) { return nb::make_tuple(s.gcells().xs, s.gcells().ys); },
          "The GCell grid lines (xs, ys) in DBU that regions align to.")
      .def(
          "regions",
          [](const RoutingSession& s, int size, int offset) {
            if (size < 1) throw nb::value_error("size must be >= 1");
            nb::list out;
            for (const Region& r : s.regions(size, offset)) {
              out.append(nb::make_tuple(nb::make_tuple(r.gx0, r.gy0),
                                        nb::make_tuple(r.box.xlo, r.box.ylo, r.box.xhi, r.box.yhi)));
            }
            return out;
          },
          "size"_a, "offset"_a = 0,
          "The router's partition into regions of size x size GCells (the first column and row shortened by "
          "offset), row by row: [((gcell column, row), (xlo, ylo, xhi, yhi) in DBU), ...].")
      .def(
          "open_region",
          [](RoutingSession& s, std::tuple<Dbu, Dbu, Dbu, Dbu> box, int iteration) {
            auto h = std::make_unique<RegionHandle>();
            h->session = &s;
            const Rect r = Rect::fromCorners({std::get<0>(box), std::get<1>(box)}, {std::get<2>(box), std::get<3>(box)});
            {
              nb::gil_scoped_release release;
              h->region = s.openRegion(r, iteration);
              h->box = r;
            }
            return h.release();
          },
          "box"_a, "iteration"_a = 0, nb::rv_policy::take_ownership, nb::keep_alive<0, 1>(),
          "Opens the region box (xlo, ylo, xhi, yhi) in DBU: nets with pins or routing inside, or whose guides "
          "cross its edges, become candidates (routed nets are ripped up inside the box).");
}

// Region: box, candidates, what is routed.
void bindRegionState(RegionClass& cls) {
  cls
      .def_prop_ro(
          "box",
          [](const RegionHandle& h) {
            const Rect& b = h.box;
            return nb::make_tuple(b.xlo, b.ylo, b.xhi, b.yhi);
          },
          "The region box (xlo, ylo, xhi, yhi) in DBU.")
      .def_prop_ro(
          "lent", [](const RegionHandle& h) { return h.lent; },
          "True for a region the router lends to a policy (valid during that call; no commit).")
      .def_prop_ro(
          "candidates",
          [](const RegionHandle& h) {
            return ownedInt32(featureRows(h.get().candidatesNow()), kFeatureCount);
          },
          nb::rv_policy::move, "int32[candidates, len(POLICY_FEATURES)]: one row per candidate net, columns as _engine.POLICY_FEATURES "
          "(routed_nearby as the region is now). In a first-pass region a net whose guides pass the region in two "
          "pieces joined elsewhere is two candidates (two parts, each its own tree).")
      .def_prop_ro(
          "route_order", [](const RegionHandle& h) { return h.get().routedOrder(); },
          "Candidate indices in the order they were routed so far (a search policy's: the order it kept).")
      .def(
          "is_routed", [](const RegionHandle& h, int32_t i) { return h.get().isRouted(h.candidate(i)); }, "index"_a,
          "Whether candidate i has been routed.")
      .def(
          "unrouted",
          [](const RegionHandle& h) {
            std::vector<int32_t> out;
            for (int32_t i = 0; i < static_cast<int32_t>(h.get().candidates().size()); ++i) {
              if (!h.get().isRouted(i)) out.push_back(i);
            }
            return out;
          },
          "Indices of the candidates not routed yet.");
}

// Region: routing nets: the maze, caller paths, the rest.
void bindRegionRouting(RegionClass& cls) {
  cls
      .def(
          "route_net",
          [](RegionHandle& h, int32_t i) {
            h.checkOpen();
            h.candidate(i);
            if (h.get().isRouted(i)) throw nb::value_error(("candidate " + std::to_string(i) + " is already routed").c_str());
            {
              nb::gil_scoped_release release;
              h.get().routeNet(i, h.region->ws);
            }
            return netResultDict(h.get().result(i));
          },
          "index"_a, "Routes candidate i now; returns its wirelength_dbu, vias and unreached terminals.")
      .def(
          "terminal_nodes",
          [](const RegionHandle& h, int32_t i) { return h.get().terminalNodes(h.candidate(i)); }, "index"_a,
          "Candidate i's terminals as the maze sees them: per terminal, its grid nodes (flat indices into the "
          "(nz, ny, nx) grid arrays; joined terminals first, the maze starts from the first). Reaching any node of "
          "a terminal connects it.")
      .def(
          "terminal_joined",
          [](const RegionHandle& h, int32_t i) { return h.get().terminalJoined(h.candidate(i)); }, "index"_a,
          "Per terminal of terminal_nodes(i): True when its nodes are one conductor (a pin's access points: all "
          "of them join the route once one is reached), False for alternatives (a free crossing: only the node "
          "reached joins).")
      .def(
          "moves",
          [](const RegionHandle& h, int32_t i, int32_t node) {
            std::array<MazeMove, kMoveCount> mv;
            h.get().moves(h.candidate(i), node, mv);
            std::vector<int32_t> nodes;
            std::vector<int64_t> costs;
            for (const MazeMove& m : mv) {
              nodes.push_back(m.node);
              costs.push_back(m.cost);
            }
            return nb::make_tuple(nodes, costs);
          },
          "index"_a, "node"_a,
          "The maze's six edges from grid node `node` for candidate i's net, by direction (0 up, 1 down, 2 north, "
          "3 south, 4 east, 5 west): (neighbour nodes, step costs in maze cost units); -1 where there is no edge. "
          "Wrong-way edges reach the next existing node.")
      .def(
          "route_net_paths",
          [](RegionHandle& h, int32_t i, std::vector<std::vector<int32_t>> paths) {
            h.checkOpen();
            h.candidate(i);
            if (h.get().isRouted(i)) throw nb::value_error(("candidate " + std::to_string(i) + " is already routed").c_str());
            try {
              nb::gil_scoped_release release;
              h.get().routeNetPaths(i, std::move(paths));
            } catch (const std::invalid_argument& e) {
              throw nb::value_error(e.what());
            }
            return netResultDict(h.get().result(i));
          },
          "index"_a, "paths"_a,
          "Routes candidate i along the caller's node paths (each step one edge of moves()) through the maze's "
          "own commit (wires, vias, min-area fix, grid marks); returns what route_net returns (unreached: "
          "terminals after the first that no path touches).")
      .def(
          "net_paths", [](const RegionHandle& h, int32_t i) { return h.get().paths(h.candidate(i)); }, "index"_a,
          "The node paths candidate i was routed along (by the maze or route_net_paths); empty before.")
      .def(
          "route_rest",
          [](RegionHandle& h, const std::string& policy, uint64_t seed, int search_budget, int search_width) {
            h.checkOpen();
            SearchSettings search;
            search.budget = search_budget;
            search.width = search_width;
            search.seed = seed;
            std::unique_ptr<NetOrderPolicy> p;
            try {
              p = makeBuiltinPolicy(policy, search);
            } catch (const std::invalid_argument& e) {
              throw nb::value_error(e.what());
            }
            nb::gil_scoped_release release;
            routeInOrder(h.get(), *p, h.region->ws);
          },
          "policy"_a = "heuristic", "seed"_a = 1, "search_budget"_a = SearchSettings{}.budget,
          "search_width"_a = SearchSettings{}.width,
          "Routes every candidate not routed yet in a built-in policy's order (heuristic, random, rollout, victims, bestof, "
          "best-of-K; the searches route trial orders on copies of the region and keep the cheapest).");
}

// Region: metrics.
void bindRegionResults(RegionClass& cls) {
  cls
      .def(
          "metrics",
          [](const RegionHandle& h) {
            int64_t wl = 0, vias = 0;
            int routed = 0, unreached = 0;
            for (int32_t i = 0; i < static_cast<int32_t>(h.get().candidates().size()); ++i) {
              const RegionNetResult& r = h.get().result(i);
              if (!r.routed) continue;
              ++routed;
              unreached += r.unreached;
              wl += r.added.wirelength();
              vias += static_cast<int64_t>(r.added.vias.size());
            }
            std::vector<Marker> markers;
            {
              nb::gil_scoped_release release;
              markers = h.get().check();
            }
            nb::dict byType;
            for (int t = 0; t < kMarkerTypes; ++t) byType[std::string(markerTypeName(static_cast<MarkerType>(t))).c_str()] = 0;
            for (const Marker& mk : markers) {
              const std::string k(markerTypeName(mk.type));
              byType[k.c_str()] = nb::cast<int>(byType[k.c_str()]) + 1;
            }
            nb::dict d;
            d["wirelength_dbu"] = wl;
            d["vias"] = vias;
            d["violations"] = markers.size();
            d["violations_by_type"] = byType;
            d["nets_routed"] = routed;
            d["unreached"] = unreached;
            return d;
          },
          "The new routing so far: wirelength_dbu, vias, nets_routed, unreached terminals, and the design-rule "
          "violations inside the box (fixed-only ones skipped).")
      .def(
          "markers",
          [](const RegionHandle& h) {
            std::vector<Marker> markers;
            {
              nb::gil_scoped_release release;
              markers = h.get().check();
            }
            return markerList(h.get().context().tech, markers);
          },
          "The design-rule markers metrics() counts (inside the box, fixed-only ones skipped), as dicts {type, "
          "layer, box: (xlo, ylo, xhi, yhi), nets: (n1, n2)}; net ids as in candidates' net column, -1 = an "
          "obstruction.");
}

// Region: grid views and commit.
void bindRegionGrid(RegionClass& cls) {
  cls
      .def(
          "grid",
          [](nb::handle self) {
            RegionHandle& h = nb::cast<RegionHandle&>(self);
            RegionGrid& g = const_cast<RegionGrid&>(h.get().grid());
            nb::dict d;
            d["xs"] = coordView(g.xs(), self);
            d["ys"] = coordView(g.ys(), self);
            d["flags"] = gridView(g, g.flags, self);
            d["fixed_owner"] = gridView(g, g.fixedOwner, self);
            d["via_fixed_owner"] = gridView(g, g.viaFixedOwner, self);
            d["wire_use"] = gridView(g, g.wireUse, self);
            d["via_use"] = gridView(g, g.viaUse, self);
            d["marker_cost"] = gridView(g, g.markerCost, self);
            d["access_net"] = nb::cast(gridCopy<int32_t>(g, [&](int32_t n) { return g.accessNet(n); }));
            d["access_pin"] = nb::cast(gridCopy<int32_t>(g, [&](int32_t n) { return g.accessPin(n); }));
            d["routed_net"] = gridView(g, g.routedNet, self);
            return d;
          },
          "Live numpy views of the region grid, each shaped (nz, ny, nx) (xs, ys: grid coordinates in DBU): flags "
          "(1 on track, 2 access point, 4 boundary terminal, 8 via landing above an access point, 16 access point "
          "whose via up pin access checked, 32 landing of a net already routed here: other nets' wires pass it "
          "freely; 0 = no node), "
          "fixed_owner / via_fixed_owner (-1 free, net allowed, -2 blocked), wire_use / via_use (routed shapes a "
          "wire / via there would violate), marker_cost, access_net, access_pin, routed_net (-1 = none). They stay "
          "valid while the Region lives and change as nets are routed (for a region lent to a policy: during that "
          "call only); access_net and access_pin, which do not change once the region is made, are copies.")
      .def(
          "node_type",
          [](const RegionHandle& h) {
            const RegionGrid& g = h.get().grid();
            return gridCopy<uint8_t>(g, [&](int32_t n) { return static_cast<uint8_t>(g.nodeType(n)); });
          },
          "uint8[nz, ny, nx]: 0 NOTEXIST, 1 BLOCKAGE, 2 NORMAL, 3 ACCESS (a copy).")
      .def(
          "commit",
          [](RegionHandle& h) {
            h.checkOpen();
            if (h.lent) throw std::runtime_error("a region lent to a policy is committed by the router, not by the policy");
            nb::gil_scoped_release release;
            h.session->commit(*h.region);
          },
          "Writes the region's new routing into the design (other open regions of the session become stale).");
}

}  // namespace

void bindRegion(nb::module_& m) {
  bindRoutingSession(m);
  RegionClass cls(m, "Region", "One routing region, routed net by net in the caller's order.");
  bindRegionState(cls);
  bindRegionRouting(cls);
  bindRegionResults(cls);
  bindRegionGrid(cls);
}
