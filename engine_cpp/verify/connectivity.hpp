// Connectivity (opens) check of a routed design: does each regular net's
// routing join all of its pins?
//
// Conductors of one net: its pins' shapes (all shapes of one pin are one
// node: the ports of a pin are connected inside the cell), its wires (ends
// extended by half the width unless an extension is given), its vias (all
// shapes of one via are one node) and its patches. Two same-layer shapes are
// connected when they overlap or share a boundary segment of positive length;
// touching at a single corner point does not connect (the DRC checker's
// rule). Different layers connect only through a via's shapes.
#pragma once

#include <cstdint>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"

namespace xroute {

struct NetConnectivity {
  NetId net;
  int32_t pinCount = 0;        // pins of the net
  int32_t pinGroups = 0;       // connected components holding at least one pin
  int32_t floatingPieces = 0;  // connected components of routing holding no pin
  bool open = false;           // pinGroups > 1
  // Open nets only: the pins of each group as indices into Design::pinRefs,
  // ascending within a group, groups ordered by their first pin.
  std::vector<std::vector<int32_t>> groups;
};

struct ConnectivityReport {
  std::vector<NetConnectivity> nets;  // one per checked net, by net id
  int32_t netsChecked = 0;      // regular nets with >= 2 pins
  int32_t openNets = 0;         // checked nets whose pins are not all connected
  int32_t singlePinNets = 0;    // regular nets with fewer than 2 pins (not checked)
  int32_t unroutedNets = 0;     // checked nets without any routing
  int32_t floatingPieces = 0;   // sum over checked nets
};

// Checks every regular net with at least two pins. Special nets are not
// checked. Pin shapes are placed as the DEF says (placement status is not
// looked at); a POLYGON pin shape counts as its bounding box.
ConnectivityReport checkConnectivity(const Tech& tech, const Design& design);

}  // namespace xroute
