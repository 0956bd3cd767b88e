// Python view of a loaded Database: counts and summaries as small dicts and
// lists, big arrays as zero-copy numpy views owned by the Database object.
// The technology's views are in database_tech_bind.cpp.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <map>
#include <optional>

#include "bindings/arrays.hpp"
#include "bindings/database_parts.hpp"
#include "db/compare.hpp"
#include "db/database.hpp"
#include "io/readers.hpp"
#include "loop/dangling.hpp"

namespace nb = nanobind;
using namespace nb::literals;

namespace xroute {
namespace {

const char* statusName(PlaceStatus s) {
  switch (s) {
    case PlaceStatus::Unplaced: return "UNPLACED";
    case PlaceStatus::Placed: return "PLACED";
    case PlaceStatus::Fixed: return "FIXED";
    case PlaceStatus::Cover: return "COVER";
  }
  return "UNPLACED";
}

nb::list shapeList(const Tech& tech, const std::vector<MacroShape>& shapes) {
  nb::list out;
  for (const MacroShape& s : shapes) {
    out.append(nb::make_tuple(tech.layer(s.layer).name, s.rect.xlo, s.rect.ylo, s.rect.xhi, s.rect.yhi));
  }
  return out;
}

const Component& componentByName(const Database& db, const std::string& name) {
  const CompId id = db.design.findComponent(name);
  if (!id.valid()) throw nb::key_error(("no component named " + name).c_str());
  return db.design.components[*id];
}

NetId netByIndex(const Database& db, int32_t net) {
  if (net < 0 || net >= static_cast<int32_t>(db.design.nets.size())) throw nb::index_error("net index out of range");
  return NetId(net);
}

void addCounts(std::map<std::string, int>& into, const std::vector<std::pair<std::string, int>>& from) {
  for (const auto& [k, v] : from) into[k] += v;
}

}  // namespace
}  // namespace xroute

using namespace xroute;

