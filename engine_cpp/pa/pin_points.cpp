// Choosing the access points of one pin.
//
// Candidates are visited best first (cost, distance to the pin's centre,
// higher z, x, y). A candidate on a layer with vias up is legal with the
// first via whose cuts lie in the pin's metal and that adds no marker, vias
// tried DEFAULT first, then by their bottom metal's area outside the pin,
// then in LEF order; otherwise it may still be legal with planar exits
// only, at cost + kCostPlanarOnly (after every via point). On the top layer
// planar exits are the only kind.
//
// On-track first: once a legal via point with both coordinates on track
// (cost kCostOnTrack) is found, the scan ends with the on-track candidates:
// the pin offers only on-track via points (the contest scorer counts every
// via off its layers' tracks, and the router takes whichever offered point
// is cheapest to reach). Off-track via points, and planar-only points, are
// offered only by pins where no on-track via point is legal.
//
// Spreading: a point's spread key is the coordinate of the wire leaving it
// (x when that wire is vertical, else y; with the axis, not the layer, so
// that the layers of a stacked pin do not count as spread). The chosen points are first the
// best legal point of each distinct key, then the best of the rest, at most
// maxPoints, returned best first. The scan stops once maxPoints distinct
// keys are known: every later candidate sorts after the points found, so the
// choice is the same as with a full scan. Planar-only points (cost +
// kCostPlanarOnly) are looked for only after every candidate failed to give
// enough via points.
//
// Without any legal point the pin gets one fallback point at the centre of
// its largest rect, snapped to the nearest on-track coordinates inside the
// rect, cost kCostFallback, exiting up through the layer's first via.
#include <algorithm>
#include <cstdlib>
#include <tuple>

#include "pa/pa_internal.hpp"

