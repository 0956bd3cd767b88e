// Design-rule checker: shapes in, markers out. Rules, their LEF meaning and
// every semantic choice are documented in drc/README.md.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "geom/geom.hpp"

namespace xroute {

// Pins, obstructions and special-net shapes are "fixed": present in the input.
enum class ShapeOrigin : uint8_t { Wire, Via, Pin, Obstruction, SpecialNet };

enum class MarkerType : uint8_t { Short, MetalSpacing, EndOfLine, CutShort, CutSpacing, AdjacentCuts, MinArea, CornerSpacing };

struct DrcShape {
  LayerId layer;        // routing or cut layer (other layers are ignored)
  Rect rect;            // DBU
  int32_t net = -1;     // conductor id; < 0 = obstruction (conflicts with every net)
  ShapeOrigin origin = ShapeOrigin::Wire;
  // Regular routing of a net of a NONDEFAULTRULE drawn to the default rule (DEF TAPER: taperedWire,
  // RouteVia::taper, RoutePatch::taper): the rule's SPACING does not hold around it.
  bool taper = false;
};

struct Marker {
  MarkerType type = MarkerType::Short;
  LayerId layer;
  Rect box;             // DBU: the overlap, the gap, or the offending area (see README)
  int32_t net1 = -1;    // the smaller net id (EOL: the line-end's net)
  int32_t net2 = -1;    // the other net; -1 for an obstruction or a one-shape rule
  friend bool operator==(const Marker&, const Marker&) = default;
};

// DrcOptions::bandShapes's default. On the routed 8x8 tiles of ispd18_test1 a band of 1.9 million
// shapes held about 140 MB at its peak (2 threads).
inline constexpr int64_t kCheckBandShapes = 2'000'000;

struct DrcOptions {
  bool skipFixedPairs = false;    // drop violations whose shapes are all fixed
  std::optional<Rect> window;     // DBU: report only markers whose box intersects it
  bool obsAsMinWidth = true;      // LEF USEMINSPACING OBS ON (the LEF default)
  bool mergeMarkers = true;       // merge same-kind markers whose boxes touch
  // NONDEFAULTRULE spacing: ndrSpacing[layer id][net id], DBU, the least gap a net's routing needs
  // on that layer besides the layer's own rules (0 = none); empty when no net has a rule. It holds
  // around the net's routing only: not around its pins (fixed shapes) nor its tapered shapes
  // (DrcShape::taper), as OpenROAD's checker reads the rule.
  std::vector<std::vector<Dbu>> ndrSpacing;
  int threads = 1;                // layers checked at once (the markers do not depend on it)
  // checkDesign: a design of more shapes than this is checked in bands of about this many shapes
  // (drc/design_check.hpp); 0: always at once. The markers do not depend on it.
  int64_t bandShapes = kCheckBandShapes;
};

// Same-net rects on a layer are one conductor when they share a segment, not just a corner point.
inline bool sharesSegment(const Rect& a, const Rect& b) {
  const int64_t ox = int64_t(std::min(a.xhi, b.xhi)) - std::max(a.xlo, b.xlo);
  const int64_t oy = int64_t(std::min(a.yhi, b.yhi)) - std::max(a.ylo, b.ylo);
  return ox >= 0 && oy >= 0 && (ox > 0 || oy > 0);
}

// Markers sorted by (type, layer, box, net1, net2); independent of input order.
std::vector<Marker> checkShapes(const Tech& tech, std::vector<DrcShape> shapes, const DrcOptions& options = {});

// What a partial check judges, after some nets' routing changed (loop/incremental_check.hpp): a
// zone per layer, the cells of a grid over `area` that zone rects touch (cells of at least the
// layer's reach, at most 1024 along a side), and the changed nets. A marker is the zone's when its box touches a zone cell
// of its layer; a MinArea marker (a whole conductor's) when its net changed on its layer. Shapes
// within reach() of a zone cell, and every shape of a net on a layer where it changed, start the rules.
class CheckZone {
 public:
  CheckZone() = default;
  CheckZone(const Tech& tech, const DrcOptions& options, size_t nets, const Rect& area);
  // Marks the cells the rect touches inside the area (and has the layer checked in any case).
  void add(LayerId layer, const Rect& rect);
  void addNet(int32_t net, LayerId layer);     // the net changed on the layer
  bool empty() const { return nets_.empty(); }
  // The zone's cells on the layer as rects, one per add() (the touched cells' bounding box).
  const std::vector<Rect>& rects(LayerId layer) const { return rects_[*layer]; }
  // DBU: how far a rule of the layer looks from a marker's box to the shapes that make it (twice the
  // layer's interaction range, NONDEFAULTRULE spacings included, plus its widest line end).
  Dbu reach(LayerId layer) const { return reach_[*layer]; }
  bool judgesNet(int32_t net, LayerId layer) const {
    const std::vector<uint8_t>& f = netFlag_[*layer];
    return net >= 0 && size_t(net) < f.size() && f[net];
  }
  // Some zone cell of the layer within `margin` of `rect` (a cell is [lo, lo + side) on each axis).
  bool near(LayerId layer, const Rect& rect, Dbu margin) const;
  bool judges(const Marker& m) const;
  const std::vector<int32_t>& nets() const { return nets_; }
  // A MinArea marker is the zone's when its box touches a zone cell, like the others (a band of a
  // whole-design check, where no net changed and every conductor near the band is judged).
  void judgeMinAreaByBox() { minAreaByBox_ = true; }
  // The part of the zone in the rows [ylo, yhi]: its rects clipped to them (cell by cell, as add()
  // marks them), no net. Parts for rows that tile the area together hold every cell of the zone.
  CheckZone rows(Dbu ylo, Dbu yhi) const;

