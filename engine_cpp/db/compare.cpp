// Deep comparison of two designs: every field the DEF writer writes (the
// DEF version, skipped-statement counters and guides are not compared).
// Layers, macros and vias are compared by id, so both designs must have been
// read with the same Tech.
#include "db/compare.hpp"

#include <algorithm>

namespace xroute {

namespace {

std::string str(int32_t v) { return std::to_string(v); }
std::string str(bool v) { return v ? "true" : "false"; }
std::string str(const std::string& s) { return "'" + s + "'"; }
// Built by appending (GCC 12 warns falsely about "(" + std::to_string(...)).
std::string str(Point p) {
  std::string s("(");
  s.append(std::to_string(p.x)).append(" ").append(std::to_string(p.y)).append(")");
  return s;
}
std::string str(const Rect& r) {
  std::string s("(");
  s.append(std::to_string(r.xlo)).append(" ").append(std::to_string(r.ylo)).append(" ");
  s.append(std::to_string(r.xhi)).append(" ").append(std::to_string(r.yhi)).append(")");
  return s;
}
std::string str(Orient o) { return std::string(orientName(o)); }
std::string str(PlaceStatus s) {
  switch (s) {
    case PlaceStatus::Unplaced: return "UNPLACED";
    case PlaceStatus::Placed: return "PLACED";
    case PlaceStatus::Fixed: return "FIXED";
    case PlaceStatus::Cover: return "COVER";
  }
  return "?";
}
template <class Tag>
std::string str(Id<Tag> id) {
  return std::to_string(id.value);
}
std::string str(ViaRef v) { return (v.defVia ? "def via " : "lef via ") + std::to_string(v.index); }
std::string str(const std::vector<Point>& pts) {
  std::string s = "[";
  for (const Point& p : pts) s += str(p);
  return s + "]";
}
std::string str(const std::pair<std::string, std::string>& p) { return "(" + p.first + " " + p.second + ")"; }

class Differ {
 public:
  explicit Differ(size_t maxDiffs) : max_(maxDiffs) {}

  bool full() const { return diffs_.size() >= max_; }
  void add(std::string s) {
    if (!full()) diffs_.push_back(std::move(s));
  }
  template <class T>
  void field(const std::string& where, const char* name, const T& a, const T& b) {
    if (!(a == b)) add(where + ": " + name + " " + str(a) + " != " + str(b));
  }
  // Sizes of two lists; returns the common length to compare element-wise.
  size_t count(const std::string& what, size_t a, size_t b) {
    if (a != b) add(what + ": count " + std::to_string(a) + " != " + std::to_string(b));
    return std::min(a, b);
  }
  std::vector<std::string> take() { return std::move(diffs_); }

