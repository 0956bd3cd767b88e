// Internal to pin access (not part of the public pa/pin_access.hpp): the
// pieces computePinAccess is assembled from, one file each.
//   pin_geometry.cpp    pin metal as rects per routing layer, cut coverage
//   layer_access.cpp    per routing layer: up vias, candidate tracks, stub size
//   candidates.cpp      candidate points of one pin with their costs
//   access_checker.cpp  legality of a via or a planar stub at a point (drc)
//   pin_points.cpp      choosing a pin's points (spread, fallback)
//   pin_access.cpp      classes of components, threads, the flat table
#pragma once

#include <cstdint>
#include <vector>

#include "drc/drc.hpp"
#include "geom/box_index.hpp"
#include "pa/pin_access.hpp"

namespace xroute::pa {

// Costs of one coordinate of a candidate point (the point's cost is the sum
// over x and y; see candidates.cpp).
inline constexpr int32_t kCostOnTrack = 0;
inline constexpr int32_t kCostHalfTrack = 1;
inline constexpr int32_t kCostCentre = 2;
inline constexpr int32_t kCostEnclosedEdge = 3;   // the cut just fits at a shape edge
// Added to a point that has only planar exits on a layer that has vias up.
inline constexpr int32_t kCostPlanarOnly = 8;
// The fallback point of a pin without any legal point.
inline constexpr int32_t kCostFallback = 100;

// One rect of a pin's metal on routing layer z.
struct PinRect {
  int32_t z = 0;  // routing index
  Rect rect;      // DBU
};

// ---- pin_geometry.cpp ----

// Area of `r` outside the union of the rects of `metal` on layer z (DBU^2).
Area uncoveredArea(const std::vector<PinRect>& metal, int32_t z, const Rect& r);

// True when `r` (with positive area) is covered by the union of the rects of
// `metal` on layer z.
bool coveredBy(const std::vector<PinRect>& metal, int32_t z, const Rect& r);

// ---- layer_access.cpp ----

// What pin access needs to know about one routing layer z.
struct LayerAccess {
  LayerId layer;                 // the LEF layer of routing index z
  std::vector<ViaId> upVias;     // LEF vias from z to z+1: DEFAULT ones first, then LEF order
  std::vector<Dbu> xTracks;      // DBU, sorted: x coordinates counted as on-track
  std::vector<Dbu> yTracks;      // DBU, sorted: y coordinates counted as on-track
  bool spreadOnX = true;         // points are spread over distinct x (else y)
  Rect cutBox;                   // DBU, bounding box of the first up via's cuts (empty if none)
  Dbu stubWidth = 0;             // DBU, width of a planar exit stub (the layer's min width)
  Dbu stubLength = 0;            // DBU, length of a planar exit stub (the preferred pitch)
  bool hasUp() const { return !upVias.empty(); }
};

// Per routing layer. On-track coordinates for a layer with a via up: x on the
// preferred tracks of whichever of z+1 and z is vertical (z+1 first), y on
// those of whichever is horizontal; for the top layer its own X / Y tracks.
std::vector<LayerAccess> buildLayerAccess(const Tech& tech, const TrackSet& tracks);

// The DEF track patterns that decide the on-track coordinates of layer z
// (its own and those of z+1), as indices into Design::tracks.
std::vector<int32_t> relevantTrackPatterns(const Tech& tech, const Design& design, int32_t z);

// ---- candidates.cpp ----

struct Candidate {
  Point at;          // DBU
  int32_t z = 0;     // routing index
  int32_t cost = 0;  // sum of the two coordinate costs
  int64_t dist = 0;  // doubled Manhattan distance to the pin's centre (DBU)
};

// Candidate points of one pin (its rects on routing layers), deduplicated,
// sorted by (cost, dist, higher z first, x, y).
std::vector<Candidate> pinCandidates(const std::vector<LayerAccess>& layers, const std::vector<PinRect>& pin);

// Doubled centre of the bounding box of the pin's rects (2x, 2y, DBU).
Point pinCentre2(const std::vector<PinRect>& pin);

// ---- access_checker.cpp ----

// How far inside its cell a via's metal on `layer` must stay when its cut
// is not covered by the pin: the largest spacing the layer asks of a line
// end or of min-width shapes (DBU).
Dbu keepInMargin(const Layer& layer);

// Checks vias and planar stubs at points of one pin against a fixed context
// (the other pins of its component with their own ids, its OBS as -1). A
// candidate is illegal when adding its shapes creates a design-rule marker
// that the context alone does not have (min area is ignored: the router's
// wire fixes it). Only the context near the candidate takes part: the shapes
// within the layers' interaction range of it (see access_checker.cpp).
class AccessChecker {
 public:
  // cell: the placed box of the pin's component (SIZE); empty (zero area)
  // for an IO pin.
  AccessChecker(const Tech& tech, std::vector<DrcShape> context, Rect die, Rect cell = {});

  // The via's shapes at `at` on net `net`: every cut inside the die and no
  // new marker; every cut inside `metal` (layer z), or, in a component,
  // the via's metal on z at least keepInMargin of z inside the cell (the
  // cut then sticks out of a narrow pin onto the via's own metal, away from
  // the neighbouring cells, which the context does not hold).
  bool viaLegal(const Via& via, Point at, int32_t net, const std::vector<PinRect>& metal, int32_t z) const;

  // A stub of the layer's width from `at` one stub length towards `dir`.
  bool stubLegal(const LayerAccess& layer, Point at, AccessDir dir, int32_t net) const;

  // Number of candidate checks so far (for measurements).
  int64_t checks() const { return checks_; }

 private:
  bool addsMarker(const std::vector<DrcShape>& added) const;

  const Tech& tech_;
  std::vector<DrcShape> context_;
  BoxIndex index_;                      // over context_ rects
  std::vector<Dbu> range_;              // DBU, per LEF layer: drc interaction range
  Rect die_;                            // DBU
  Rect cell_;                           // DBU, the component's box (zero area: none)
  std::vector<Dbu> keepIn_;             // DBU, per LEF layer: keepInMargin
  // The last local context (ids into context_) and its markers, sorted,
  // min area removed: consecutive candidates of a pin usually share it.
  mutable std::vector<int32_t> lastIds_;
  mutable std::vector<Marker> lastBaseline_;
  mutable bool haveLast_ = false;
  mutable int64_t checks_ = 0;
};

// ---- pin_points.cpp ----

struct PinPointsResult {
  std::vector<AccessPoint> points;  // best first
  bool fallback = false;            // no legal point: one fallback point
};

// Chooses at most maxPoints legal points of the pin whose context is in
// `checker` (the pin's own shapes carry net id `net` there).
PinPointsResult choosePinPoints(const Tech& tech, const std::vector<LayerAccess>& layers,
                                const AccessChecker& checker, const std::vector<PinRect>& pin, int32_t net,
                                int maxPoints);

}  // namespace xroute::pa
