// Technology database: what a LEF file says. Plain structs with int ids;
// all lengths in DBU (LEF microns x Tech::dbuPerMicron, rounded to nearest).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "db/ids.hpp"
#include "db/string_map.hpp"
#include "geom/geom.hpp"

namespace xroute {

enum class LayerType : uint8_t { Routing, Cut, Masterslice, Overlap, Implant, Other };
enum class Direction : uint8_t { None, Horizontal, Vertical };

// LEF "SPACING s ENDOFLINE eolWidth WITHIN within [PARALLELEDGE parSpace WITHIN
// parWithin [TWOEDGES]]": an edge shorter than eolWidth needs `space` to any
// metal within `within` beside it (and, with PARALLELEDGE, only when a
// parallel edge is within parSpace / parWithin).
struct EolRule {
  Dbu space = 0;          // DBU
  Dbu eolWidth = 0;       // DBU
  Dbu within = 0;         // DBU
  bool parallelEdge = false;
  Dbu parSpace = 0;       // DBU
  Dbu parWithin = 0;      // DBU
  bool twoEdges = false;
};

// Plain "SPACING s [RANGE lo hi] [SAMENET] ;" on a routing layer.
struct SpacingRule {
  Dbu space = 0;        // DBU
  bool hasRange = false;
  Dbu rangeLo = 0;      // DBU, width range when hasRange
  Dbu rangeHi = 0;      // DBU
  bool sameNet = false;
};

// SPACINGTABLE PARALLELRUNLENGTH: spacing required between a shape of width
// >= widths[i] and another shape, for a parallel run length > prls[j]
// (the first column is for any run length). spacing is row-major
// (widths.size() rows x prls.size() columns).
struct PrlSpacingTable {
  std::vector<Dbu> prls;     // DBU, ascending
  std::vector<Dbu> widths;   // DBU, ascending
  std::vector<Dbu> spacing;  // DBU, row-major [widthIndex * prls.size() + prlIndex]

  bool empty() const { return widths.empty(); }
  Dbu at(size_t widthIndex, size_t prlIndex) const { return spacing[widthIndex * prls.size() + prlIndex]; }
};

// LEF58_CORNERSPACING "CORNERSPACING CONVEXCORNER [EXCEPTEOL eolWidth]
// WIDTH w SPACING s ..." (ispd19 files): required corner-to-corner spacing
// for a convex corner of a shape whose width is >= widths[i].
struct CornerSpacingRule {
  bool convexCorner = false;
  bool concaveCorner = false;
  bool exceptEol = false;
  Dbu eolWidth = 0;           // DBU
  std::vector<Dbu> widths;    // DBU, ascending
  std::vector<Dbu> spacings;  // DBU, one per width
};

// "SPACING s [ADJACENTCUTS n WITHIN w] [CENTERTOCENTER] [SAMENET]" on a cut layer.
struct CutSpacingRule {
  Dbu space = 0;             // DBU, edge-to-edge (center-to-center if centerToCenter)
  bool centerToCenter = false;
  bool sameNet = false;
  int adjacentCuts = 0;      // 0 = plain cut spacing rule
  Dbu cutWithin = 0;         // DBU, with adjacentCuts
};

struct Layer {
  std::string name;
  LayerType type = LayerType::Other;
  int routingIndex = -1;     // 0.. over routing layers only (z), -1 if not routing
  int cutIndex = -1;         // 0.. over cut layers only, -1 if not cut

  // Where the LAYER statement is (for errors found after reading).
  std::string path;
  int line = 0;

  // Routing layers.
  Direction direction = Direction::None;
  Dbu pitchX = 0, pitchY = 0;     // DBU ("PITCH p" sets both)
  Dbu offsetX = 0, offsetY = 0;   // DBU
  Dbu width = 0;                  // DBU, default wire width (cut layers: cut width)
  Dbu minWidth = 0;               // DBU (0 = same as width)
  Area minArea = 0;               // DBU^2 ("AREA", microns^2 x dbu^2)
  std::vector<SpacingRule> spacings;
  std::vector<EolRule> eolRules;
  PrlSpacingTable prlTable;
  std::vector<CornerSpacingRule> cornerSpacings;

  // Cut layers.
  std::vector<CutSpacingRule> cutSpacings;

  // PROPERTY name value pairs as written (LEF58_* strings kept verbatim,
  // including the ones parsed into rules above).
  std::vector<std::pair<std::string, std::string>> properties;

  // Rules this layer states that the checker does not judge, each once, in the order read:
  // "MINSTEP", "SPACING NOTCHLENGTH", "SPACINGTABLE TWOWIDTHS", "LEF58_SPACING", ... (the
  // reader's noteUnjudged; electrical properties such as RESISTANCE are no rules and not listed).
  std::vector<std::string> unjudged;

