// Design-rule checker: shapes in, markers out. Rules, their LEF meaning and
// every semantic choice are documented in drc/README.md.
#pragma once

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
};

struct Marker {
  MarkerType type = MarkerType::Short;
  LayerId layer;
  Rect box;             // DBU: the overlap, the gap, or the offending area (see README)
  int32_t net1 = -1;    // the smaller net id (EOL: the line-end's net)
  int32_t net2 = -1;    // the other net; -1 for an obstruction or a one-shape rule
  friend bool operator==(const Marker&, const Marker&) = default;
};

struct DrcOptions {
  bool skipFixedPairs = false;    // drop violations whose shapes are all fixed
  std::optional<Rect> window;     // DBU: report only markers whose box intersects it
  bool obsAsMinWidth = true;      // LEF USEMINSPACING OBS ON (the LEF default)
  bool mergeMarkers = true;       // merge same-kind markers whose boxes touch
  // NONDEFAULTRULE spacing: ndrSpacing[layer id][net id], DBU, the least gap a net's metal needs
  // on that layer besides the layer's own rules (0 = none); empty when no net has a rule.
  std::vector<std::vector<Dbu>> ndrSpacing;
  int threads = 1;                // layers checked at once (the markers do not depend on it)
};

// Markers sorted by (type, layer, box, net1, net2); independent of input order.
std::vector<Marker> checkShapes(const Tech& tech, std::vector<DrcShape> shapes, const DrcOptions& options = {});

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
