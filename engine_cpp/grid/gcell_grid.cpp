#include "grid/gcell_grid.hpp"

#include <algorithm>

namespace xroute {

namespace {

// The most common guide extent along an axis: the global router's GCell
// pitch (most guides are one GCell wide), or 0 without guides.
Dbu guidePitch(const Design& design, bool isX, Dbu& origin) {
  std::vector<Dbu> sizes;
  for (const Rect& g : design.guideRects) {
    const Dbu s = isX ? g.width() : g.height();
    if (s > 0) sizes.push_back(s);
  }
  if (sizes.empty()) return 0;
  std::sort(sizes.begin(), sizes.end());
  Dbu best = sizes.front();
  size_t bestCount = 0;
  for (size_t i = 0; i < sizes.size();) {
    size_t j = i;
    while (j < sizes.size() && sizes[j] == sizes[i]) ++j;
    if (j - i > bestCount) {
      bestCount = j - i;
      best = sizes[i];
    }
    i = j;
  }
  // Grid origin: the low edge of a guide of exactly that size.
  origin = 0;
  for (const Rect& g : design.guideRects) {
    if ((isX ? g.width() : g.height()) == best) {
      origin = isX ? g.xlo : g.ylo;
      break;
    }
  }
  return best;
}

std::vector<Dbu> derivedLines(const Design& design, const TrackSet& tracks, bool isX) {
  const Dbu lo = isX ? design.dieArea.xlo : design.dieArea.ylo;
  const Dbu hi = isX ? design.dieArea.xhi : design.dieArea.yhi;
  std::vector<Dbu> lines = gcellLines(design, isX);
  if (lines.size() < 2) {
    lines.clear();
    Dbu origin = 0;
    Dbu step = guidePitch(design, isX, origin);
    if (step <= 0) {
      // No grid given: 15 pitches of the lowest layer whose tracks run across this axis.
      for (const LayerTracks& lt : tracks.layers) {
        if (lt.horizontal != isX && lt.pitch > 0) {
          step = lt.pitch * 15;
          break;
        }
      }
      origin = lo;
    }
    if (step <= 0) step = std::max<Dbu>(1, (hi - lo) / 16);
    Dbu first = origin - ((origin - lo) / step) * step;  // first line at or after lo
    if (first < lo) first += step;
    for (Dbu v = first; v < hi; v += step) lines.push_back(v);
    // A last cell shorter than half a pitch joins its neighbour.
    if (!lines.empty() && hi - lines.back() < step / 2 && lines.back() > lo) lines.pop_back();
  }
  lines.push_back(lo);
  lines.push_back(hi);
  std::erase_if(lines, [&](Dbu v) { return v < lo || v > hi; });
  std::sort(lines.begin(), lines.end());
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  return lines;
}

}  // namespace

GCellGrid makeGCellGrid(const Design& design, const TrackSet& tracks) {
  return GCellGrid{derivedLines(design, tracks, true), derivedLines(design, tracks, false)};
}

}  // namespace xroute