namespace {

// Database: files, units, die, counts, warnings.
void bindDatabaseSummary(DatabaseClass& cls) {
  cls
      .def_prop_ro("design_name", [](const Database& d) { return d.design.name; }, "DESIGN name from the DEF.")
      .def_prop_ro("lef_paths", [](const Database& d) { return d.lefPaths; }, "LEF files read, in order.")
      .def_prop_ro("def_path", [](const Database& d) { return d.design.path; }, "DEF file read.")
      .def_prop_ro("guide_path", [](const Database& d) { return d.guidePath; }, "Guide file read, or ''.")
      .def_prop_ro("dbu_per_micron", [](const Database& d) { return d.design.dbuPerMicron; },
                   "DEF UNITS DISTANCE MICRONS.")
      .def_prop_ro("lef_dbu_per_micron", [](const Database& d) { return d.tech.dbuPerMicron; },
                   "LEF UNITS DATABASE MICRONS.")
      .def_prop_ro("manufacturing_grid", [](const Database& d) { return d.tech.manufacturingGrid; },
                   "MANUFACTURINGGRID in DBU (0 if none).")
      .def_prop_ro("die_area",
                   [](const Database& d) {
                     const Rect& r = d.design.dieArea;
                     return std::tuple<Dbu, Dbu, Dbu, Dbu>(r.xlo, r.ylo, r.xhi, r.yhi);
                   },
                   "DIEAREA bounding box (xlo, ylo, xhi, yhi) in DBU.")
      .def(
          "counts",
          [](const Database& d) {
            nb::typed<nb::dict, nb::str, int> c;
            c["layers"] = d.tech.layers.size();
            c["routing_layers"] = d.tech.routingLayers.size();
            c["cut_layers"] = d.tech.cutLayers.size();
            c["lef_vias"] = d.tech.vias.size();
            c["via_rules"] = d.tech.viaRules.size();
            c["sites"] = d.tech.sites.size();
            c["macros"] = d.tech.macros.size();
            c["rows"] = d.design.rows.size();
            c["tracks"] = d.design.tracks.size();
            c["gcell_patterns"] = d.design.gcellGrid.size();
            c["def_vias"] = d.design.vias.size();
            c["components"] = d.design.components.size();
            c["io_pins"] = d.design.ioPins.size();
            c["blockages"] = d.design.blockages.size();
            c["special_nets"] = d.design.specialNets.size();
            c["nets"] = d.design.nets.size();
            c["net_pins"] = d.design.pinRefs.size();
            c["guides"] = d.design.guideRects.size();
            size_t wires = 0, vias = 0;
            for (const Net& n : d.design.nets) {
              wires += n.routing.wires.size();
              vias += n.routing.vias.size();
            }
            c["route_wires"] = wires;
            c["route_vias"] = vias;
            return c;
          },
          "Counts of everything read, by kind.")
      .def(
          "skipped_statements",
          [](const Database& d) {
            std::map<std::string, int> all;
            addCounts(all, d.tech.skippedStatements);
            addCounts(all, d.design.skippedStatements);
            return all;
          },
          "Statements the readers skipped (not understood), keyword -> count.")
      .def(
          "unjudged_rules",
          [](const Database& d) {
            std::vector<std::pair<std::string, std::string>> out;
            for (const Layer& l : d.tech.layers)
              for (const std::string& rule : l.unjudged) out.emplace_back(l.name, rule);
            return out;
          },
          "The rules the LEF states on metal and cut layers that the checker does not judge, as "
          "(layer, rule) pairs in LEF order: skipped statements and forms (MINSTEP, SPACING "
          "NOTCHLENGTH, SPACINGTABLE TWOWIDTHS, ...), LEF58 properties other than the corner "
          "spacing it models, and rules kept for the router only (MINWIDTH, SPACING SAMENET).")
      .def_prop_ro("warning_count", [](const Database& d) { return d.tech.warningCount + d.design.warningCount; },
                   "Warnings raised while reading (LEF + DEF).")
      .def(
          "warnings",
          [](const Database& d) {
            std::vector<std::string> all = d.tech.warnings;
            all.insert(all.end(), d.design.warnings.begin(), d.design.warnings.end());
            return all;
          },
          "Odd but routable things found after reading, one 'file:line: message' each.");
}

// Database: nets, pins, guides.
void bindDatabaseNets(DatabaseClass& cls) {
  cls
      .def(
          "net_names",
          [](const Database& d) {
            std::vector<std::string> names;
            names.reserve(d.design.nets.size());
            for (const Net& n : d.design.nets) names.push_back(n.name);
            return names;
          },
          "Net names in DEF order (index = net id).")
      .def("net_id", [](const Database& d, const std::string& name) { return *d.design.findNet(name); }, "name"_a,
           "Net id by name, -1 if absent.")
      .def_prop_ro(
          "net_pin_start",
          [](const Database& d) { return int32View(d.design.netPinStart.data(), d.design.netPinStart.size(), 1); },
          nb::rv_policy::reference_internal, "int32[nets+1]: net i owns pin_refs[start[i]:start[i+1]].")
      .def_prop_ro(
          "pin_refs", [](const Database& d) { return int32View(d.design.pinRefs.data(), d.design.pinRefs.size(), 2); },
          nb::rv_policy::reference_internal,
          "int32[pins, 2]: (component id or -1 for an IO pin, macro pin index or IO pin id).")
      .def_prop_ro(
          "guide_start",
          [](const Database& d) { return int32View(d.design.guideStart.data(), d.design.guideStart.size(), 1); },
          nb::rv_policy::reference_internal, "int32[nets+1] (empty without guides): net i owns guide rows.")
      .def_prop_ro(
          "guide_rects",
          [](const Database& d) { return int32View(d.design.guideRects.data(), d.design.guideRects.size(), 4); },
          nb::rv_policy::reference_internal, "int32[guides, 4]: xlo, ylo, xhi, yhi in DBU.")
      .def_prop_ro(
          "guide_layers",
          [](const Database& d) { return int32View(d.design.guideLayers.data(), d.design.guideLayers.size(), 1); },
          nb::rv_policy::reference_internal, "int32[guides]: LEF layer index of each guide.")
      .def(
          "net_pins",
          [](const Database& d, int32_t net) {
            const NetId n = netByIndex(d, net);
            nb::list out;
            for (int32_t r = d.design.netPinStart[*n]; r < d.design.netPinStart[*n + 1]; ++r) {
              const PinRef& ref = d.design.pinRefs[r];
              if (ref.isIo()) {
                out.append(nb::make_tuple("PIN", d.design.ioPins[ref.pin].name));
              } else {
                const Component& c = d.design.components[*ref.comp];
                out.append(nb::make_tuple(c.name, d.tech.macros[*c.macro].pins[ref.pin].name));
              }
            }
            return out;
          },
          "net"_a, "The pins of a net as (component, pin) pairs; IO pins as ('PIN', name).")
      .def(
          "net_pin_shapes",
          [](const Database& d, int32_t net) {
            const NetId n = netByIndex(d, net);
            std::vector<PlacedShape> shapes;
            {
              nb::gil_scoped_release release;
              shapes = netPinShapes(d.tech, d.design, n);
            }
            std::vector<int32_t> flat;
            flat.reserve(shapes.size() * 6);
            for (const PlacedShape& s : shapes) {
              const int32_t row[6] = {s.pinRef - d.design.netPinStart[*n], *s.layer, s.rect.xlo, s.rect.ylo,
                                      s.rect.xhi, s.rect.yhi};
              flat.insert(flat.end(), row, row + 6);
            }
            return ownedInt32(std::move(flat), 6);
          },
          "net"_a,
          "int32[shapes, 6]: (pin index within the net, LEF layer index, xlo, ylo, xhi, yhi) in DBU, placed.");
}

// Database: components and macros.
void bindDatabaseLibrary(DatabaseClass& cls) {
  cls
      .def(
          "component",
          [](const Database& d, const std::string& name) {
            const Component& c = componentByName(d, name);
            nb::dict r;
            r["name"] = c.name;
            r["macro"] = d.tech.macros[*c.macro].name;
            r["location"] = nb::make_tuple(c.location.x, c.location.y);
            r["orient"] = std::string(orientName(c.orient));
            r["status"] = statusName(c.status);
            return r;
          },
          "name"_a, "A component's macro, location (DBU), orientation and status.")
      .def(
          "component_pin_shapes",
          [](const Database& d, const std::string& comp, const std::string& pin) {
            const Component& c = componentByName(d, comp);
            const Macro& m = d.tech.macros[*c.macro];
            auto it = m.pinIndex.find(pin);
            if (it == m.pinIndex.end()) throw nb::key_error(("macro " + m.name + " has no pin " + pin).c_str());
            const Transform t = componentTransform(d.tech, c);
            nb::list out;
            for (const MacroShape& s : m.pins[it->second].shapes) {
              const Rect r = t.apply(s.rect);
              out.append(nb::make_tuple(d.tech.layer(s.layer).name, r.xlo, r.ylo, r.xhi, r.yhi));
            }
            return out;
          },
          "component"_a, "pin"_a, "A component pin's shapes placed in design coordinates: (layer, xlo, ylo, xhi, yhi).")
      .def(
          "macro",
          [](const Database& d, const std::string& name) {
            const MacroId id = d.tech.findMacro(name);
            if (!id.valid()) throw nb::key_error(("no macro named " + name).c_str());
            const Macro& m = d.tech.macros[*id];
            nb::dict r;
            r["name"] = m.name;
            r["class"] = m.macroClass;
            r["origin"] = nb::make_tuple(m.origin.x, m.origin.y);
            r["size"] = nb::make_tuple(m.width, m.height);
            r["site"] = m.site;
            nb::dict pins;
            for (const MacroPin& p : m.pins) {
              nb::dict pd;
              pd["direction"] = p.direction;
              pd["use"] = p.use;
              pd["port_count"] = p.portCount;
              pd["shapes"] = shapeList(d.tech, p.shapes);
              pins[p.name.c_str()] = pd;
            }
            r["pins"] = pins;
            r["obstructions"] = shapeList(d.tech, m.obstructions);
            return r;
          },
          "name"_a, "A LEF macro: class, origin, size, pins (with shapes in macro coordinates, DBU) and OBS.");
}

// Database: DEF vias, IO pins, special nets.
void bindDatabaseDefObjects(DatabaseClass& cls) {
  cls
      .def(
          "def_via",
          [](const Database& d, const std::string& name) {
            auto it = d.design.viaIndex.find(name);
            if (it == d.design.viaIndex.end()) throw nb::key_error(("no DEF via named " + name).c_str());
            const DefVia& v = d.design.vias[*it->second];
            auto layerName = [&](LayerId l) { return l.valid() ? d.tech.layer(l).name : std::string(); };
            nb::dict r;
            r["name"] = v.via.name;
            r["generated"] = v.generated;
            r["rule"] = v.rule.valid() ? d.tech.viaRules[*v.rule].name : std::string();
            r["rowcol"] = nb::make_tuple(v.rows, v.cols);
            r["bottom"] = layerName(v.via.bottom);
            r["cut"] = layerName(v.via.cut);
            r["top"] = layerName(v.via.top);
            nb::list shapes;
            for (const ViaShape& s : v.via.shapes) {
              shapes.append(nb::make_tuple(d.tech.layer(s.layer).name, s.rect.xlo, s.rect.ylo, s.rect.xhi, s.rect.yhi));
            }
            r["shapes"] = shapes;
            return r;
          },
          "name"_a, "A DEF VIAS entry: generated flag, rule, (rows, cols), layers and shapes (layer, xlo, ylo, xhi, yhi) in DBU.")
      .def(
          "io_pin",
          [](const Database& d, const std::string& name) {
            auto it = d.design.ioPinIndex.find(name);
            if (it == d.design.ioPinIndex.end()) throw nb::key_error(("no IO pin named " + name).c_str());
            const IoPin& p = d.design.ioPins[*it->second];
            nb::dict r;
            r["name"] = p.name;
            r["net"] = p.netName;
            r["net_id"] = *p.net;
            r["direction"] = p.direction;
            r["use"] = p.use;
            r["status"] = statusName(p.status);
            r["location"] = nb::make_tuple(p.location.x, p.location.y);
            r["orient"] = std::string(orientName(p.orient));
            const Transform t{p.location, p.orient, 0, 0};
            nb::list shapes;
            for (const IoPinShape& s : p.shapes) {
              const Rect q = t.apply(s.rect);
              shapes.append(nb::make_tuple(d.tech.layer(s.layer).name, q.xlo, q.ylo, q.xhi, q.yhi));
            }
            r["shapes"] = shapes;
            return r;
          },
          "name"_a, "A DEF PINS entry; shapes placed in design coordinates: (layer, xlo, ylo, xhi, yhi).")
      .def(
          "special_net",
          [](const Database& d, const std::string& name) {
            for (const SpecialNet& n : d.design.specialNets) {
              if (n.name != name) continue;
              nb::dict r;
              r["name"] = n.name;
              r["use"] = n.use;
              nb::list pins, wires, vias, rects;
              for (const auto& [c, p] : n.pins) pins.append(nb::make_tuple(c, p));
              for (const SpecialWire& w : n.wires) {
                wires.append(nb::make_tuple(d.tech.layer(w.layer).name, w.width, w.shape, w.from.x, w.from.y, w.to.x,
                                            w.to.y));
              }
              for (const SpecialVia& v : n.vias) {
                vias.append(nb::make_tuple(d.design.via(d.tech, v.via).name, v.at.x, v.at.y, v.shape));
              }
              for (const RoutePatch& p : n.rects) {
                rects.append(nb::make_tuple(d.tech.layer(p.layer).name, p.rect.xlo, p.rect.ylo, p.rect.xhi, p.rect.yhi));
              }
              r["pins"] = pins;
              r["wires"] = wires;
              r["vias"] = vias;
              r["rects"] = rects;
              return r;
            }
            throw nb::key_error(("no special net named " + name).c_str());
          },
          "name"_a,
          "A SPECIALNETS entry: pins, wires (layer, width, shape, x1, y1, x2, y2), vias (name, x, y, shape), "
          "rects (layer, xlo, ylo, xhi, yhi); DBU.");
}

// Database: routing, writing, comparing.
void bindDatabaseRouting(DatabaseClass& cls) {
  cls
      .def(
          "net_routing",
          [](const Database& d, int32_t net) {
            const NetId n = netByIndex(d, net);
            const NetRouting& rt = d.design.nets[*n].routing;
            nb::list wires, vias, patches;
            for (const RouteWire& w : rt.wires) {
              wires.append(nb::make_tuple(d.tech.layer(w.layer).name, w.from.x, w.from.y, w.to.x, w.to.y, w.width,
                                          w.extFrom, w.extTo));
            }
            for (const RouteVia& v : rt.vias) vias.append(nb::make_tuple(d.design.via(d.tech, v.via).name, v.at.x, v.at.y));
            for (const RoutePatch& p : rt.patches) {
              patches.append(nb::make_tuple(d.tech.layer(p.layer).name, p.rect.xlo, p.rect.ylo, p.rect.xhi, p.rect.yhi));
            }
            nb::dict r;
            r["wires"] = wires;
            r["vias"] = vias;
            r["patches"] = patches;
            return r;
          },
          "net"_a,
          "A net's routing: wires (layer, x1, y1, x2, y2, width, ext_from, ext_to; width 0 = default, ext -1 = "
          "half width), vias (name, x, y), patches (layer, xlo, ylo, xhi, yhi); DBU.")
      .def(
          "trim_dangling",
          [](Database& d) {
            TrimCounts sum;
            {
              nb::gil_scoped_release release;
              sum = trimDanglingAll(d.tech, d.design);
            }
            nb::dict r;
            r["wires"] = sum.wires;
            r["shortened"] = sum.shortened;
            r["vias"] = sum.vias;
            r["patches"] = sum.patches;
            r["length_dbu"] = sum.length;
            return r;
          },
          "Cuts every net's routing back to what joins its pins, as the flow does after each iteration:\n"
          "a wire's end past the last thing it meets on its centre line (another wire or via of the net,\n"
          "or a pin shape) goes back to it, or the wire goes; a via with nothing on one of its layers\n"
          "goes; then a patch touching none of the net's metal goes. Returns {wires (removed), shortened,\n"
          "vias, patches, length_dbu (centre line removed)}.")
      .def(
          "write_def",
          [](const Database& d, const std::string& path) {
            nb::gil_scoped_release release;
            writeDef(path, d.tech, d.design);
          },
          "path"_a, "Writes the design as DEF (atomically: temporary file, then rename).")
      .def(
          "def_text",
          [](const Database& d) {
            nb::gil_scoped_release release;
            return writeDefText(d.tech, d.design);
          },
          "The design as DEF text.")
      .def(
          "compare",
          [](const Database& a, const Database& b, size_t max_diffs) {
            nb::gil_scoped_release release;
            return compareDesigns(a.design, b.design, max_diffs);
          },
          "other"_a, "max_diffs"_a = 20, "Differences between two designs (empty list = equal).");
}

}  // namespace

