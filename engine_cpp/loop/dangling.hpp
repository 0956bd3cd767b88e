// Routing that joins nothing: a wire's end past the last thing it meets, a via with nothing on one
// of its layers, a patch left touching none of its net's metal.
#pragma once

#include <cstdint>

#include "db/design.hpp"

namespace xroute {

struct TrimCounts {
  int64_t wires = 0;    // wires removed
  int64_t shortened = 0;  // wires cut back
  int64_t vias = 0;     // vias removed
  int64_t patches = 0;  // patches removed
  int64_t length = 0;   // DBU of centre line removed

  bool any() const { return wires + shortened + vias + patches > 0; }
  TrimCounts& operator+=(const TrimCounts& o) {
    wires += o.wires, shortened += o.shortened, vias += o.vias, patches += o.patches, length += o.length;
    return *this;
  }
};

// Cuts net n's routing back to what joins its pins and pieces, read on centre lines
// (CentreLineIndex): an end of a wire or a via's layer is held when it lies in one of the net's pin
// shapes on its layer or on another piece's centre line. An end that is not held goes back to the
// nearest thing along the wire that is (a point of another piece, or a pin shape crossing it), or
// the wire goes; a via with a layer not held goes; repeated until nothing changes. A patch that
// touches none of the net's wires or vias left then goes too. Pins stay joined: every removed
// piece was an end, and an end holds no pin.
TrimCounts trimDangling(const Tech& tech, Design& design, NetId n);
// trimDangling on every net; the sum.
TrimCounts trimDanglingAll(const Tech& tech, Design& design);

}  // namespace xroute
