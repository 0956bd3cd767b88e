// Design database: what a DEF file (and a guide file) says about one placed
// chip. Plain structs with int ids; all coordinates in DEF DBU. Net pins and
// guides are flat arrays with start offsets (net i owns [start[i], start[i+1])).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "db/ids.hpp"
#include "db/string_map.hpp"
#include "db/tech.hpp"
#include "geom/geom.hpp"

namespace xroute {

enum class PlaceStatus : uint8_t { Unplaced, Placed, Fixed, Cover };

struct Row {
  std::string name;
  std::string site;
  Point origin;               // DBU
  Orient orient = Orient::N;
  int numX = 1, numY = 1;     // DO numX BY numY
  Dbu stepX = 0, stepY = 0;   // DBU
};

// "TRACKS X start DO count STEP step LAYER l": `isX` tracks are vertical
// lines at x = start + i*step (they carry vertical wires).
struct TrackPattern {
  LayerId layer;
  bool isX = false;
  Dbu start = 0;   // DBU
  int count = 0;
  Dbu step = 0;    // DBU
  int line = 0;    // line of its TRACKS statement in the DEF (0: not read from a file)
};

// "GCELLGRID X start DO count STEP step": grid lines at start + i*step.
struct GCellPattern {
  bool isX = false;
  Dbu start = 0;   // DBU
  int count = 0;
  Dbu step = 0;    // DBU
};

struct Component {
  std::string name;
  MacroId macro;
  Point location;   // DBU, lower-left of the placed bounding box
  Orient orient = Orient::N;
  PlaceStatus status = PlaceStatus::Unplaced;
};

// A DEF PINS entry. Port shapes are relative to the pin's placement point and
// are oriented about it (no bounding-box shift): Transform{location, orient, 0, 0}.
struct IoPinShape {
  LayerId layer;
  Rect rect;  // DBU, relative to `location`, before orientation
};

struct IoPin {
  std::string name;
  std::string netName;   // as written after "+ NET"
  NetId net;             // resolved against NETS (invalid if the net is absent)
  std::string direction; // INPUT, OUTPUT, INOUT, FEEDTHRU or empty
  std::string use;       // SIGNAL, POWER, ... or empty
  std::vector<IoPinShape> shapes;
  PlaceStatus status = PlaceStatus::Unplaced;
  Point location;        // DBU
  Orient orient = Orient::N;
};

struct Blockage {
  bool placement = false;  // true: PLACEMENT blockage; false: LAYER blockage
  LayerId layer;           // for layer blockages
  std::vector<Rect> rects; // DBU
  std::vector<std::vector<Point>> polygons;  // DBU, POLYGON entries as written
};

// A via used in routing: either a LEF VIA (Tech::vias) or a DEF VIAS entry
// (Design::vias).
struct ViaRef {
  int32_t index = -1;     // into Tech::vias or Design::vias
  bool defVia = false;    // true: Design::vias

  bool valid() const { return index >= 0; }
  friend bool operator==(const ViaRef&, const ViaRef&) = default;
};

// A DEF VIAS entry: either fixed shapes (+ RECT / + POLYGON), or generated
// from a VIARULE with parameters; in both cases `via.shapes` holds the
// resulting rectangles relative to the via origin.
struct DefVia {
  Via via;
  bool generated = false;
  ViaRuleId rule;
  Dbu cutSizeX = 0, cutSizeY = 0;           // DBU
  LayerId botLayer, cutLayer, topLayer;
  Dbu cutSpacingX = 0, cutSpacingY = 0;     // DBU
  Dbu botEncX = 0, botEncY = 0, topEncX = 0, topEncY = 0;  // DBU
  int rows = 1, cols = 1;
  Dbu originX = 0, originY = 0;             // DBU (+ ORIGIN)
  Dbu botOffX = 0, botOffY = 0, topOffX = 0, topOffY = 0;  // DBU (+ OFFSET)
  std::string pattern;                      // + PATTERN as written
};

// One straight piece of regular (NETS) routing on one layer. A point-only
// piece (from == to) is allowed for a via-only path. Ends extend by half the
// wire width unless an explicit extension is given.
struct RouteWire {
  LayerId layer;
  Point from, to;   // DBU; from.x == to.x or from.y == to.y
  Dbu width = 0;    // DBU; 0 = the layer's default width
  Dbu extFrom = -1; // DBU; -1 = default (half width)
  Dbu extTo = -1;   // DBU

