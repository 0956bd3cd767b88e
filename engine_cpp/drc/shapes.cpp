// collectDesignShapes: every metal and cut shape of a design as DrcShapes.
//
// Net ids: regular net i -> i; special net j -> nets + j; a component pin or
// IO pin on no net -> one fresh id each after those (so it conflicts with
// everything else). Pins of special nets (SPECIALNETS "( * VDD )", "( comp
// pin )", "( PIN name )", or an IO pin whose + NET names the special net)
// take the special net's id; POWER / GROUND pins on no net share one id per
// pin name. Obstructions (cell OBS, DEF layer blockages)
// get -1; a cell's OBS is cut back where its own pins are. Unplaced components and IO pins are skipped. Regular wires extend
// by half their width at each end unless an extension is given; special
// wires end flush. Rectilinear polygons are cut into rects.
#include <algorithm>

#include "drc/drc.hpp"
#include "geom/polygon.hpp"

namespace xroute {

namespace {

bool placed(PlaceStatus s) { return s != PlaceStatus::Unplaced; }

class Collector {
 public:
  Collector(const Tech& tech, const Design& design, std::vector<std::string>* names)
      : tech_(tech), design_(design), names_(names) {}

  // Pins, obstructions, special routing, regular routing (unless not `routing`), in that order.
  std::vector<DrcShape> run(bool routing = true);

 private:
  void add(LayerId layer, const Rect& r, int32_t net, ShapeOrigin origin, bool taper = false) {
    if (layer.valid()) out_.push_back({layer, r, net, origin, taper});
  }
  void addMacroShape(const MacroShape& s, const Transform& t, int32_t net, ShapeOrigin origin);
  void addObstructions(const Component& c);
  void addVia(const ViaRef& ref, Point at, int32_t net, ShapeOrigin origin);
  void addComponentPin(int32_t comp, int32_t pin, int32_t net);
  void addIoPin(int32_t io, int32_t net);
  void addNetPins();            // pins of regular and special nets
  void addUnconnectedPins();    // pins on no net (ids after the special nets)
  void addBlockages();          // cell OBS and DEF blockages
  void addSpecialRouting();     // special wires (flush ends), vias, rects
  void addRegularRouting();     // wires extended by half width unless told otherwise, vias, patches

