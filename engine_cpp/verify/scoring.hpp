// Routing-preference figures of a routed design in the style of the ISPD
// 2018/2019 contest scorer: out-of-guide wire length and vias, off-track wire
// length and vias, wrong-way wire length. Regular nets (NETS) only. The
// contest's evaluator is a binary without public source; these are our
// definitions of its published terms (verify/README.md):
//
// A wire piece is a RouteWire with from != to; its length is |to - from|
// (extensions not counted, as in the wirelength).
// - wrong way: a horizontal piece on a VERTICAL layer or a vertical piece
//   on a HORIZONTAL layer (a layer without DIRECTION has no wrong way).
// - off track: a horizontal piece whose y is on no horizontal track line of
//   its layer (DEF "TRACKS Y ... LAYER l": lines y = start + i*step), or a
//   vertical piece whose x is on no vertical one ("TRACKS X"). A layer with
//   no track lines of that orientation does not count the piece either way.
// - out of guide: the part of the piece's centre line outside the union of
//   the net's guide rects on its layer (closed rects: the boundary is in).
// A via is a RouteVia at point (x, y) between routing layers B and T (the
// via's bottom and top metal).
// - off track: on B or on T, the point is off the layer's preferred-
//   direction tracks: y on no TRACKS Y line of a HORIZONTAL layer, x on no
//   TRACKS X line of a VERTICAL one (with alternating directions: not on a
//   track crossing). A layer without DIRECTION or without such lines is not
//   looked at.
// - out of guide: the point is outside every guide rect of the net on B, or
//   outside every one on T (closed rects).
#pragma once

#include <cstdint>
#include <optional>

#include "db/design.hpp"
#include "db/tech.hpp"

namespace xroute {

struct GuideTrackFigures {
  int64_t wrongWayWirelength = 0;   // DBU
  int64_t offTrackWirelength = 0;   // DBU
  int64_t offTrackVias = 0;         // via instances
  bool hasGuides = false;           // a guide file was read
  int64_t outOfGuideWirelength = 0; // DBU (0 when !hasGuides)
  int64_t outOfGuideVias = 0;       // via instances (0 when !hasGuides)
};

GuideTrackFigures computeGuideTrackFigures(const Tech& tech, const Design& design);

// The contest score's unit of length, DBU: the LEF PITCH of the second routing layer (the first's
// with one; 0 with none). The maze's via cost (route/maze.hpp pitchCosts) counts in it too.
Dbu scorerPitch(const Tech& tech);

}  // namespace xroute
