// The 3D grid graph of one routing region. Nodes sit at (xs[i], ys[j], z):
// xs / ys are every track coordinate of every routing layer inside the
// region box, the box edges, and the extra coordinates asked for (access
// points, boundary terminals). A node exists on layer z when its
// coordinate across z's preferred direction is one of z's preferred tracks
// (it lies on a track), or when it is an access point or terminal there.
//
// Edges are implicit: along the preferred direction between neighbouring
// nodes on one track; against it (wrong way) to the next existing node;
// up/down (vias) between existing nodes at the same (x, y).
//
// Cost fields are flat arrays indexed by node (struct of arrays); the RL
// side observes them as numpy views.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geom/geom.hpp"
#include "grid/node_array.hpp"
#include "grid/tracks.hpp"

namespace xroute {

enum NodeFlag : uint8_t {
  kOnTrack = 1,   // on one of the layer's preferred tracks
  kAccess = 2,    // an access point of a pin being routed in this region
  kTerminal = 4,  // a boundary terminal (where a net's outside routing ends)
  kLanding = 8,   // right above an access point: where its via lands (may be off-track)
  kAccessVia = 16,  // an access point whose via up pin access checked against fixed shapes
  kReleased = 32,   // a landing whose net is routed here: other nets' wires pass it freely
  kSoleLanding = 64,  // a landing above the only access point of its pin that offers a via up
};

inline constexpr int32_t kOwnerNone = -1;   // no shape claims the node
inline constexpr int32_t kOwnerMixed = -2;  // shapes of several nets / an obstruction
inline constexpr uint8_t kAnyExit = 0xFF;   // accessExits of a node that is no access point

// Observation node types (what the RL side sees).
enum class NodeType : uint8_t { NotExist = 0, Blockage = 1, Normal = 2, Access = 3 };

// Largest grid a region may have (kGridBytesPerNode plus the maze's
// kSearchBytesPerNode a node): a bigger one means the region size is far too
// large for the design.
inline constexpr size_t kMaxRegionNodes = 20'000'000;

// The grid lines of a region `box`: `xs` and `ys` hold extra coordinates (terminals) on entry and, on
// return, those within the box, its edges and every layer's tracks (preferred and cross) within
// it, sorted and unique.
void regionGridLines(const TrackSet& tracks, const Rect& box, std::vector<Dbu>& xs, std::vector<Dbu>& ys);

class RegionGrid {
 public:
  // Throws std::invalid_argument when the grid would exceed kMaxRegionNodes.
  RegionGrid(const TrackSet& tracks, const Rect& box, std::vector<Dbu> extraXs, std::vector<Dbu> extraYs);

  const Rect& box() const { return box_; }
  int nx() const { return static_cast<int>(xs_.size()); }
  int ny() const { return static_cast<int>(ys_.size()); }
  int nz() const { return nz_; }
  size_t size() const { return flags.size(); }
  const std::vector<Dbu>& xs() const { return xs_; }
  const std::vector<Dbu>& ys() const { return ys_; }
  bool horizontal(int z) const { return horizontal_[z] != 0; }

  int32_t index(int x, int y, int z) const { return (z * ny() + y) * nx() + x; }
  int xOf(int32_t n) const { return n % nx(); }
  int yOf(int32_t n) const { return (n / nx()) % ny(); }
  int zOf(int32_t n) const { return n / (nx() * ny()); }
  Point point(int32_t n) const { return {xs_[xOf(n)], ys_[yOf(n)]}; }

  // Index of an exact coordinate, -1 when it is not a grid line.
  int xIndex(Dbu x) const;
  int yIndex(Dbu y) const;
  // Grid lines strictly inside (lo, hi): [first, last] index range (first > last when none).
  void xRangeOpen(Dbu lo, Dbu hi, int& first, int& last) const;
  void yRangeOpen(Dbu lo, Dbu hi, int& first, int& last) const;

  bool exists(int32_t n) const { return flags[n] != 0; }
  NodeType nodeType(int32_t n) const;