void bindDatabase(nb::module_& m) {
  DatabaseClass cls(m, "Database", "A loaded design: technology (LEF) + design (DEF) + guides.");
  bindDatabaseSummary(cls);
  bindDatabaseTechnology(cls);
  bindDatabaseNets(cls);
  bindDatabaseLibrary(cls);
  bindDatabaseVias(cls);
  bindDatabaseDefObjects(cls);
  bindDatabaseRouting(cls);

  m.def(
      "load",
      [](const std::vector<std::string>& lef_paths, const std::string& def_path,
         const std::optional<std::string>& guide_path) {
        nb::gil_scoped_release release;
        return new Database(loadDatabase(lef_paths, def_path, guide_path.value_or("")));
      },
      "lef_paths"_a, "def_path"_a, "guide_path"_a = nb::none(), nb::rv_policy::take_ownership,
      "Reads LEF files, a DEF and optionally a guide file. Raises xroute.errors.InputError on bad input.");

  m.def(
      "load_lef",
      [](const std::vector<std::string>& lef_paths) {
        nb::gil_scoped_release release;
        auto* db = new Database();
        try {
          for (const std::string& lef : lef_paths) readLef(lef, db->tech);
        } catch (...) {
          delete db;
          throw;
        }
        db->lefPaths = lef_paths;
        return db;
      },
      "lef_paths"_a, nb::rv_policy::take_ownership,
      "Reads LEF files only (the design part stays empty). Raises InputError on bad input.");
}