  // Smallest spacing any rule asks for between two min-width shapes: the
  // table's first entry, else the smallest plain SPACING; 0 if none.
  Dbu minSpacing() const;
};

struct ViaShape {
  LayerId layer;
  Rect rect;  // DBU, relative to the via origin
};

// A fixed LEF VIA (or a DEF VIAS entry: see Design::vias, same struct).
struct Via {
  std::string name;
  bool isDefault = false;
  LayerId bottom, cut, top;        // derived from the shapes' layers
  std::vector<ViaShape> shapes;
};

// VIARULE name GENERATE [DEFAULT]: two metal layers with ENCLOSURE and one
// cut layer with RECT and SPACING, in the order written.
struct ViaRuleLayer {
  LayerId layer;
  Dbu enclosure1 = 0, enclosure2 = 0;  // DBU (metal layers)
  bool hasWidth = false;
  Dbu widthLo = 0, widthHi = 0;        // DBU, WIDTH min TO max (optional)
  Rect cutRect;                        // DBU (cut layer)
  Dbu spacingX = 0, spacingY = 0;      // DBU, cut pitch "SPACING x BY y" (cut layer)
};

struct ViaRule {
  std::string name;
  bool generate = false;
  bool isDefault = false;
  std::vector<ViaRuleLayer> layers;  // in the order written (usually 3)
};

struct Site {
  std::string name;
  std::string siteClass;   // CORE, PAD, ...
  Dbu width = 0, height = 0;  // DBU
  std::string symmetry;    // as written, e.g. "Y" or "X Y"
};

// One pin or obstruction shape in macro-local coordinates (after the LEF
// ORIGIN shift, so the macro's lower-left corner is (0,0)). A POLYGON is kept
// with its points and its bounding box in `rect`.
struct MacroShape {
  LayerId layer;
  Rect rect;                  // DBU
  std::vector<Point> polygon; // DBU, empty for a RECT
};

struct MacroPin {
  std::string name;
  std::string direction;  // INPUT, OUTPUT, INOUT, FEEDTHRU or empty
  std::string use;        // SIGNAL, POWER, GROUND, CLOCK, ... or empty
  std::vector<MacroShape> shapes;  // all PORTs together
  int portCount = 0;
};

struct Macro {
  std::string name;
  std::string macroClass;  // "CORE", "BLOCK", "PAD INPUT", ... as written
  Point origin;            // DBU, LEF ORIGIN
  Dbu width = 0, height = 0;  // DBU, SIZE
  std::string site;
  std::string symmetry;
  std::vector<MacroPin> pins;
  std::vector<MacroShape> obstructions;
  StringMap<int> pinIndex;  // pin name -> index into pins
};

// One layer of a NONDEFAULTRULE (LEF "LAYER l WIDTH w ; [SPACING s ;] [WIREEXTENSION e ;] END l",
// DEF "+ LAYER l WIDTH w [SPACING s] [WIREEXT e]").
struct NdrLayer {
  LayerId layer;
  Dbu width = 0;    // DBU, wire width on this layer for nets of the rule
  Dbu spacing = 0;  // DBU, minimum spacing (0 = the layer's own rules)
  Dbu wireExt = 0;  // DBU (0 = half the width)
};

// A non-default routing rule, from a LEF NONDEFAULTRULE block or a DEF NONDEFAULTRULES entry.
struct NonDefaultRule {
  std::string name;
  bool hardSpacing = false;
  std::vector<NdrLayer> layers;
  std::vector<std::string> vias;      // VIA / USEVIA names (DEF + VIA, + VIARULE names in viaRules)
  std::vector<std::string> viaRules;  // USEVIARULE names
  // The rule's layer entry for `layer`, or nullptr (the layer's defaults apply).
  const NdrLayer* find(LayerId layer) const {
    for (const NdrLayer& l : layers) {
      if (l.layer == layer) return &l;
    }
    return nullptr;
  }
};

struct Tech {
  int dbuPerMicron = 0;        // LEF UNITS DATABASE MICRONS (0 until read)
  Dbu manufacturingGrid = 0;   // DBU (0 = none given)
  std::string version;
  std::string busBitChars = "[]";
  std::string dividerChar = "/";
  std::string clearanceMeasure;  // EUCLIDEAN or MAXXY, empty if not given

  std::vector<Layer> layers;       // all layers in LEF order
  std::vector<LayerId> routingLayers;  // routingIndex -> layer
  std::vector<LayerId> cutLayers;      // cutIndex -> layer
  std::vector<Via> vias;
  std::vector<ViaRule> viaRules;
  std::vector<Site> sites;
  std::vector<Macro> macros;
  std::vector<NonDefaultRule> ndrs;  // LEF NONDEFAULTRULE blocks

  StringMap<LayerId> layerIndex;
  StringMap<ViaId> viaIndex;
  StringMap<ViaRuleId> viaRuleIndex;
  StringMap<SiteId> siteIndex;
  StringMap<MacroId> macroIndex;
  StringMap<int> ndrIndex;  // name -> index into ndrs

  // Statements the reader did not understand and skipped, by keyword.
  std::vector<std::pair<std::string, int>> skippedStatements;
  int warningCount = 0;
  // Odd but routable things found while reading, "file:line: message" (also in warningCount).
  std::vector<std::string> warnings;

  const Layer& layer(LayerId id) const { return layers[*id]; }
  LayerId findLayer(std::string_view name) const;
  ViaId findVia(std::string_view name) const;
  MacroId findMacro(std::string_view name) const;
  ViaRuleId findViaRule(std::string_view name) const;
};

}  // namespace xroute
