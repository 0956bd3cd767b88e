// Pin access: for every pin a net connects (every entry of Design::pinRefs),
// a few legal points where a route may start or end, best first.
#pragma once

#include <cstdint>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "grid/tracks.hpp"

namespace xroute {

// Exits a route may take from an access point.
enum AccessDir : uint8_t {
  kAccessUp = 1,      // a via to the routing layer above (upVia)
  kAccessEast = 2,    // planar on the pin's layer, towards +x
  kAccessWest = 4,
  kAccessNorth = 8,   // towards +y
  kAccessSouth = 16,
};

struct AccessPoint {
  Point at;              // DBU, inside (or on the edge of) a shape of the pin
  int32_t z = 0;         // routing index of the pin shape's layer
  uint8_t dirs = 0;      // AccessDir bits
  ViaId upVia;           // LEF via used for kAccessUp (legal at this point)
  int32_t cost = 0;      // 0 = on-track in both axes; + 1 / 2 / 3 per half-track / centre /
                         // enclosed-edge coordinate; + 8 planar exits only; 100 = fallback
};

// Access points kept per pin (best first, spread over distinct wire
// coordinates). 6 measured on ispd18_test1: 3 gives 89,896 um / 13
// violations, 6 gives 89,027 um / 37 (with the router's default marker and
// history costs), 10 gives more violations and no shorter wires after repair.
inline constexpr int kAccessPointsPerPin = 6;

struct PinAccessSettings {
  int maxPointsPerPin = kAccessPointsPerPin;  // keep at most this many, best first
  int threads = 1;
  bool shareClasses = true;  // false: compute every component on its own (to check the classes)
  // Check component pins' access vias again among every design shape around them (see pin_access.cpp).
  bool checkInContext = true;
};

// Flat per-pinRef table: pinRef i owns points[start[i] .. start[i+1]).
struct PinAccessTable {
  std::vector<int32_t> start;       // size pinRefs.size() + 1
  std::vector<AccessPoint> points;
  int32_t fallbackPins = 0;         // pinRefs whose only point is a fallback (no legal point found)
  int32_t classes = 0;              // component classes computed (IO pins not counted)

  int32_t count(int32_t pinRef) const { return start[pinRef + 1] - start[pinRef]; }
  const AccessPoint* begin(int32_t pinRef) const { return points.data() + start[pinRef]; }
  const AccessPoint* end(int32_t pinRef) const { return points.data() + start[pinRef + 1]; }
};

// Computes access points for every pinRef. Unique component classes (macro,
// orientation, position modulo the track pitches) are computed once and
// reused. Every pin with at least one shape on a routing layer gets at least
// one point (a fallback at the centre of its largest shape when no legal
// point exists; such points have a high cost). Legality is checked against
// the pin's own component only (its other pins and OBS); an IO pin against
// every design shape around it (pad cells, rings); see pa/README.md. Then
// (checkInContext) each component pin's access via is checked again among
// every design shape around it, and loses its via exit if it adds a marker.
PinAccessTable computePinAccess(const Tech& tech, const Design& design, const TrackSet& tracks,
                                const PinAccessSettings& settings);

// The share of pin refs whose points offer a via up at exactly one of them (0 without pin refs).
double soleViaShare(const PinAccessTable& table);

}  // namespace xroute
