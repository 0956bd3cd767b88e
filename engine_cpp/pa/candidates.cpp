// Candidate access points of one pin. On each of the pin's rects, the x and
// y coordinates are chosen independently and combined:
//   on-track      a track of LayerAccess::xTracks / yTracks      cost 0
//   half-track    midway between two neighbouring tracks          cost 1
//   centre        the rect's centre                               cost 2
//   enclosed edge where the first up via's cut just fits inside
//                 the rect at its low or high edge                cost 3
// (at most kPerCategory of each on-track / half-track kind per axis, those
// nearest the rect's centre). A point's cost is the sum of its two
// coordinate costs; a coordinate found by two rules keeps the cheaper one.
// Order: cost, distance to the pin's centre, higher layer first (a pin
// stacked on several layers is best reached on its top one), x, y.
#include <algorithm>
#include <cstdlib>
#include <tuple>

#include "pa/pa_internal.hpp"

namespace xroute::pa {

namespace {

constexpr size_t kPerCategory = 8;

struct AxisCoord {
  Dbu v = 0;         // DBU
  int32_t cost = 0;
};

// Keeps the `kPerCategory` values nearest to the doubled centre c2.
void keepNearest(std::vector<Dbu>& vs, int64_t c2) {
  if (vs.size() <= kPerCategory) return;
  std::sort(vs.begin(), vs.end(), [&](Dbu a, Dbu b) {
    const int64_t da = std::llabs(2 * int64_t(a) - c2), db = std::llabs(2 * int64_t(b) - c2);
    return da != db ? da < db : a < b;
  });
  vs.resize(kPerCategory);
}

// Coordinates in [lo, hi] along one axis. cutLo / cutHi: the cut's extent
// relative to the via origin (cutLo <= 0 <= cutHi usually); hasCut false
// when the layer has no via up.
std::vector<AxisCoord> axisCoords(const std::vector<Dbu>& tracks, Dbu lo, Dbu hi, bool hasCut, Dbu cutLo, Dbu cutHi) {
  const int64_t c2 = int64_t(lo) + hi;
  std::vector<AxisCoord> out;

  auto first = std::lower_bound(tracks.begin(), tracks.end(), lo);
  auto last = std::upper_bound(tracks.begin(), tracks.end(), hi);
  std::vector<Dbu> on(first, last);
  keepNearest(on, c2);
  for (Dbu v : on) out.push_back({v, kCostOnTrack});

  std::vector<Dbu> half;
  auto from = first == tracks.begin() ? first : first - 1;
  for (auto it = from; it != tracks.end() && it + 1 != tracks.end() && it < last; ++it) {
    const Dbu mid = Dbu(*it + (int64_t(it[1]) - *it) / 2);
    if (mid >= lo && mid <= hi) half.push_back(mid);
  }
  keepNearest(half, c2);
  for (Dbu v : half) out.push_back({v, kCostHalfTrack});

  out.push_back({Dbu(c2 >> 1), kCostCentre});
  if (hasCut && int64_t(hi) - lo >= int64_t(cutHi) - cutLo) {
    out.push_back({Dbu(lo - cutLo), kCostEnclosedEdge});
    out.push_back({Dbu(hi - cutHi), kCostEnclosedEdge});
  }

  std::sort(out.begin(), out.end(), [](const AxisCoord& a, const AxisCoord& b) {
    return a.v != b.v ? a.v < b.v : a.cost < b.cost;
  });
  out.erase(std::unique(out.begin(), out.end(), [](const AxisCoord& a, const AxisCoord& b) { return a.v == b.v; }),
            out.end());
  return out;
}

}  // namespace

Point pinCentre2(const std::vector<PinRect>& pin) {
  if (pin.empty()) return {};
  Rect box = pin.front().rect;
  for (const PinRect& r : pin) box.expandToInclude(r.rect);
  return {box.xlo + box.xhi, box.ylo + box.yhi};
}

std::vector<Candidate> pinCandidates(const std::vector<LayerAccess>& layers, const std::vector<PinRect>& pin) {
  std::vector<Candidate> out;
  const Point c2 = pinCentre2(pin);
  for (const PinRect& pr : pin) {
    const LayerAccess& la = layers[pr.z];
    const Rect& r = pr.rect;
    const bool hasCut = la.hasUp();
    const std::vector<AxisCoord> xs = axisCoords(la.xTracks, r.xlo, r.xhi, hasCut, la.cutBox.xlo, la.cutBox.xhi);
    const std::vector<AxisCoord> ys = axisCoords(la.yTracks, r.ylo, r.yhi, hasCut, la.cutBox.ylo, la.cutBox.yhi);
    for (const AxisCoord& x : xs) {
      for (const AxisCoord& y : ys) {
        Candidate c;
        c.at = {x.v, y.v};
        c.z = pr.z;
        c.cost = x.cost + y.cost;
        c.dist = std::llabs(2 * int64_t(x.v) - c2.x) + std::llabs(2 * int64_t(y.v) - c2.y);
        out.push_back(c);
      }
    }
  }
  // One candidate per (z, x, y): the cheapest.
  std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.z, a.at.x, a.at.y, a.cost) < std::tie(b.z, b.at.x, b.at.y, b.cost);
  });
  out.erase(std::unique(out.begin(), out.end(),
                        [](const Candidate& a, const Candidate& b) { return a.z == b.z && a.at == b.at; }),
            out.end());
  std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
    return std::make_tuple(a.cost, a.dist, -a.z, a.at.x, a.at.y) < std::make_tuple(b.cost, b.dist, -b.z, b.at.x, b.at.y);
  });
  return out;
}

}  // namespace xroute::pa