  // DBU along the centre line, end to end (extensions not counted): the one
  // definition of wirelength that reports, metrics and region costs sum.
  int64_t length() const { return std::abs(int64_t(to.x) - from.x) + std::abs(int64_t(to.y) - from.y); }
};

struct RouteVia {
  ViaRef via;
  Point at;  // DBU
  // DEF TAPER: on a path drawn to the layers' default rule though the net has a NONDEFAULTRULE
  // (no rule spacing around its metal).
  bool taper = false;
};

// A DEF "RECT ( dx1 dy1 dx2 dy2 )" patch in a routed path, already made absolute.
struct RoutePatch {
  LayerId layer;
  Rect rect;  // DBU
  bool taper = false;  // on a DEF TAPER path (RouteVia::taper)
};

struct NetRouting {
  std::vector<RouteWire> wires;
  std::vector<RouteVia> vias;
  std::vector<RoutePatch> patches;
  bool empty() const { return wires.empty() && vias.empty() && patches.empty(); }
  // DBU: the wires' summed RouteWire::length.
  int64_t wirelength() const {
    int64_t sum = 0;
    for (const RouteWire& w : wires) sum += w.length();
    return sum;
  }
};

struct Net {
  std::string name;
  std::string use;   // SIGNAL, CLOCK, ... or empty
  int ndr = -1;      // + NONDEFAULTRULE: index into Design::ndrs (-1 = the default rule)
  NetRouting routing;
};

// A special-net path piece (SPECIALNETS): flush ends (no extension).
struct SpecialWire {
  LayerId layer;
  Dbu width = 0;        // DBU
  std::string shape;    // RING, STRIPE, FOLLOWPIN, ... or empty
  Point from, to;       // DBU; from == to for a via-only point
};

struct SpecialVia {
  ViaRef via;
  Point at;             // DBU
  std::string shape;
};

struct SpecialNet {
  std::string name;
  std::string use;      // POWER, GROUND, ...
  std::vector<std::pair<std::string, std::string>> pins;  // (component or "*" or "PIN", pin)
  std::vector<SpecialWire> wires;
  std::vector<SpecialVia> vias;
  std::vector<RoutePatch> rects;  // + RECT / + POLYGON bounding boxes
};

// A net's reference to one pin: a component pin (comp valid, pin = index
// into the macro's pins) or an IO pin (comp invalid, pin = IoPinId value).
struct PinRef {
  CompId comp;
  int32_t pin = -1;
  bool isIo() const { return !comp.valid(); }
};

// A pin shape placed in design coordinates (see netPinShapes()).
struct PlacedShape {
  int32_t pinRef = -1;   // index into Design::pinRefs
  LayerId layer;
  Rect rect;             // DBU, bounding box for polygons
};

struct Design {
  std::string path;  // the DEF file read ("" for a design built in code): named by later errors
  std::string name;
  std::string version;
  int dbuPerMicron = 0;      // DEF UNITS DISTANCE MICRONS (the LEF's when the DEF was rescaled)
  // A DEF whose UNITS differ from the LEF's: its coordinates (and the guides') were multiplied by
  // defScaleMul and divided by defScaleDiv to reach the LEF's units.
  int defScaleMul = 1, defScaleDiv = 1;
  std::string busBitChars = "[]";
  std::string dividerChar = "/";
  Rect dieArea;              // DBU, bounding box of DIEAREA
  std::vector<Point> diePolygon;  // DBU, DIEAREA points as written (2 for a rectangle)

  std::vector<Row> rows;
  std::vector<TrackPattern> tracks;
  std::vector<GCellPattern> gcellGrid;
  std::vector<DefVia> vias;
  std::vector<Component> components;
  std::vector<IoPin> ioPins;
  std::vector<Blockage> blockages;
  std::vector<SpecialNet> specialNets;
  std::vector<Net> nets;
  // DEF NONDEFAULTRULES, then the LEF rules that nets name (copied from Tech::ndrs when named).
  std::vector<NonDefaultRule> ndrs;

  // Net -> pins, flat: net i owns pinRefs[netPinStart[i] .. netPinStart[i+1]).
  std::vector<int32_t> netPinStart;  // size nets.size() + 1
  std::vector<PinRef> pinRefs;