  // The next existing node from the node at (x, y, z) against layer z's preferred direction
  // (dir = +1 / -1), or -1; x and y move to the neighbour's. Wrong-way edges go there.
  int32_t wrongWayNeighbour(int& x, int& y, int z, int dir) const {
    const int n = nx();
    if (horizontal(z)) {
      for (y += dir; y >= 0 && y < ny(); y += dir) {
        const int32_t m = index(x, y, z);
        if (flags[m]) return m;
      }
    } else {
      const int32_t row = (z * ny() + y) * n;
      for (x += dir; x >= 0 && x < n; x += dir) {
        if (flags[row + x]) return row + x;
      }
    }
    return -1;
  }

  // Per node (size nx*ny*nz; kGridBytesPerNode in all):
  NodeArray<uint8_t> flags;          // NodeFlag bits; 0 = the node does not exist
  NodeArray<int32_t> fixedOwner;     // wire here would violate a fixed shape: kOwnerNone, the one net allowed, or kOwnerMixed
  NodeArray<int32_t> viaFixedOwner;  // same for a via's metal landing here
  NodeArray<uint16_t> wireUse;       // routed shapes a wire here would violate
  NodeArray<int32_t> wireUseOwner;   // kOwnerNone, the only net those shapes belong to, or kOwnerMixed
  NodeArray<uint16_t> viaUse;        // routed shapes a via's metal here would violate
  NodeArray<int32_t> viaUseOwner;
  NodeArray<uint16_t> cutUse;        // routed cuts a via from z to z+1 here would violate
  NodeArray<int32_t> cutUseOwner;
  NodeArray<int32_t> markerCost;     // cost units from DRC markers and history
  NodeArray<int32_t> routedNet;      // net whose new route uses the node, else -1

  // Only at nodes flagged kAccess, kTerminal or kLanding (a few per net), so
  // kept apart from the per-node arrays; the defaults everywhere else.
  // Net of the access point / terminal at n, else -1.
  int32_t accessNet(int32_t n) const { return sparse(n).net; }
  // PinRef of the access point at n, else -1.
  int32_t accessPin(int32_t n) const { return sparse(n).pin; }
  // At an access point: the planar exits pin access found legal there (AccessDir bits 2 east,
  // 4 west, 8 north, 16 south, of every point of the node); kAnyExit elsewhere.
  uint8_t accessExits(int32_t n) const { return sparse(n).exits; }
  // At a landing right above an access point: the net whose via it is kept for (kOwnerMixed when
  // several), else kOwnerNone.
  int32_t reservedNet(int32_t n) const { return sparse(n).reserved; }
  // The fields above at once: net, pin, reserved and exits (the defaults where none is set).
  struct Sparse {
    int32_t net = -1;
    int32_t pin = -1;
    int32_t reserved = kOwnerNone;
    uint8_t exits = kAnyExit;
  };
  // The search asks at every step: the flag test stays inline, the lookup runs at flagged nodes only.
  const Sparse& sparse(int32_t n) const { return (flags[n] & kSparseFlags) ? lookup(n) : kNoSparse; }
  void setAccess(int32_t n, int32_t net, int32_t pin);  // pin < 0 keeps the pin there
  void addAccessExits(int32_t n, uint8_t exits);
  void reserveLanding(int32_t n, int32_t net);

 private:
  static constexpr uint8_t kSparseFlags = kAccess | kTerminal | kLanding;
  static const Sparse kNoSparse;
  const Sparse& lookup(int32_t n) const;

  Rect box_;                   // DBU
  int nz_ = 0;
  std::vector<Dbu> xs_, ys_;   // DBU, sorted unique
  std::vector<uint8_t> horizontal_;
  std::unordered_map<int32_t, Sparse> sparse_;  // node -> its access fields (set ones only)
};

// Bytes of the per-node arrays above, held by a static_assert in region_grid.cpp.
inline constexpr size_t kGridBytesPerNode = 35;

// Adds `net` to an owner field: none -> net, same net -> net, other -> mixed.
inline void claimOwner(int32_t& owner, int32_t net) {
  if (owner == kOwnerNone) owner = net;
  else if (owner != net) owner = kOwnerMixed;
}

}  // namespace xroute