 private:
  bool cellRange(size_t layer, const Rect& r, int& x0, int& x1, int& y0, int& y1) const;

  Rect area_;
  std::vector<Dbu> side_;                 // by layer id: DBU, a cell's side
  std::vector<int> nx_, ny_;              // by layer id: cells along x and y
  std::vector<std::vector<uint8_t>> cells_;  // by layer id: nx_ * ny_ flags, empty while none is set
  std::vector<std::vector<Rect>> rects_;  // by layer id
  std::vector<Dbu> reach_;                // by layer id
  size_t netCount_ = 0;
  std::vector<std::vector<uint8_t>> netFlag_;  // by layer id, by net id (empty: none on the layer)
  std::vector<uint8_t> anyNet_;           // by net id: added on some layer
  std::vector<int32_t> nets_;             // every net added, once
  bool minAreaByBox_ = false;
};

// checkShapes before its last step: the markers of the rules, fixed ones dropped under
// skipFixedPairs, not merged, in no particular order. With a zone: only the zone's markers, from
// the shapes near it; `links` (empty, or one per shape) joins the shapes that share a value >= 0
// into one conductor besides their same-net contacts (a conductor cut by the choice of shapes).
std::vector<Marker> checkShapesUnmerged(const Tech& tech, std::vector<DrcShape> shapes, const DrcOptions& options,
                                        const CheckZone* zone = nullptr, const std::vector<int32_t>& links = {});
// checkShapes's last step: merges touching markers (mergeMarkers), keeps the window's, sorts, dedupes.
std::vector<Marker> finishMarkers(std::vector<Marker> markers, const DrcOptions& options);
// Sorts markers by (type, layer, box, net1, net2) and drops exact repeats (finishMarkers's order).
void sortMarkers(std::vector<Marker>& markers);

// Every metal and cut shape of a placed design, with net ids: regular nets
// [0, nets), special nets [nets, nets + specialNets), then one id per pin on
// no net. Obstructions (cell OBS, DEF layer blockages) have net -1.
// netNames, when given, receives a name per net id: the net's name, then
// "comp/pin", "*/pin" (POWER/GROUND pins sharing an id) or "PIN/name" (IO pin).
// DrcOptions::ndrSpacing for a design: the SPACING of each net's NONDEFAULTRULE, by layer and
// net id (regular nets only); empty when no net names a rule with a spacing.
std::vector<std::vector<Dbu>> ndrSpacingByNet(const Tech& tech, const Design& design);

std::vector<DrcShape> collectDesignShapes(const Tech& tech, const Design& design,
                                          std::vector<std::string>* netNames = nullptr);
// collectDesignShapes's fixed shapes only (pins, obstructions, special nets; no regular routing),
// with the same net ids and names.
std::vector<DrcShape> collectFixedShapes(const Tech& tech, const Design& design,
                                         std::vector<std::string>* netNames = nullptr);

// The marker type's name as reports write it; "Unknown" for a value outside the enum.
constexpr std::string_view markerTypeName(MarkerType type) {
  switch (type) {
    case MarkerType::Short: return "Short";
    case MarkerType::MetalSpacing: return "MetalSpacing";
    case MarkerType::EndOfLine: return "EndOfLine";
    case MarkerType::CutShort: return "CutShort";
    case MarkerType::CutSpacing: return "CutSpacing";
    case MarkerType::AdjacentCuts: return "AdjacentCuts";
    case MarkerType::MinArea: return "MinArea";
    case MarkerType::CornerSpacing: return "CornerSpacing";
  }
  return "Unknown";
}

// The number of marker types: the enum's values are 0..kMarkerTypes-1. A new
// type is appended to the enum; markerTypeName's switch must name it (-Wswitch),
// and then this count must follow, or the static_assert below fails.
inline constexpr int kMarkerTypes = static_cast<int>(MarkerType::CornerSpacing) + 1;
static_assert(markerTypeName(static_cast<MarkerType>(kMarkerTypes - 1)) != "Unknown" &&
                  markerTypeName(static_cast<MarkerType>(kMarkerTypes)) == "Unknown",
              "kMarkerTypes must be the number of MarkerType values");

// Spacing a routing layer requires between shapes of widths w1 and w2 with a
// parallel run length prl (DBU): the PRL table (row: last WIDTH strictly
// below the larger width; column: last PRL strictly below prl), else the
// plain SPACING rules that apply.
Dbu requiredSpacing(const Layer& layer, Dbu w1, Dbu w2, Dbu prl);
inline bool isFixedOrigin(ShapeOrigin o) { return o == ShapeOrigin::Pin || o == ShapeOrigin::Obstruction || o == ShapeOrigin::SpecialNet; }

}  // namespace xroute