 private:
  size_t max_;
  std::vector<std::string> diffs_;
};

std::string item(const char* kind, size_t i, const std::string& name) {
  return std::string(kind) + " " + std::to_string(i) + " (" + name + ")";
}
std::string item(const char* kind, size_t i) { return std::string(kind) + " " + std::to_string(i); }

void compareVia(Differ& d, const std::string& w, const Via& a, const Via& b) {
  d.field(w, "name", a.name, b.name);
  d.field(w, "bottom layer", a.bottom, b.bottom);
  d.field(w, "cut layer", a.cut, b.cut);
  d.field(w, "top layer", a.top, b.top);
  const size_t n = d.count(w + " shapes", a.shapes.size(), b.shapes.size());
  for (size_t i = 0; i < n && !d.full(); ++i) {
    const std::string s = w + " shape " + std::to_string(i);
    d.field(s, "layer", a.shapes[i].layer, b.shapes[i].layer);
    d.field(s, "rect", a.shapes[i].rect, b.shapes[i].rect);
  }
}

void compareDefVias(Differ& d, const Design& a, const Design& b) {
  const size_t n = d.count("vias", a.vias.size(), b.vias.size());
  for (size_t i = 0; i < n && !d.full(); ++i) {
    const DefVia& x = a.vias[i];
    const DefVia& y = b.vias[i];
    const std::string w = item("via", i, x.via.name);
    compareVia(d, w, x.via, y.via);
    d.field(w, "generated", x.generated, y.generated);
    if (!x.generated || !y.generated) continue;
    d.field(w, "rule", x.rule, y.rule);
    d.field(w, "cut size x", x.cutSizeX, y.cutSizeX);
    d.field(w, "cut size y", x.cutSizeY, y.cutSizeY);
    d.field(w, "bottom layer", x.botLayer, y.botLayer);
    d.field(w, "cut layer", x.cutLayer, y.cutLayer);
    d.field(w, "top layer", x.topLayer, y.topLayer);
    d.field(w, "cut spacing x", x.cutSpacingX, y.cutSpacingX);
    d.field(w, "cut spacing y", x.cutSpacingY, y.cutSpacingY);
    d.field(w, "bottom enclosure x", x.botEncX, y.botEncX);
    d.field(w, "bottom enclosure y", x.botEncY, y.botEncY);
    d.field(w, "top enclosure x", x.topEncX, y.topEncX);
    d.field(w, "top enclosure y", x.topEncY, y.topEncY);
    d.field(w, "rows", x.rows, y.rows);
    d.field(w, "cols", x.cols, y.cols);
    d.field(w, "origin x", x.originX, y.originX);
    d.field(w, "origin y", x.originY, y.originY);
    d.field(w, "bottom offset x", x.botOffX, y.botOffX);
    d.field(w, "bottom offset y", x.botOffY, y.botOffY);
    d.field(w, "top offset x", x.topOffX, y.topOffX);
    d.field(w, "top offset y", x.topOffY, y.topOffY);
    d.field(w, "pattern", x.pattern, y.pattern);
  }
}

void compareHeader(Differ& d, const Design& a, const Design& b) {
  d.field("design", "name", a.name, b.name);
  d.field("design", "units", a.dbuPerMicron, b.dbuPerMicron);
  d.field("design", "bus bit chars", a.busBitChars, b.busBitChars);
  d.field("design", "divider char", a.dividerChar, b.dividerChar);
  d.field("design", "die area", a.dieArea, b.dieArea);
  d.field("design", "die polygon", a.diePolygon, b.diePolygon);

  size_t n = d.count("rows", a.rows.size(), b.rows.size());
  for (size_t i = 0; i < n && !d.full(); ++i) {
    const Row& x = a.rows[i];
    const Row& y = b.rows[i];
    const std::string w = item("row", i, x.name);
    d.field(w, "name", x.name, y.name);
    d.field(w, "site", x.site, y.site);
    d.field(w, "origin", x.origin, y.origin);
    d.field(w, "orient", x.orient, y.orient);
    d.field(w, "num x", x.numX, y.numX);
    d.field(w, "num y", x.numY, y.numY);
    d.field(w, "step x", x.stepX, y.stepX);
    d.field(w, "step y", x.stepY, y.stepY);
  }
  n = d.count("tracks", a.tracks.size(), b.tracks.size());
  for (size_t i = 0; i < n && !d.full(); ++i) {
    const TrackPattern& x = a.tracks[i];
    const TrackPattern& y = b.tracks[i];
    const std::string w = item("tracks", i);
    d.field(w, "layer", x.layer, y.layer);
    d.field(w, "is x", x.isX, y.isX);
    d.field(w, "start", x.start, y.start);
    d.field(w, "count", x.count, y.count);
    d.field(w, "step", x.step, y.step);
  }
  n = d.count("gcell grid", a.gcellGrid.size(), b.gcellGrid.size());
  for (size_t i = 0; i < n && !d.full(); ++i) {
    const GCellPattern& x = a.gcellGrid[i];
    const GCellPattern& y = b.gcellGrid[i];
    const std::string w = item("gcell grid", i);
    d.field(w, "is x", x.isX, y.isX);
    d.field(w, "start", x.start, y.start);
    d.field(w, "count", x.count, y.count);
    d.field(w, "step", x.step, y.step);
  }
}

void compareCells(Differ& d, const Design& a, const Design& b) {
  size_t n = d.count("components", a.components.size(), b.components.size());
  for (size_t i = 0; i < n && !d.full(); ++i) {
    const Component& x = a.components[i];
    const Component& y = b.components[i];
    const std::string w = item("component", i, x.name);
    d.field(w, "name", x.name, y.name);
    d.field(w, "macro", x.macro, y.macro);
    d.field(w, "location", x.location, y.location);
    d.field(w, "orient", x.orient, y.orient);
    d.field(w, "status", x.status, y.status);
  }
  n = d.count("io pins", a.ioPins.size(), b.ioPins.size());
  for (size_t i = 0; i < n && !d.full(); ++i) {
    const IoPin& x = a.ioPins[i];
    const IoPin& y = b.ioPins[i];
    const std::string w = item("io pin", i, x.name);
    d.field(w, "name", x.name, y.name);
    d.field(w, "net name", x.netName, y.netName);
    d.field(w, "net", x.net, y.net);
    d.field(w, "direction", x.direction, y.direction);
    d.field(w, "use", x.use, y.use);
    d.field(w, "status", x.status, y.status);
    d.field(w, "location", x.location, y.location);
    d.field(w, "orient", x.orient, y.orient);
    const size_t m = d.count(w + " shapes", x.shapes.size(), y.shapes.size());
    for (size_t k = 0; k < m; ++k) {
      const std::string s = w + " shape " + std::to_string(k);
      d.field(s, "layer", x.shapes[k].layer, y.shapes[k].layer);
      d.field(s, "rect", x.shapes[k].rect, y.shapes[k].rect);
    }
  }
  n = d.count("blockages", a.blockages.size(), b.blockages.size());
  for (size_t i = 0; i < n && !d.full(); ++i) {
    const Blockage& x = a.blockages[i];
    const Blockage& y = b.blockages[i];
    const std::string w = item("blockage", i);
    d.field(w, "placement", x.placement, y.placement);
    d.field(w, "layer", x.layer, y.layer);
    const size_t m = d.count(w + " rects", x.rects.size(), y.rects.size());
    for (size_t k = 0; k < m; ++k) d.field(w + " rect " + std::to_string(k), "rect", x.rects[k], y.rects[k]);
    const size_t p = d.count(w + " polygons", x.polygons.size(), y.polygons.size());
    for (size_t k = 0; k < p; ++k) {
      d.field(w + " polygon " + std::to_string(k), "points", x.polygons[k], y.polygons[k]);
    }
  }
}

void compareSpecialNets(Differ& d, const Design& a, const Design& b) {
  const size_t n = d.count("special nets", a.specialNets.size(), b.specialNets.size());
  for (size_t i = 0; i < n && !d.full(); ++i) {
    const SpecialNet& x = a.specialNets[i];
    const SpecialNet& y = b.specialNets[i];
    const std::string w = item("special net", i, x.name);
    d.field(w, "name", x.name, y.name);
    d.field(w, "use", x.use, y.use);
    size_t m = d.count(w + " pins", x.pins.size(), y.pins.size());
    for (size_t k = 0; k < m && !d.full(); ++k) d.field(w + " pin " + std::to_string(k), "ref", x.pins[k], y.pins[k]);
    m = d.count(w + " wires", x.wires.size(), y.wires.size());
    for (size_t k = 0; k < m && !d.full(); ++k) {
      const SpecialWire& p = x.wires[k];
      const SpecialWire& q = y.wires[k];
      const std::string s = w + " wire " + std::to_string(k);
      d.field(s, "layer", p.layer, q.layer);
      d.field(s, "width", p.width, q.width);
      d.field(s, "shape", p.shape, q.shape);
      d.field(s, "from", p.from, q.from);
      d.field(s, "to", p.to, q.to);
    }
    m = d.count(w + " vias", x.vias.size(), y.vias.size());
    for (size_t k = 0; k < m && !d.full(); ++k) {
      const std::string s = w + " via " + std::to_string(k);
      d.field(s, "via", x.vias[k].via, y.vias[k].via);
      d.field(s, "at", x.vias[k].at, y.vias[k].at);
      d.field(s, "shape", x.vias[k].shape, y.vias[k].shape);
    }
    m = d.count(w + " rects", x.rects.size(), y.rects.size());
    for (size_t k = 0; k < m && !d.full(); ++k) {
      const std::string s = w + " rect " + std::to_string(k);
      d.field(s, "layer", x.rects[k].layer, y.rects[k].layer);
      d.field(s, "rect", x.rects[k].rect, y.rects[k].rect);
    }
  }
}

void compareNets(Differ& d, const Design& a, const Design& b) {
  const size_t n = d.count("nets", a.nets.size(), b.nets.size());
  const bool pinsOk = a.netPinStart.size() == a.nets.size() + 1 && b.netPinStart.size() == b.nets.size() + 1;
  if (!pinsOk) d.add("net pin arrays: netPinStart has the wrong size");
  for (size_t i = 0; i < n && !d.full(); ++i) {
    const Net& x = a.nets[i];
    const Net& y = b.nets[i];
    const std::string w = item("net", i, x.name);
    d.field(w, "name", x.name, y.name);
    d.field(w, "use", x.use, y.use);
    if (pinsOk) {
      const int32_t xa = a.netPinStart[i], ya = b.netPinStart[i];
      const size_t m = d.count(w + " pins", static_cast<size_t>(a.netPinStart[i + 1] - xa),
                               static_cast<size_t>(b.netPinStart[i + 1] - ya));
      for (size_t k = 0; k < m && !d.full(); ++k) {
        const PinRef& p = a.pinRefs[xa + k];
        const PinRef& q = b.pinRefs[ya + k];
        const std::string s = w + " pin " + std::to_string(k);
        d.field(s, "component", p.comp, q.comp);
        d.field(s, "pin", p.pin, q.pin);
      }
    }
    const NetRouting& rx = x.routing;
    const NetRouting& ry = y.routing;
    size_t m = d.count(w + " wires", rx.wires.size(), ry.wires.size());
    for (size_t k = 0; k < m && !d.full(); ++k) {
      const RouteWire& p = rx.wires[k];
      const RouteWire& q = ry.wires[k];
      const std::string s = w + " wire " + std::to_string(k);
      d.field(s, "layer", p.layer, q.layer);
      d.field(s, "from", p.from, q.from);
      d.field(s, "to", p.to, q.to);
      d.field(s, "width", p.width, q.width);
      d.field(s, "ext from", p.extFrom, q.extFrom);
      d.field(s, "ext to", p.extTo, q.extTo);
    }
    m = d.count(w + " vias", rx.vias.size(), ry.vias.size());
    for (size_t k = 0; k < m && !d.full(); ++k) {
      const std::string s = w + " via " + std::to_string(k);
      d.field(s, "via", rx.vias[k].via, ry.vias[k].via);
      d.field(s, "at", rx.vias[k].at, ry.vias[k].at);
    }
    m = d.count(w + " patches", rx.patches.size(), ry.patches.size());
    for (size_t k = 0; k < m && !d.full(); ++k) {
      const std::string s = w + " patch " + std::to_string(k);
      d.field(s, "layer", rx.patches[k].layer, ry.patches[k].layer);
      d.field(s, "rect", rx.patches[k].rect, ry.patches[k].rect);
    }
  }
}

}  // namespace

std::vector<std::string> compareDesigns(const Design& a, const Design& b, size_t maxDiffs) {
  Differ d(maxDiffs);
  compareHeader(d, a, b);
  compareDefVias(d, a, b);
  compareCells(d, a, b);
  compareSpecialNets(d, a, b);
  compareNets(d, a, b);
  return d.take();
}

}  // namespace xroute