  const Tech& tech_;
  const Design& design_;
  std::vector<std::string>* names_;  // by net id, when asked for
  std::vector<DrcShape> out_;
  std::vector<std::vector<uint8_t>> compPinDone_;  // [component][macro pin]
  std::vector<uint8_t> ioPinDone_;
  std::vector<Rect> scratch_;
};

void Collector::addMacroShape(const MacroShape& s, const Transform& t, int32_t net, ShapeOrigin origin) {
  scratch_.clear();
  placedShapeRects(s, t, scratch_);
  for (const Rect& r : scratch_) add(s.layer, r, net, origin);
}

// A component's OBS minus its own pins: LEF abstracts often cover a block's
// pins with OBS, and the pin stays accessible.
void Collector::addObstructions(const Component& c) {
  const Macro& m = tech_.macros[*c.macro];
  if (m.obstructions.empty()) return;
  const Transform t = componentTransform(tech_, c);
  std::vector<std::pair<LayerId, Rect>> pins;
  for (const MacroPin& pin : m.pins) {
    for (const MacroShape& s : pin.shapes) {
      scratch_.clear();
      placedShapeRects(s, t, scratch_);
      for (const Rect& r : scratch_) pins.push_back({s.layer, r});
    }
  }
  std::vector<Rect> pieces, next;
  for (const MacroShape& s : m.obstructions) {
    pieces.clear();
    placedShapeRects(s, t, pieces);
    for (const auto& [layer, pin] : pins) {
      if (layer != s.layer) continue;
      next.clear();
      for (const Rect& r : pieces) subtractRect(r, pin, next);
      pieces.swap(next);
    }
    for (const Rect& r : pieces) add(s.layer, r, -1, ShapeOrigin::Obstruction);
  }
}

void Collector::addVia(const ViaRef& ref, Point at, int32_t net, ShapeOrigin origin) {
  if (!ref.valid()) return;
  for (const ViaShape& s : design_.via(tech_, ref).shapes) add(s.layer, s.rect.translated(at), net, origin);
}

void Collector::addComponentPin(int32_t comp, int32_t pin, int32_t net) {
  const Component& c = design_.components[comp];
  if (!placed(c.status) || compPinDone_[comp][pin]) return;
  compPinDone_[comp][pin] = 1;
  const Transform t = componentTransform(tech_, c);
  for (const MacroShape& s : tech_.macros[*c.macro].pins[pin].shapes) addMacroShape(s, t, net, ShapeOrigin::Pin);
}

void Collector::addIoPin(int32_t io, int32_t net) {
  const IoPin& p = design_.ioPins[io];
  if (!placed(p.status) || ioPinDone_[io]) return;
  ioPinDone_[io] = 1;
  const Transform t{p.location, p.orient, 0, 0};
  for (const IoPinShape& s : p.shapes) add(s.layer, t.apply(s.rect), net, ShapeOrigin::Pin);
}

std::vector<DrcShape> Collector::run(bool routing) {
  compPinDone_.resize(design_.components.size());
  for (size_t c = 0; c < design_.components.size(); ++c)
    compPinDone_[c].assign(tech_.macros[*design_.components[c].macro].pins.size(), 0);
  ioPinDone_.assign(design_.ioPins.size(), 0);

  addNetPins();
  addUnconnectedPins();
  addBlockages();
  addSpecialRouting();
  if (routing) addRegularRouting();
  return std::move(out_);
}

void Collector::addNetPins() {
  const int32_t nets = int32_t(design_.nets.size());
  // Pins of regular nets.
  for (int32_t n = 0; n < nets && size_t(n + 1) < design_.netPinStart.size(); ++n) {
    for (int32_t r = design_.netPinStart[n]; r < design_.netPinStart[n + 1]; ++r) {
      const PinRef& ref = design_.pinRefs[r];
      if (ref.isIo()) addIoPin(ref.pin, n);
      else addComponentPin(*ref.comp, ref.pin, n);
    }
  }
  // Pins of special nets.
  for (size_t s = 0; s < design_.specialNets.size(); ++s) {
    const SpecialNet& sn = design_.specialNets[s];
    const int32_t id = nets + int32_t(s);
    for (const auto& [compName, pinName] : sn.pins) {
      if (compName == "PIN") {
        auto it = design_.ioPinIndex.find(pinName);
        if (it != design_.ioPinIndex.end()) addIoPin(*it->second, id);
        continue;
      }
      auto addByName = [&](int32_t c) {
        const Macro& m = tech_.macros[*design_.components[c].macro];
        auto it = m.pinIndex.find(pinName);
        if (it != m.pinIndex.end()) addComponentPin(c, it->second, id);
      };
      if (compName == "*") {
        for (size_t c = 0; c < design_.components.size(); ++c) addByName(int32_t(c));
      } else if (const CompId c = design_.findComponent(compName); c.valid()) {
        addByName(*c);
      }
    }
    for (size_t io = 0; io < design_.ioPins.size(); ++io)
      if (!design_.ioPins[io].net.valid() && design_.ioPins[io].netName == sn.name) addIoPin(int32_t(io), id);
  }
}

void Collector::addUnconnectedPins() {
  const int32_t nets = int32_t(design_.nets.size());
  // Pins on no net: one id each, except that POWER / GROUND pins of the same
  // name share one (the rails of abutting cells are one conductor).
  int32_t nextId = nets + int32_t(design_.specialNets.size());
  if (names_) {
    names_->clear();
    for (const Net& n : design_.nets) names_->push_back(n.name);
    for (const SpecialNet& sn : design_.specialNets) names_->push_back(sn.name);
  }
  auto name = [&](std::string_view owner, const std::string& pin) {
    if (names_) names_->push_back(std::string(owner) + "/" + pin);
  };
  StringMap<int32_t> supplyIds;
  for (size_t c = 0; c < design_.components.size(); ++c) {
    if (!placed(design_.components[c].status)) continue;
    const Macro& m = tech_.macros[*design_.components[c].macro];
    for (size_t p = 0; p < compPinDone_[c].size(); ++p) {
      if (compPinDone_[c][p]) continue;
      const MacroPin& pin = m.pins[p];
      int32_t id = -1;
      if (pin.use == "POWER" || pin.use == "GROUND") {
        auto [it, added] = supplyIds.emplace(pin.name, nextId);
        if (added) {
          ++nextId;
          name("*", pin.name);
        }
        id = it->second;
      } else {
        id = nextId++;
        name(design_.components[c].name, pin.name);
      }
      addComponentPin(int32_t(c), int32_t(p), id);
    }
  }
  for (size_t io = 0; io < design_.ioPins.size(); ++io)
    if (!ioPinDone_[io] && placed(design_.ioPins[io].status)) {
      name("PIN", design_.ioPins[io].name);
      addIoPin(int32_t(io), nextId++);
    }
}

void Collector::addBlockages() {
  // Obstructions.
  for (const Component& c : design_.components)
    if (placed(c.status)) addObstructions(c);
  for (const Blockage& b : design_.blockages) {
    if (b.placement) continue;
    for (const Rect& r : b.rects) add(b.layer, r, -1, ShapeOrigin::Obstruction);
    for (const auto& poly : b.polygons) {
      scratch_.clear();
      polygonRects(poly, scratch_);
      for (const Rect& r : scratch_) add(b.layer, r, -1, ShapeOrigin::Obstruction);
    }
  }
}

void Collector::addSpecialRouting() {
  const int32_t nets = int32_t(design_.nets.size());
  // Special-net routing: flush ends.
  for (size_t s = 0; s < design_.specialNets.size(); ++s) {
    const SpecialNet& sn = design_.specialNets[s];
    const int32_t id = nets + int32_t(s);
    for (const SpecialWire& w : sn.wires) {
      if (w.from == w.to) continue;
      const Dbu lo = w.width / 2, hi = w.width - w.width / 2;
      if (w.from.y == w.to.y) {
        add(w.layer, {std::min(w.from.x, w.to.x), w.from.y - lo, std::max(w.from.x, w.to.x), w.from.y + hi}, id,
            ShapeOrigin::SpecialNet);
      } else if (w.from.x == w.to.x) {
        add(w.layer, {w.from.x - lo, std::min(w.from.y, w.to.y), w.from.x + hi, std::max(w.from.y, w.to.y)}, id,
            ShapeOrigin::SpecialNet);
      }
    }
    for (const SpecialVia& v : sn.vias) addVia(v.via, v.at, id, ShapeOrigin::SpecialNet);
    for (const RoutePatch& p : sn.rects) add(p.layer, p.rect, id, ShapeOrigin::SpecialNet);
  }
}

void Collector::addRegularRouting() {
  const int32_t nets = int32_t(design_.nets.size());
  // Regular routing: wires extend by half width unless told otherwise.
  for (int32_t n = 0; n < nets; ++n) {
    forEachRoutingShape(tech_, design_, design_.nets[n].routing, design_.nets[n].ndr,
                        [&](LayerId layer, const Rect& rect, bool via, bool taper) {
                          add(layer, rect, n, via ? ShapeOrigin::Via : ShapeOrigin::Wire, taper);
                        });
  }
}

}  // namespace

std::vector<std::vector<Dbu>> ndrSpacingByNet(const Tech& tech, const Design& design) {
  std::vector<std::vector<Dbu>> out;
  for (size_t n = 0; n < design.nets.size(); ++n) {
    const int rule = design.nets[n].ndr;
    if (rule < 0) continue;
    for (const NdrLayer& l : design.ndrs[rule].layers) {
      if (l.spacing <= 0) continue;
      if (out.empty()) out.assign(tech.layers.size(), {});
      std::vector<Dbu>& byNet = out[*l.layer];
      if (byNet.empty()) byNet.assign(design.nets.size(), 0);
      byNet[n] = l.spacing;
    }
  }
  return out;
}

std::vector<DrcShape> collectDesignShapes(const Tech& tech, const Design& design, std::vector<std::string>* netNames) {
  return Collector(tech, design, netNames).run();
}

std::vector<DrcShape> collectFixedShapes(const Tech& tech, const Design& design, std::vector<std::string>* netNames) {
  return Collector(tech, design, netNames).run(false);
}

}  // namespace xroute