namespace xroute::pa {

namespace {

constexpr AccessDir kPlanarDirs[4] = {kAccessEast, kAccessWest, kAccessNorth, kAccessSouth};
constexpr uint8_t kAllPlanar = kAccessEast | kAccessWest | kAccessNorth | kAccessSouth;

struct Legal {
  AccessPoint point;
  int64_t dist = 0;            // doubled DBU, to the pin's centre
  int64_t spread = 0;          // (axis, wire coordinate) packed
  bool planarKnown = false;    // planar exits already checked
};

int64_t spreadKey(const LayerAccess& la, Point at) {
  return la.spreadOnX ? (int64_t(1) << 32) | uint32_t(at.x) : int64_t(uint32_t(at.y));
}

uint8_t planarDirs(const AccessChecker& checker, const LayerAccess& la, Point at, int32_t net) {
  uint8_t dirs = 0;
  for (AccessDir d : kPlanarDirs)
    if (checker.stubLegal(la, at, d, net)) dirs |= d;
  return dirs;
}

// The on-track coordinate in [lo, hi] nearest to the middle, else the middle.
Dbu snapped(const std::vector<Dbu>& tracks, Dbu lo, Dbu hi) {
  const Dbu mid = Dbu((int64_t(lo) + hi) / 2);
  auto it = std::lower_bound(tracks.begin(), tracks.end(), mid);
  Dbu best = mid;
  int64_t bestD = -1;
  for (auto c : {it, it == tracks.begin() ? tracks.end() : it - 1}) {
    if (c == tracks.end() || *c < lo || *c > hi) continue;
    const int64_t d = std::llabs(int64_t(*c) - mid);
    if (bestD < 0 || d < bestD || (d == bestD && *c < best)) best = *c, bestD = d;
  }
  return best;
}

AccessPoint fallbackPoint(const std::vector<LayerAccess>& layers, const std::vector<PinRect>& pin) {
  const PinRect* big = &pin.front();
  for (const PinRect& r : pin)
    if (r.rect.area() > big->rect.area()) big = &r;
  const LayerAccess& la = layers[big->z];
  AccessPoint p;
  p.at = {snapped(la.xTracks, big->rect.xlo, big->rect.xhi), snapped(la.yTracks, big->rect.ylo, big->rect.yhi)};
  p.z = big->z;
  p.cost = kCostFallback;
  if (la.hasUp()) {
    p.dirs = kAccessUp;
    p.upVia = la.upVias.front();
  } else {
    p.dirs = kAllPlanar;
  }
  return p;
}

// The layer's vias up: DEFAULT ones first, each group ordered by how much of
// their bottom metal at `at` lies outside the pin (least first: a via inside
// the pin makes no new line ends), then LEF order.
std::vector<ViaId> viasByFit(const Tech& tech, const LayerAccess& la, const std::vector<PinRect>& pin, int32_t z,
                             Point at) {
  struct Ranked {
    bool nonDefault;
    Area outside;  // DBU^2
    ViaId via;
  };
  std::vector<Ranked> order;
  order.reserve(la.upVias.size());
  for (ViaId v : la.upVias) {
    const Via& via = tech.vias[*v];
    Area outside = 0;
    for (const ViaShape& s : via.shapes)
      if (s.layer == via.bottom) outside += uncoveredArea(pin, z, s.rect.translated(at));
    order.push_back({!via.isDefault, outside, v});
  }
  std::stable_sort(order.begin(), order.end(), [](const Ranked& a, const Ranked& b) {
    return std::tie(a.nonDefault, a.outside) < std::tie(b.nonDefault, b.outside);
  });
  std::vector<ViaId> out;
  out.reserve(order.size());
  for (const Ranked& r : order) out.push_back(r.via);
  return out;
}

auto legalKey(const Legal& l) {
  return std::make_tuple(l.point.cost, l.dist, -l.point.z, l.point.at.x, l.point.at.y);
}

// A legal-point shell for candidate c (no exits yet).
Legal shellOf(const LayerAccess& la, const Candidate& c) {
  Legal l;
  l.point.at = c.at;
  l.point.z = c.z;
  l.point.cost = c.cost;
  l.dist = c.dist;
  l.spread = spreadKey(la, c.at);
  return l;
}

// The spread choice (see the top of the file), best first; sorts `legal`.
std::vector<const Legal*> spreadChoice(std::vector<Legal>& legal, int maxPoints) {
  std::stable_sort(legal.begin(), legal.end(), [](const Legal& a, const Legal& b) { return legalKey(a) < legalKey(b); });
  std::vector<const Legal*> chosen;
  std::vector<int64_t> usedKeys;
  for (const Legal& l : legal) {
    if (int(chosen.size()) >= maxPoints) break;
    if (std::find(usedKeys.begin(), usedKeys.end(), l.spread) != usedKeys.end()) continue;
    usedKeys.push_back(l.spread);
    chosen.push_back(&l);
  }
  for (const Legal& l : legal) {
    if (int(chosen.size()) >= maxPoints) break;
    if (std::find(chosen.begin(), chosen.end(), &l) == chosen.end()) chosen.push_back(&l);
  }
  std::sort(chosen.begin(), chosen.end(), [](const Legal* a, const Legal* b) { return legalKey(*a) < legalKey(*b); });
  return chosen;
}

}  // namespace

PinPointsResult choosePinPoints(const Tech& tech, const std::vector<LayerAccess>& layers,
                                const AccessChecker& checker, const std::vector<PinRect>& pin, int32_t net,
                                int maxPoints) {
  PinPointsResult result;
  if (pin.empty()) return result;
  maxPoints = std::max(maxPoints, 1);

  // Phase A: via points (and planar points on layers without vias up), in
  // candidate order, until maxPoints distinct spread keys are known.
  const std::vector<Candidate> cands = pinCandidates(layers, pin);
  std::vector<Legal> legal;
  std::vector<int64_t> keys;
  auto addKey = [&](int64_t k) {
    if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    return int(keys.size()) >= maxPoints;
  };
  std::vector<size_t> noVia;  // candidates on layers with vias up where no via is legal
  bool enough = false;
  bool onTrackVia = false;  // a legal via point with both coordinates on track was found
  for (size_t i = 0; i < cands.size() && !enough; ++i) {
    const Candidate& c = cands[i];
    if (onTrackVia && c.cost > kCostOnTrack) {
      enough = true;  // on-track via points only: no off-track via where an on-track one is legal
      break;
    }
    const LayerAccess& la = layers[c.z];
    Legal l = shellOf(la, c);
    if (la.hasUp()) {
      for (ViaId v : viasByFit(tech, la, pin, c.z, c.at)) {
        if (checker.viaLegal(tech.vias[*v], c.at, net, pin, c.z)) {
          l.point.dirs = kAccessUp;
          l.point.upVia = v;
          break;
        }
      }
      if (l.point.dirs == 0) {
        noVia.push_back(i);
        continue;
      }
      onTrackVia = onTrackVia || c.cost == kCostOnTrack;
    } else {
      l.point.dirs = planarDirs(checker, la, c.at, net);
      l.planarKnown = true;
      if (l.point.dirs == 0) continue;
    }
    legal.push_back(l);
    enough = addKey(l.spread);
  }
  // Phase B, only when phase A saw every candidate without enough keys:
  // planar-only points, which sort after every phase A point (cost +
  // kCostPlanarOnly), so the choice is the same as one scan of everything.
  for (size_t k = 0; k < noVia.size() && !enough; ++k) {
    const Candidate& c = cands[noVia[k]];
    const LayerAccess& la = layers[c.z];
    Legal l = shellOf(la, c);
    l.point.dirs = planarDirs(checker, la, c.at, net);
    l.point.cost = c.cost + kCostPlanarOnly;
    l.planarKnown = true;
    if (l.point.dirs == 0) continue;
    legal.push_back(l);
    enough = addKey(l.spread);
  }

  if (legal.empty()) {
    result.points.push_back(fallbackPoint(layers, pin));
    result.fallback = true;
    return result;
  }

  for (const Legal* l : spreadChoice(legal, maxPoints)) {
    AccessPoint p = l->point;
    if (!l->planarKnown) p.dirs |= planarDirs(checker, layers[p.z], p.at, net);
    result.points.push_back(p);
  }
  return result;
}

}  // namespace xroute::pa
