// Multi-terminal A* on a region grid: grows one tree from the first
// terminal, each round searching from the whole tree to the nearest
// terminal not yet reached, until every terminal is connected. The
// estimate to go is the planar distance to the nearest unreached
// terminal's nodes plus a via for each layer between (exact search).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "grid/region_grid.hpp"

namespace xroute {

struct MazeCosts {
  int64_t viaCost = 1200;          // cost units (DBU of wire) per via, at least viaPitches pitches
  // A via costs at least this many pitches of the second routing layer's wire (pitchCosts): the
  // contest scorer's via weight in its unit of wire. 1,600 on ispd18_test1 (pitch 400); viaCost where
  // the pitch is 200 (the ISPD-2019 designs, ispd18_sample3): there 4 pitches (800) measured 39,038
  // vias on ispd19_test1 against 37,325. Against viaCost alone (2026-11-27, 2 threads, 0 violations):
  // contest score ispd18_test1 290,989 -> 290,154 (34,538 -> 32,999 vias); generated designs of 3,000
  // cells on ispd18_test2's technology 163,098 -> 162,551 and 148,432 -> 147,873. 0: viaCost alone.
  int64_t viaPitches = 4;
  int64_t wrongWayFactor = 4;      // wrong-way wire length multiplier
  // Wire length / via multiplier outside the net's guides, as the contest scorer counts them (a wire's
  // centre line, a via's centre on either layer). 3 is the scorer's weight for wire: 1 a pitch outside
  // on top of 0.5 a pitch (for a via, 1 on top of 2; the one factor serves both). Against 2
  // (2026-11-27, 2 threads, 0 violations either way): contest score ispd18_test1 291,944 -> 291,326,
  // ispd19_test1 422,954 -> 421,750 (63,710.1 -> 63,958.4 um).
  int64_t outOfGuideFactor = 3;
  // outOfGuideFactor where the guides are the built-in global router's (Design::guidesBuiltIn, applied
  // by guideCosts): no scorer counts wire outside them, they only plan the congestion. 1 measured
  // better than 2 on ispd19_test3, ispd18_test1 and ispd19_test1 with built-in guides (loop/README.md).
  int64_t builtInGuideFactor = 1;
  int64_t fixedPenalty = 400000;   // entering a node a fixed shape of another net forbids
  int64_t usePenalty = 8000;       // per routed shape of another net a wire/via here would violate
  int64_t markerUnit = 1;          // multiplier of RegionGrid::markerCost
  int64_t bottomLayerFactor = 1;   // wire length multiplier on routing layer 0 (the pin layer). With the
                                   // pin-access and access-exit rules, 1 measured better than 2 and 4 on
                                   // ispd18_test1 (2 threads: 36,690 vias / contest score 325,731 vs
                                   // 38,194 / 329,643 and 39,101 / 336,126; 0 violations each)
  int64_t reservePenalty = 20000;  // entering another net's access point or boundary terminal
  // Entering the landing right above another net's access point (its via's metal) while that net is
  // unrouted. 0 measured best on ispd18_test1 (contest score 293,217 -> 291,859, 34,794 -> 34,440 vias;
  // 2,000: 292,280; 6,000: 293,144; 20,000 before) and on ispd19_test1, a little worse on ispd19_test3
  // (loop/README.md): the detours it forced on the nets routed first cost more than the markers it spared.
  int64_t landingPenalty = 0;
  // Entering the landing above the one access point of another unrouted net's pin that offers a
  // via up (kSoleLanding): a wire there leaves that pin no way up but a short or a metal-1 detour.
  // -1 (the default, automatic): kSoleLandingPenalty where at least kSoleLandingShare of the
  // design's net pins have one via point, else 0 (soleLandingCosts).
  int64_t soleLandingPenalty = -1;
  int64_t crossingPull = 2;        // per DBU a free crossing lies off the range of the pins beyond it
  // Cost units per DBU of a step's wire length and of the A* estimate's distance: set by pitchCosts,
  // 1 where the second routing layer's pitch is kCostPitch or more. crossingPull stays per DBU.
  int64_t wireUnit = 1;
};

// soleLandingPenalty's automatic value. Where most pins have one via point (Nangate45's small metal-1
// pins under a metal-2 pitch wider than they are: 64% of gcd's net pins, 67% of aes's), a wire over
// such a landing leaves the pin a short, and the penalty pays: at 8,000 (2 threads, 2026-11-29)
// OpenROAD's aes on Nangate45 went from 0.71 first-pass violations a net to 0.43, 897 s to 547 s,
// and from 1 violation left after 16 iterations to 0 after 7. Where fewer do (every ISPD design
// here: 18-46%; asap7 4-7%; sky130 4-43%) it stays 0: charged there, aes on asap7 ended at 2
// CornerSpacing markers after 16 iterations (0 after 15 without) and ispd19_test3 at 1 CutSpacing
// marker (0 after 10), and ispd18_test1's contest score went up 0.03% (loop/README.md).
inline constexpr int64_t kSoleLandingPenalty = 8000;
inline constexpr double kSoleLandingShare = 0.5;

// `c` with an automatic soleLandingPenalty resolved for a design where `soleShare` of the net pins
// have one access point that offers a via up.
inline MazeCosts soleLandingCosts(MazeCosts c, double soleShare) {
  if (c.soleLandingPenalty < 0) c.soleLandingPenalty = soleShare >= kSoleLandingShare ? kSoleLandingPenalty : 0;
  return c;
}

// `c` for a design whose guides are the built-in global router's (builtIn) or a guide file's.
inline MazeCosts guideCosts(MazeCosts c, bool builtIn) {
  if (builtIn) c.outOfGuideFactor = c.builtInGuideFactor;
  return c;
}

// The penalties above are cost units a node or a shape, set on technologies whose second routing
// layer's pitch is 200 to 400 DBU (the ISPD designs). Where the pitch is finer (OpenROAD's asap7 gcd,
// DEF units of 1,000 a micron: 45), a DBU of wire counts kCostPitch / pitch units, rounded (wireUnit:
// 4 there), so that a penalty spans about as many tracks as at 200 DBU. Counted in DBU, one use
// penalty (8,000) was worth 178 tracks of wire there: the searches flooded their regions before they
// would pay one, and that gcd (416 nets) took 46 s where it takes 11 s with the unit (loop/README.md).
constexpr int64_t kCostPitch = 200;

// `c` for a technology whose second routing layer has pitch `pitch` (DBU; 0: unknown).
inline MazeCosts pitchCosts(MazeCosts c, int64_t pitch) {
  c.wireUnit = pitch > 0 && pitch < kCostPitch ? std::max<int64_t>(1, (kCostPitch + pitch / 2) / pitch) : 1;
  if (pitch > 0 && c.viaPitches > 0) c.viaCost = std::max(c.viaCost, c.viaPitches * pitch * c.wireUnit);
  return c;
}

struct MazeTerminal {
  std::vector<int32_t> nodes;  // grid nodes; reaching any one of them connects the terminal
  bool joined = true;          // true: the nodes are one conductor (a pin's access points, a via's
                               // two layers), so all of them join the tree; false: alternatives
  std::vector<int64_t> exitCost;  // optional, per node: cost added when the route ends there
  // Joined terminals of one group >= 0 are one conductor outside the grid (a ripped-up net's kept
  // routing): reaching one reaches them all. -1: a group of its own.
  int32_t group = -1;
};

struct MazeNet {
  int32_t net = -1;
  std::vector<MazeTerminal> terminals;
  const NodeArray<uint8_t>* inGuide = nullptr;  // per node, 1 = inside the net's guides; null = all
  // A net of a NONDEFAULTRULE: per node, the cost units its wider wire (ruleWire) or its via's
  // metal kept at the rule's spacing (ruleVia) adds there; null for a net of the default rule.
  const NodeArray<int32_t>* ruleWire = nullptr;
  const NodeArray<int32_t>* ruleVia = nullptr;
  // (node, cost units) added to a via step from or to the node: the net's access points whose via
  // pin access chose is not the one the grid's footprints assume, where that via's metal breaks a
  // rule with another net's routed metal; null: none.
  const std::vector<std::pair<int32_t, int64_t>>* accessVia = nullptr;
};

// An entry of the search's open list: least estimate first, then least cost so far, then node.
struct MazeOpenEntry {
  int64_t estimate;  // cost so far plus the heuristic
  int64_t cost;
  int32_t node;
};

// The same order packed into one number (route/maze.cpp's OpenList).
using MazeOpenKey = unsigned __int128;

// The open list's storage (route/maze.cpp's OpenList): a heap of the least entries and 64 buckets.
template <class Entry>
struct MazeOpenStorage {
  std::vector<Entry> least;
  std::array<std::vector<Entry>, 64> buckets;
};

// Reusable search buffers (one per thread), per node of the region's grid.
struct MazeWorkspace {
  // The open list's storage, reused by every search round: packed, or not where the heuristic can
  // exceed 32 bits.
  MazeOpenStorage<MazeOpenKey> packedOpen;
  MazeOpenStorage<MazeOpenEntry> open;
  NodeArray<int64_t> cost;
  NodeArray<int32_t> parent;
  // Search round r (stamps 2r, 2r + 1): 2r = cost / parent valid, 2r + 1 = expanded too.
  NodeArray<uint32_t> visit;
  NodeArray<uint32_t> inTree;      // stamp of the net being routed
  NodeArray<int32_t> terminalSlot;  // index into the route's terminal slots, else -1
  uint32_t stamp = 0;               // the round's even stamp
  uint32_t treeStamp = 0;
};
// Bytes of MazeWorkspace's per-node arrays, held by a static_assert in maze.cpp.
inline constexpr size_t kSearchBytesPerNode = 24;

// Appends one node path per round to `paths` (from a tree node to a terminal
// node, inclusive). Returns the number of terminals that could not be
// reached (0 = connected).
// The six moves from a node (index = direction): the neighbour the maze's edge
// that way reaches (-1: no edge) and its step cost for `net`, as the search
// counts it. Wrong-way edges go to the next existing node.
enum MazeDirection : int { kMoveUp = 0, kMoveDown, kMoveNorth, kMoveSouth, kMoveEast, kMoveWest, kMoveCount };
struct MazeMove {
  int32_t node = -1;
  int64_t cost = 0;
};
void mazeMoves(const RegionGrid& grid, const MazeCosts& costs, const MazeNet& net, int32_t node,
               std::array<MazeMove, kMoveCount>& out);

int routeMaze(const RegionGrid& grid, const MazeCosts& costs, const MazeNet& net, MazeWorkspace& ws,
              std::vector<std::vector<int32_t>>& paths);

}  // namespace xroute
