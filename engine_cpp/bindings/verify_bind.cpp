// Python view of the routed-design verification: connectivity (opens),
// routing metrics and the DRC report file, as methods of Database returning
// plain dicts. The work runs without the GIL.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/optional.h>

#include <string>
#include <vector>

#include "bindings/marker_list.hpp"
#include "db/database.hpp"
#include "drc/design_check.hpp"
#include "drc/drc.hpp"
#include "verify/connectivity.hpp"
#include "verify/drc_report.hpp"
#include "verify/metrics.hpp"
#include "verify/scoring.hpp"

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

namespace {

using DatabaseClass = nb::class_<Database>;

// Opens and metrics of the routing a Database holds.
void bindConnectivity(DatabaseClass& cls) {
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
}

// Everything a routed design is judged on (xroute check).
void bindCheckRouting(DatabaseClass& cls) {
  cls.def(
      "check_routing",
      [](const Database& db, bool skip_fixed_pairs, const std::string& report_path, int threads) {
        ConnectivityReport conn;
        RoutingMetrics metrics;
        GuideTrackFigures figures;
        std::vector<Marker> markers;
        {
          nb::gil_scoped_release release;
          conn = checkConnectivity(db.tech, db.design);
          metrics = computeMetrics(db.tech, db.design);
          figures = computeGuideTrackFigures(db.tech, db.design);
          DrcOptions options;
          options.skipFixedPairs = skip_fixed_pairs;
          options.ndrSpacing = ndrSpacingByNet(db.tech, db.design);
          options.threads = threads;
          std::vector<std::string> names;
          markers = checkDesign(db.tech, db.design, options, &names);
          if (!report_path.empty()) writeDrcReport(report_path, db.tech, markers, names);  // the same markers
        }
        const int dbu = db.design.dbuPerMicron > 0 ? db.design.dbuPerMicron : db.tech.dbuPerMicron;
        auto um = [&](int64_t v) { return dbu > 0 ? double(v) / dbu : 0.0; };
        nb::dict d;
        d["opens"] = conn.openNets;
        d["connectivity"] = connectivityDict(db, conn);
        d["markers"] = markerList(db.tech, markers);
        d["wirelength_dbu"] = metrics.wirelength;
        d["wirelength_um"] = metrics.wirelengthMicrons;
        d["vias"] = metrics.vias;
        d["wrong_way_wirelength_dbu"] = figures.wrongWayWirelength;
        d["wrong_way_wirelength_um"] = um(figures.wrongWayWirelength);
        d["off_track_wirelength_dbu"] = figures.offTrackWirelength;
        d["off_track_wirelength_um"] = um(figures.offTrackWirelength);
        d["off_track_vias"] = figures.offTrackVias;
        d["has_guides"] = figures.hasGuides;
        d["scorer_pitch_dbu"] = scorerPitch(db.tech);
        if (figures.hasGuides) {
          d["out_of_guide_wirelength_dbu"] = figures.outOfGuideWirelength;
          d["out_of_guide_wirelength_um"] = um(figures.outOfGuideWirelength);
          d["out_of_guide_vias"] = figures.outOfGuideVias;
        } else {
          d["out_of_guide_wirelength_dbu"] = nb::none();
          d["out_of_guide_wirelength_um"] = nb::none();
          d["out_of_guide_vias"] = nb::none();
        }
        return d;
      },
      "skip_fixed_pairs"_a = true, "report_path"_a = "", "threads"_a = 1,
      "Everything a routed design is judged on, in one call (the engine side of `xroute check`); with\n"
      "report_path, also writes the markers found as write_drc_report does (no second check). threads:\n"
      "layers checked at once (the result does not depend on it).\n\n"
      "Regular nets (NETS) only, except the markers (the whole design, as check_drc). Returns {opens\n"
      "(open nets), connectivity (check_connectivity's dict), markers (check_drc's list),\n"
      "wirelength_dbu/_um and vias (as metrics), wrong_way_wirelength_dbu/_um, off_track_wirelength_dbu/\n"
      "_um, off_track_vias, scorer_pitch_dbu (the contest score's unit of length: the LEF PITCH of the\n"
      "second routing layer), has_guides, out_of_guide_wirelength_dbu/_um and out_of_guide_vias (None\n"
      "without a guide file)}. A wire piece (from != to; length |to - from|, extensions not counted) is\n"
      "wrong-way when it runs across its layer's DIRECTION; off-track when its centre line lies on no\n"
      "track line of its layer parallel to it (TRACKS Y lines for a horizontal piece, TRACKS X for a\n"
      "vertical one; a layer with no such lines counts none); out-of-guide for the part of its centre\n"
      "line outside the union of its net's guides on its layer (closed rects). A via is off-track when\n"
      "its point is off the preferred-direction tracks of its bottom or top metal layer (y on a TRACKS Y\n"
      "line of a horizontal layer, x on a TRACKS X line of a vertical one), and out-of-guide when no\n"
      "guide of its net on its bottom metal, or none on its top metal, contains its point.");
}

// The marker report file.
void bindDrcReport(DatabaseClass& cls) {
  cls.def(
      "write_drc_report",
      [](const Database& db, const std::string& path, bool skip_fixed_pairs, int threads) {
        std::array<int64_t, kMarkerTypes> counts;
        {
          nb::gil_scoped_release release;
          std::vector<std::string> names;
          DrcOptions options;
          options.skipFixedPairs = skip_fixed_pairs;
          options.ndrSpacing = ndrSpacingByNet(db.tech, db.design);  // as check_routing judges
          options.threads = threads;
          const std::vector<Marker> markers = checkDesign(db.tech, db.design, options, &names);
          writeDrcReport(path, db.tech, markers, names);
          counts = countMarkers(markers);
        }
        nb::dict d;
        for (int t = 0; t < kMarkerTypes; ++t) d[nb::str(std::string(markerTypeName(MarkerType(t))).c_str())] = counts[t];
        return d;
      },
      "path"_a, "skip_fixed_pairs"_a = true, "threads"_a = 1,
      "Design-rule check of the whole design (as check_drc), written to `path` atomically (threads:\n"
      "layers checked at once, the result does not depend on it): a header\n"
      "'# markers N <type> <count> ...' then one line per marker '<type> <layer> <xlo> <ylo> <xhi> <yhi>\n"
      "<net1> <net2>' (DBU; net names, '-' for none or an obstruction; pins on no net as comp/pin,\n"
      "*/pin or PIN/name). Returns {marker type: count} for every type. Raises InputError when the\n"
      "file cannot be written (nothing is left behind).");
}

}  // namespace

void bindVerify(nb::module_& m) {
  nb::class_<Database> cls = nb::borrow<nb::class_<Database>>(nb::type<Database>());
  bindConnectivity(cls);
  bindCheckRouting(cls);
  bindDrcReport(cls);
}
