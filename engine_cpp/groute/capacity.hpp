// The global router's 3D GCell grid and its capacities. A GCell edge joins
// two neighbouring GCells of one layer along the layer's preferred
// direction; its capacity is the number of the layer's preferred tracks
// inside the GCell row (horizontal layers) or column (vertical layers) that
// no fixed shape blocks between the two GCell centres.
#pragma once

#include <cstdint>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "grid/gcell_grid.hpp"
#include "grid/tracks.hpp"

namespace xroute {

struct GrLayer {
  LayerId layer;
  bool horizontal = true;   // preferred direction
  // Capacity per edge, in tracks. Horizontal layer: edge (x,y)-(x+1,y) at
  // index y*nx + x (x < nx-1); vertical layer: edge (x,y)-(x,y+1) at index
  // y*nx + x (y < ny-1). Other entries are 0.
  std::vector<int32_t> capacity;
  std::vector<int32_t> tracks;    // the same edge's track count before blocking
};

struct GrGrid {
  GCellGrid gcells;              // DBU lines, shared with the detailed router's derivation
  std::vector<Dbu> cx, cy;       // DBU, GCell centres
  std::vector<GrLayer> layers;   // by routing index (z)
  int nx() const { return gcells.nx(); }
  int ny() const { return gcells.ny(); }
  int nz() const { return static_cast<int>(layers.size()); }
  int32_t cell(int x, int y) const { return y * nx() + x; }
  Rect box(int x, int y) const { return {gcells.xs[x], gcells.ys[y], gcells.xs[x + 1], gcells.ys[y + 1]}; }
  int gcellX(Dbu x) const;  // GCell column holding x (clamped)
  int gcellY(Dbu y) const;  // GCell row holding y (clamped)
};

// Builds the grid (DEF GCELLGRID, else the regular grid grid/gcell_grid.cpp
// derives: guide pitch, else 15 pitches) and counts capacities: a track is
// blocked for an edge when a pin, obstruction, layer blockage or special-net
// shape, grown by half the wire width plus the layer's minimum spacing,
// overlaps the track's piece between the two GCell centres (open intervals:
// touching does not block).
GrGrid buildGrGrid(const Tech& tech, const Design& design, const TrackSet& tracks);

}  // namespace xroute
