// Python view of the routed-design verification: connectivity (opens),
// routing metrics and the DRC report file, as methods of Database returning
// plain dicts. The work runs without the GIL.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>

#include <string>
#include <vector>

#include "db/database.hpp"
#include "drc/drc.hpp"
#include "verify/connectivity.hpp"
#include "verify/drc_report.hpp"
#include "verify/metrics.hpp"

namespace nb = nanobind;
using namespace nb::literals;

namespace xroute {
namespace {

// (component, pin) names of a net's pin; an IO pin is ("PIN", name) as in DEF.
nb::tuple pinNames(const Tech& tech, const Design& design, int32_t pinRef) {
  const PinRef& ref = design.pinRefs[pinRef];
  if (ref.isIo()) return nb::make_tuple("PIN", design.ioPins[ref.pin].name);
  const Component& comp = design.components[*ref.comp];
  return nb::make_tuple(comp.name, tech.macros[*comp.macro].pins[ref.pin].name);
}

nb::dict connectivityDict(const Database& db, const ConnectivityReport& report) {
  nb::list opens;
  for (const NetConnectivity& n : report.nets) {
    if (!n.open) continue;
    nb::list groups;
    for (const std::vector<int32_t>& g : n.groups) {
      nb::list pins;
      for (int32_t r : g) pins.append(pinNames(db.tech, db.design, r));
      groups.append(pins);
    }
    nb::dict d;
    d["net"] = db.design.nets[*n.net].name;
    d["pins"] = n.pinCount;
    d["groups"] = groups;
    d["floating_pieces"] = n.floatingPieces;
    opens.append(d);
  }
  nb::dict d;
  d["nets_checked"] = report.netsChecked;
  d["open_nets"] = report.openNets;
  d["single_pin_nets"] = report.singlePinNets;
  d["unrouted_nets"] = report.unroutedNets;
  d["floating_pieces"] = report.floatingPieces;
  d["opens"] = opens;
  return d;
}

nb::dict metricsDict(const Tech& tech, const RoutingMetrics& m) {
  nb::dict byLayer, byCut;
  for (LayerId l : tech.routingLayers) byLayer[nb::str(tech.layer(l).name.c_str())] = m.layerWirelength[*l];
  for (LayerId l : tech.cutLayers) byCut[nb::str(tech.layer(l).name.c_str())] = m.cutLayerVias[*l];
  nb::dict d;
  d["wirelength_dbu"] = m.wirelength;
  d["wirelength_um"] = m.wirelengthMicrons;
  d["wirelength_by_layer"] = byLayer;
  d["vias"] = m.vias;
  d["vias_by_cut_layer"] = byCut;
  d["nets_routed"] = m.netsRouted;
  return d;
}

}  // namespace
}  // namespace xroute

using namespace xroute;

void bindVerify(nb::module_& m) {
  nb::class_<Database> cls = nb::borrow<nb::class_<Database>>(nb::type<Database>());
  cls.def(
      "check_connectivity",
      [](const Database& db) {
        ConnectivityReport report;
        {
          nb::gil_scoped_release release;
          report = checkConnectivity(db.tech, db.design);
        }
        return connectivityDict(db, report);
      },
      "Opens check of every regular net with >= 2 pins: are its pins joined by its routing?\n\n"
      "Conductors: pin shapes (one node per pin), wires (half-width or given extensions), vias (one node\n"
      "each), patches; same-layer shapes connect when they overlap or share an edge segment (a corner\n"
      "point does not), layers connect only through vias. Returns {nets_checked, open_nets,\n"
      "single_pin_nets (fewer than 2 pins, not checked), unrouted_nets (checked nets without routing),\n"
      "floating_pieces (routing components touching no pin), opens: [{net, pins, groups, floating_pieces}]}\n"
      "where groups lists the connected pin groups, each a list of (component, pin) names\n"
      "((\"PIN\", name) for an IO pin), groups ordered by their first pin in the net.");
  cls.def(
      "metrics",
      [](const Database& db) {
        RoutingMetrics metrics;
        {
          nb::gil_scoped_release release;
          metrics = computeMetrics(db.tech, db.design);
        }
        return metricsDict(db.tech, metrics);
      },
      "Routing metrics of the regular nets: {wirelength_dbu (sum of wire piece lengths, extensions not\n"
      "counted), wirelength_um, wirelength_by_layer {routing layer: DBU}, vias (instances),\n"
      "vias_by_cut_layer {cut layer: count}, nets_routed (nets with any routing)}.");
  cls.def(
      "write_drc_report",
      [](const Database& db, const std::string& path, bool skip_fixed_pairs) {
        std::array<int64_t, kMarkerTypeCount> counts;
        {
          nb::gil_scoped_release release;
          std::vector<std::string> names;
          std::vector<DrcShape> shapes = collectDesignShapes(db.tech, db.design, &names);
          DrcOptions options;
          options.skipFixedPairs = skip_fixed_pairs;
          const std::vector<Marker> markers = checkShapes(db.tech, std::move(shapes), options);
          writeDrcReport(path, db.tech, markers, names);
          counts = countMarkers(markers);
        }
        nb::dict d;
        for (int t = 0; t < kMarkerTypeCount; ++t) d[nb::str(std::string(markerTypeName(MarkerType(t))).c_str())] = counts[t];
        return d;
      },
      "path"_a, "skip_fixed_pairs"_a = true,
      "Design-rule check of the whole design (as check_drc), written to `path` atomically: a header\n"
      "'# markers N <type> <count> ...' then one line per marker '<type> <layer> <xlo> <ylo> <xhi> <yhi>\n"
      "<net1> <net2>' (DBU; net names, '-' for none or an obstruction; pins on no net as comp/pin,\n"
      "*/pin or PIN/name). Returns {marker type: count} for every type. Raises InputError when the\n"
      "file cannot be written (nothing is left behind).");
}
