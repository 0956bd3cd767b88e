#include "groute/capacity.hpp"

#include <algorithm>

#include "drc/drc.hpp"

namespace xroute {

namespace {

int lineIndex(const std::vector<Dbu>& lines, Dbu v) {
  const int g = static_cast<int>(std::upper_bound(lines.begin(), lines.end(), v) - lines.begin()) - 1;
  return std::clamp(g, 0, static_cast<int>(lines.size()) - 2);
}

// One layer's capacities. "along" is the preferred direction's axis (x for
// a horizontal layer), "across" the other one; tracks sit at `across`
// coordinates and edges join GCells along `along`.
void countLayer(const Tech& tech, const GrGrid& grid, const LayerTracks& lt, const std::vector<DrcShape>& shapes,
                GrLayer& out) {
  const bool h = lt.horizontal;
  const std::vector<Dbu>& acrossLines = h ? grid.gcells.ys : grid.gcells.xs;
  const std::vector<Dbu>& centres = h ? grid.cx : grid.cy;
  const int nAlong = h ? grid.nx() : grid.ny();
  const int nEdges = std::max(0, nAlong - 1);
  const std::vector<Dbu>& tracks = lt.pref;
  const size_t nTracks = tracks.size();
  std::vector<uint8_t> blocked(nTracks * static_cast<size_t>(nEdges), 0);

  const Layer& layer = tech.layer(lt.layer);
  const Dbu grow = lt.wireWidth / 2 + layer.minSpacing();
  for (const DrcShape& s : shapes) {
    if (s.layer != lt.layer) continue;
    const Dbu aLo = (h ? s.rect.xlo : s.rect.ylo) - grow, aHi = (h ? s.rect.xhi : s.rect.yhi) + grow;
    const Dbu cLo = (h ? s.rect.ylo : s.rect.xlo) - grow, cHi = (h ? s.rect.yhi : s.rect.xhi) + grow;
    // Tracks strictly inside (cLo, cHi).
    const size_t t0 = std::upper_bound(tracks.begin(), tracks.end(), cLo) - tracks.begin();
    const size_t t1 = std::lower_bound(tracks.begin(), tracks.end(), cHi) - tracks.begin();
    if (t0 >= t1 || nEdges == 0) continue;
    // Edges e with (centres[e], centres[e+1]) overlapping (aLo, aHi).
    int e0 = static_cast<int>(std::upper_bound(centres.begin(), centres.end(), aLo) - centres.begin()) - 1;
    int e1 = static_cast<int>(std::lower_bound(centres.begin(), centres.end(), aHi) - centres.begin()) - 1;
    e0 = std::max(e0, 0);
    e1 = std::min(e1, nEdges - 1);
    for (size_t t = t0; t < t1; ++t) {
      for (int e = e0; e <= e1; ++e) blocked[t * nEdges + e] = 1;
    }
  }

  const size_t cells = static_cast<size_t>(grid.nx()) * grid.ny();
  out.capacity.assign(cells, 0);
  out.tracks.assign(cells, 0);
  for (size_t t = 0; t < nTracks; ++t) {
    if (tracks[t] < acrossLines.front() || tracks[t] > acrossLines.back()) continue;
    const int row = lineIndex(acrossLines, tracks[t]);
    for (int e = 0; e < nEdges; ++e) {
      const int32_t at = h ? grid.cell(e, row) : grid.cell(row, e);
      ++out.tracks[at];
      if (!blocked[t * nEdges + e]) ++out.capacity[at];
    }
  }
}

}  // namespace

int GrGrid::gcellX(Dbu x) const { return lineIndex(gcells.xs, x); }
int GrGrid::gcellY(Dbu y) const { return lineIndex(gcells.ys, y); }

GrGrid buildGrGrid(const Tech& tech, const Design& design, const TrackSet& tracks) {
  GrGrid grid;
  grid.gcells = makeGCellGrid(design, tracks);
  for (int x = 0; x < grid.nx(); ++x) grid.cx.push_back((grid.gcells.xs[x] + grid.gcells.xs[x + 1]) / 2);
  for (int y = 0; y < grid.ny(); ++y) grid.cy.push_back((grid.gcells.ys[y] + grid.gcells.ys[y + 1]) / 2);

  std::vector<DrcShape> fixed;
  for (DrcShape& s : collectDesignShapes(tech, design)) {
    if (isFixedOrigin(s.origin)) fixed.push_back(s);
  }
  grid.layers.resize(tracks.layers.size());
  for (size_t z = 0; z < tracks.layers.size(); ++z) {
    const LayerTracks& lt = tracks.layers[z];
    GrLayer& gl = grid.layers[z];
    gl.layer = lt.layer;
    gl.horizontal = lt.horizontal;
    countLayer(tech, grid, lt, fixed, gl);
  }
  return grid;
}

}  // namespace xroute
