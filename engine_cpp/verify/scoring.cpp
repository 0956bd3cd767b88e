#include "verify/scoring.hpp"

#include <algorithm>
#include <cstdlib>
#include <utility>
#include <vector>

namespace xroute {

namespace {

// Track lines of one routing layer, by orientation.
struct LayerTracks {
  std::vector<const TrackPattern*> horizontal;  // TRACKS Y: lines y = const
  std::vector<const TrackPattern*> vertical;    // TRACKS X: lines x = const
};

bool onPattern(const TrackPattern& t, Dbu c) {
  if (t.count <= 0 || c < t.start) return false;
  if (t.step <= 0) return c == t.start;
  const int64_t d = int64_t(c) - t.start;
  return d % t.step == 0 && d / t.step < t.count;
}

// 1 = on a line, 0 = off every line, -1 = the layer has no line of that orientation.
int onTrack(const std::vector<const TrackPattern*>& lines, Dbu c) {
  if (lines.empty()) return -1;
  for (const TrackPattern* t : lines)
    if (onPattern(*t, c)) return 1;
  return 0;
}

// Length of [lo, hi] covered by the union of closed intervals.
int64_t coveredLength(Dbu lo, Dbu hi, std::vector<std::pair<Dbu, Dbu>>& cover) {
  std::sort(cover.begin(), cover.end());
  int64_t covered = 0;
  Dbu at = lo;
  for (auto [clo, chi] : cover) {
    clo = std::max(clo, at);
    chi = std::min(chi, hi);
    if (chi <= clo) continue;
    covered += chi - clo;
    at = chi;
  }
  return covered;
}

}  // namespace

GuideTrackFigures computeGuideTrackFigures(const Tech& tech, const Design& design) {
  GuideTrackFigures f;
  std::vector<LayerTracks> tracks(tech.layers.size());
  for (const TrackPattern& t : design.tracks) {
    if (!t.layer.valid() || size_t(*t.layer) >= tracks.size()) continue;
    (t.isX ? tracks[*t.layer].vertical : tracks[*t.layer].horizontal).push_back(&t);
  }
  f.hasGuides = design.hasGuides();
  std::vector<std::pair<Dbu, Dbu>> cover;

  for (size_t n = 0; n < design.nets.size(); ++n) {
    const NetRouting& r = design.nets[n].routing;
    const int32_t g0 = f.hasGuides ? design.guideStart[n] : 0, g1 = f.hasGuides ? design.guideStart[n + 1] : 0;
    for (const RouteWire& w : r.wires) {
      if (w.from == w.to || !w.layer.valid() || size_t(*w.layer) >= tech.layers.size()) continue;
      const Layer& layer = tech.layer(w.layer);
      const bool horizontal = w.from.y == w.to.y;
      const Dbu lo = horizontal ? std::min(w.from.x, w.to.x) : std::min(w.from.y, w.to.y);
      const Dbu hi = horizontal ? std::max(w.from.x, w.to.x) : std::max(w.from.y, w.to.y);
      const Dbu across = horizontal ? w.from.y : w.from.x;
      const int64_t length = int64_t(hi) - lo;
      if ((horizontal && layer.direction == Direction::Vertical) || (!horizontal && layer.direction == Direction::Horizontal))
        f.wrongWayWirelength += length;
      const LayerTracks& lt = tracks[*w.layer];
      if (onTrack(horizontal ? lt.horizontal : lt.vertical, across) == 0) f.offTrackWirelength += length;
      if (f.hasGuides) {
        cover.clear();
        for (int32_t g = g0; g < g1; ++g) {
          if (design.guideLayers[g] != w.layer) continue;
          const Rect& b = design.guideRects[g];
          if (horizontal && b.ylo <= across && across <= b.yhi) cover.push_back({b.xlo, b.xhi});
          if (!horizontal && b.xlo <= across && across <= b.xhi) cover.push_back({b.ylo, b.yhi});
        }
        f.outOfGuideWirelength += length - coveredLength(lo, hi, cover);
      }
    }
    for (const RouteVia& v : r.vias) {
      if (!v.via.valid()) continue;
      const Via& via = design.via(tech, v.via);
      bool offTrack = false, outOfGuide = false;
      for (LayerId metal : {via.bottom, via.top}) {
        if (!metal.valid() || size_t(*metal) >= tech.layers.size()) continue;
        const Layer& layer = tech.layer(metal);
        if (layer.direction == Direction::Horizontal) offTrack = offTrack || onTrack(tracks[*metal].horizontal, v.at.y) == 0;
        if (layer.direction == Direction::Vertical) offTrack = offTrack || onTrack(tracks[*metal].vertical, v.at.x) == 0;
        if (f.hasGuides) {
          bool inside = false;
          for (int32_t g = g0; g < g1 && !inside; ++g)
            inside = design.guideLayers[g] == metal && design.guideRects[g].contains(v.at);
          outOfGuide = outOfGuide || !inside;
        }
      }
      f.offTrackVias += offTrack;
      f.outOfGuideVias += outOfGuide;
    }
  }
  return f;
}

Dbu scorerPitch(const Tech& tech) {
  if (tech.routingLayers.empty()) return 0;
  // Loaded technologies have a positive PITCH on every routing layer (io/validate.cpp).
  return tech.layer(tech.routingLayers[std::min<size_t>(1, tech.routingLayers.size() - 1)]).pitchX;
}

}  // namespace xroute