  // Net -> guides, flat: net i owns guide rows [guideStart[i] .. guideStart[i+1]).
  // Empty until a guide file is read.
  std::vector<int32_t> guideStart;   // size nets.size() + 1, or 0
  std::vector<Rect> guideRects;      // DBU
  std::vector<LayerId> guideLayers;
  bool guidesBuiltIn = false;  // the guides are the built-in global router's (installGuides), not a file's

  StringMap<CompId> compIndex;
  StringMap<NetId> netIndex;
  StringMap<IoPinId> ioPinIndex;
  StringMap<DefViaId> viaIndex;
  StringMap<int> ndrIndex;  // name -> index into ndrs

  // Sections and statements the reader skipped, by keyword.
  std::vector<std::pair<std::string, int>> skippedStatements;
  int warningCount = 0;
  // Odd but routable things found while reading, "file:line: message" (also in warningCount).
  std::vector<std::string> warnings;
  int dieLine = 0;  // line of DIEAREA in the DEF (0: none read)
  int gcellLine = 0;  // line of the first GCELLGRID (0: none)
  int endLine = 0;  // line of END DESIGN

  int pinCount(NetId n) const { return netPinStart[*n + 1] - netPinStart[*n]; }
  bool hasGuides() const { return !guideStart.empty(); }
  CompId findComponent(std::string_view name) const;
  NetId findNet(std::string_view name) const;
  const Via& via(const Tech& tech, ViaRef ref) const {
    return ref.defVia ? vias[ref.index].via : tech.vias[ref.index];
  }
};

// Placement transform of a component (macro SIZE and ORIGIN applied).
Transform componentTransform(const Tech& tech, const Component& comp);

// All pin shapes of net `n` in design coordinates, in pin order.
std::vector<PlacedShape> netPinShapes(const Tech& tech, const Design& design, NetId n);
// The placed rects of pin ref `pinRef` on `layer` appended to `out` (DBU; polygons as rects).
void pinRefRects(const Tech& tech, const Design& design, int32_t pinRef, LayerId layer, std::vector<Rect>& out);

// The rectangle of a regular wire: its width (0 = the layer's default) and
// its end extensions (-1 = half the width). False for a point wire or a wire
// without a layer.
bool routeWireRect(const Tech& tech, const RouteWire& wire, Rect& out);

// The entry of net n's NONDEFAULTRULE for `layer`, or nullptr (the net has no rule, or its rule
// leaves the layer to its defaults; n outside the regular nets: nullptr).
const NdrLayer* netRuleLayer(const Design& design, int32_t net, LayerId layer);
// A wire of a net of a NONDEFAULTRULE drawn at its layer's default width where the rule names
// another (DEF writes and reads it "TAPER"): the default rule holds around it, not the net's.
// ndr: the net's Net::ndr (-1: no rule, never tapered).
bool taperedWire(const Tech& tech, const Design& design, int ndr, const RouteWire& wire);

// Every shape of regular routing, in order: its wires (routeWireRect), its vias' shapes, its RECT
// patches, as fn(layer, rect, isVia, taper). taper: drawn to the default rule though the net has
// one (ndr: the net's Net::ndr; -1: nothing tapered).
template <class Fn>
void forEachRoutingShape(const Tech& tech, const Design& design, const NetRouting& routing, int ndr, Fn&& fn) {
  const bool rule = ndr >= 0;
  for (const RouteWire& w : routing.wires) {
    Rect r;
    if (routeWireRect(tech, w, r)) fn(w.layer, r, false, taperedWire(tech, design, ndr, w));
  }
  for (const RouteVia& v : routing.vias) {
    if (!v.via.valid()) continue;
    for (const ViaShape& s : design.via(tech, v.via).shapes) fn(s.layer, s.rect.translated(v.at), true, rule && v.taper);
  }
  for (const RoutePatch& p : routing.patches) fn(p.layer, p.rect, false, rule && p.taper);
}

// Appends a macro shape placed by `t` as rects (a POLYGON cut into slabs).
void placedShapeRects(const MacroShape& shape, const Transform& t, std::vector<Rect>& out);

// All GCell grid line coordinates along x (isX) or y, sorted, deduplicated.
std::vector<Dbu> gcellLines(const Design& design, bool isX);

}  // namespace xroute
