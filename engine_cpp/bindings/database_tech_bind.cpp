// Python view of a Database's technology: layers with their rules, tracks,
// the GCell grid, LEF vias, via rules, sites and macro names.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include "bindings/arrays.hpp"
#include "bindings/database_parts.hpp"

namespace nb = nanobind;
using namespace nb::literals;

namespace xroute {

namespace {

const char* layerTypeName(LayerType t) {
  switch (t) {
    case LayerType::Routing: return "ROUTING";
    case LayerType::Cut: return "CUT";
    case LayerType::Masterslice: return "MASTERSLICE";
    case LayerType::Overlap: return "OVERLAP";
    case LayerType::Implant: return "IMPLANT";
    case LayerType::Other: return "OTHER";
  }
  return "OTHER";
}

const char* directionName(Direction d) {
  switch (d) {
    case Direction::Horizontal: return "HORIZONTAL";
    case Direction::Vertical: return "VERTICAL";
    case Direction::None: return "";
  }
  return "";
}

nb::dict layerDict(const Layer& l) {
  nb::dict d;
  d["name"] = l.name;
  d["type"] = layerTypeName(l.type);
  d["routing_index"] = l.routingIndex;
  d["cut_index"] = l.cutIndex;
  d["direction"] = directionName(l.direction);
  d["pitch"] = nb::make_tuple(l.pitchX, l.pitchY);
  d["offset"] = nb::make_tuple(l.offsetX, l.offsetY);
  d["width"] = l.width;
  d["min_width"] = l.minWidth;
  d["min_area"] = l.minArea;
  d["min_spacing"] = l.minSpacing();
  nb::list eols;
  for (const EolRule& e : l.eolRules) {
    nb::dict r;
    r["space"] = e.space;
    r["eol_width"] = e.eolWidth;
    r["within"] = e.within;
    r["parallel_edge"] = e.parallelEdge;
    r["par_space"] = e.parSpace;
    r["par_within"] = e.parWithin;
    r["two_edges"] = e.twoEdges;
    eols.append(r);
  }
  d["eol_rules"] = eols;
  nb::list spacings;
  for (const SpacingRule& s : l.spacings) {
    nb::dict r;
    r["space"] = s.space;
    r["range"] = s.hasRange ? nb::object(nb::make_tuple(s.rangeLo, s.rangeHi)) : nb::none();
    r["same_net"] = s.sameNet;
    spacings.append(r);
  }
  d["spacing_rules"] = spacings;
  nb::list cuts;
  for (const CutSpacingRule& c : l.cutSpacings) {
    nb::dict r;
    r["space"] = c.space;
    r["center_to_center"] = c.centerToCenter;
    r["same_net"] = c.sameNet;
    r["adjacent_cuts"] = c.adjacentCuts;
    r["cut_within"] = c.cutWithin;
    cuts.append(r);
  }
  d["cut_spacing_rules"] = cuts;
  nb::list corners;
  for (const CornerSpacingRule& c : l.cornerSpacings) {
    nb::dict r;
    r["convex_corner"] = c.convexCorner;
    r["concave_corner"] = c.concaveCorner;
    r["except_eol"] = c.exceptEol;
    r["eol_width"] = c.eolWidth;
    r["widths"] = c.widths;
    r["spacings"] = c.spacings;
    corners.append(r);
  }
  d["corner_spacing_rules"] = corners;
  nb::dict table;
  table["prls"] = l.prlTable.prls;
  table["widths"] = l.prlTable.widths;
  nb::list rows;
  const size_t cols = l.prlTable.prls.size();
  for (size_t i = 0; i < l.prlTable.widths.size() && cols; ++i) {
    rows.append(std::vector<Dbu>(l.prlTable.spacing.begin() + i * cols,
                                 l.prlTable.spacing.begin() + (i + 1) * cols));
  }
  table["spacing"] = rows;
  d["spacing_table"] = table;
  nb::list props;
  for (const auto& [k, v] : l.properties) props.append(nb::make_tuple(k, v));
  d["properties"] = props;
  return d;
}

}  // namespace

// Database: layers, tracks, GCell grid.
void bindDatabaseTechnology(DatabaseClass& cls) {
  cls
      .def(
          "layers", [](const Database& d) {
            nb::list out;
            for (const Layer& l : d.tech.layers) out.append(layerDict(l));
            return out;
          },
          "Every LEF layer in order, as dicts (lengths in DBU, areas in DBU^2).")
      .def(
          "tracks",
          [](const Database& d) {
            nb::list out;
            for (const TrackPattern& t : d.design.tracks) {
              nb::dict r;
              r["layer"] = d.tech.layer(t.layer).name;
              r["axis"] = t.isX ? "X" : "Y";
              r["start"] = t.start;
              r["count"] = t.count;
              r["step"] = t.step;
              out.append(r);
            }
            return out;
          },
          "DEF TRACKS statements as dicts (DBU).")
      .def(
          "gcell_lines",
          [](const Database& d, const std::string& axis) {
            if (axis != "x" && axis != "y") throw nb::value_error("axis must be 'x' or 'y'");
            std::vector<Dbu> lines = gcellLines(d.design, axis == "x");
            return ownedInt32(std::vector<int32_t>(lines.begin(), lines.end()), 1);
          },
          "axis"_a, "GCell grid line coordinates along 'x' or 'y' (DBU, sorted); empty without GCELLGRID.");
}

// Database: LEF vias, via rules, sites, macro names.
void bindDatabaseVias(DatabaseClass& cls) {
  cls
      .def(
          "via",
          [](const Database& d, const std::string& name) {
            const ViaId id = d.tech.findVia(name);
            if (!id.valid()) throw nb::key_error(("no LEF via named " + name).c_str());
            const Via& v = d.tech.vias[*id];
            auto layerName = [&](LayerId l) { return l.valid() ? d.tech.layer(l).name : std::string(); };
            nb::dict r;
            r["name"] = v.name;
            r["default"] = v.isDefault;
            r["bottom"] = layerName(v.bottom);
            r["cut"] = layerName(v.cut);
            r["top"] = layerName(v.top);
            nb::list shapes;
            for (const ViaShape& s : v.shapes) {
              shapes.append(nb::make_tuple(d.tech.layer(s.layer).name, s.rect.xlo, s.rect.ylo, s.rect.xhi, s.rect.yhi));
            }
            r["shapes"] = shapes;
            return r;
          },
          "name"_a, "A LEF VIA: default flag, bottom/cut/top layer names and shapes (layer, xlo, ylo, xhi, yhi) in DBU.")
      .def(
          "via_rule",
          [](const Database& d, const std::string& name) {
            const ViaRuleId id = d.tech.findViaRule(name);
            if (!id.valid()) throw nb::key_error(("no VIARULE named " + name).c_str());
            const ViaRule& v = d.tech.viaRules[*id];
            nb::dict r;
            r["name"] = v.name;
            r["generate"] = v.generate;
            r["default"] = v.isDefault;
            nb::list layers;
            for (const ViaRuleLayer& l : v.layers) {
              nb::dict ld;
              ld["layer"] = d.tech.layer(l.layer).name;
              ld["enclosure"] = nb::make_tuple(l.enclosure1, l.enclosure2);
              ld["width"] = l.hasWidth ? nb::object(nb::make_tuple(l.widthLo, l.widthHi)) : nb::none();
              ld["rect"] = rectTuple(l.cutRect);
              ld["spacing"] = nb::make_tuple(l.spacingX, l.spacingY);
              layers.append(ld);
            }
            r["layers"] = layers;
            return r;
          },
          "name"_a, "A LEF VIARULE: generate/default flags and its layers in order (DBU).")
      .def(
          "sites",
          [](const Database& d) {
            nb::list out;
            for (const Site& s : d.tech.sites) {
              nb::dict r;
              r["name"] = s.name;
              r["class"] = s.siteClass;
              r["size"] = nb::make_tuple(s.width, s.height);
              r["symmetry"] = s.symmetry;
              out.append(r);
            }
            return out;
          },
          "LEF SITEs in order: name, class, size (DBU), symmetry.")
      .def(
          "macro_names",
          [](const Database& d) {
            std::vector<std::string> names;
            for (const Macro& m : d.tech.macros) names.push_back(m.name);
            return names;
          },
          "LEF macro names in order.");
}

}  // namespace xroute
