// Legality of an access via or a planar exit stub, with the design-rule
// checker (drc/drc.hpp).
//
// For a candidate (the via's shapes, or a stub), the local context is every
// context shape within R + 1 of the candidate's bounding box, R the largest
// interaction range (drc::interactionRange) of the candidate's layers: a
// shape further away cannot be in a marker with the candidate (the rules
// that look at a conductor's other edges, end of line and corner spacing,
// look at edges the candidate changes, near it). The local context is checked alone (cached while it stays the
// same) and with the candidate; the candidate is illegal when the second
// check has a marker the first does not (a candidate shape touching a
// context shape of another net on its layer is a Short: decided without the
// checker). Markers are not merged (so that a
// new marker cannot hide inside a merged old one), and min area is ignored:
// an access via or stub is the start of a wire that the router extends.
#include <algorithm>
#include <tuple>

#include "drc/layer_shapes.hpp"
#include "pa/pa_internal.hpp"

namespace xroute::pa {

namespace {

DrcOptions rawOptions() {
  DrcOptions o;
  o.skipFixedPairs = false;
  o.mergeMarkers = false;
  return o;
}

auto markerKey(const Marker& m) {
  return std::make_tuple(m.type, *m.layer, m.box.xlo, m.box.ylo, m.box.xhi, m.box.yhi, m.net1, m.net2);
}

bool markerLess(const Marker& a, const Marker& b) { return markerKey(a) < markerKey(b); }

bool inside(const Rect& r, const Rect& outer) {
  return r.xlo >= outer.xlo && r.ylo >= outer.ylo && r.xhi <= outer.xhi && r.yhi <= outer.yhi;
}

std::vector<Rect> rectsOf(const std::vector<DrcShape>& shapes) {
  std::vector<Rect> out;
  out.reserve(shapes.size());
  for (const DrcShape& s : shapes) out.push_back(s.rect);
  return out;
}

bool isCheckedLayer(const Tech& tech, LayerId id) {
  const LayerType t = tech.layer(id).type;
  return t == LayerType::Routing || t == LayerType::Cut;
}

}  // namespace

Dbu keepInMargin(const Layer& layer) {
  Dbu m = layer.minSpacing();
  for (const EolRule& r : layer.eolRules) m = std::max(m, r.space);
  return m;
}

AccessChecker::AccessChecker(const Tech& tech, std::vector<DrcShape> context, Rect die, Rect cell)
    : tech_(tech), context_(std::move(context)), index_(rectsOf(context_)), die_(die), cell_(cell) {
  range_.reserve(tech.layers.size());
  keepIn_.reserve(tech.layers.size());
  for (const Layer& l : tech.layers) {
    range_.push_back(drc::interactionRange(l));
    keepIn_.push_back(keepInMargin(l));
  }
}

bool AccessChecker::addsMarker(const std::vector<DrcShape>& added) const {
  // A candidate shape touching a context shape of another net on its layer
  // is a short: no need to run the checker.
  for (const DrcShape& s : added) {
    bool shorted = false;
    index_.query(s.rect, [&](int32_t i) {
      const DrcShape& c = context_[i];
      shorted = shorted || (c.layer == s.layer && (c.net < 0 || c.net != s.net) && c.rect.xlo < c.rect.xhi &&
                            c.rect.ylo < c.rect.yhi);
    });
    if (shorted && isCheckedLayer(tech_, s.layer) && s.rect.xlo < s.rect.xhi && s.rect.ylo < s.rect.yhi) return true;
  }
  ++checks_;
  Rect box = added.front().rect;
  Dbu range = 0;
  for (const DrcShape& s : added) {
    box.expandToInclude(s.rect);
    range = std::max(range, range_[*s.layer]);
  }
  const std::vector<int32_t> ids = index_.query(drc::expanded(box, range + 1));

  std::vector<DrcShape> shapes;
  shapes.reserve(ids.size() + added.size());
  for (int32_t i : ids) shapes.push_back(context_[i]);
  if (!haveLast_ || ids != lastIds_) {
    lastBaseline_ = checkShapes(tech_, shapes, rawOptions());
    std::erase_if(lastBaseline_, [](const Marker& m) { return m.type == MarkerType::MinArea; });
    std::sort(lastBaseline_.begin(), lastBaseline_.end(), markerLess);
    lastIds_ = ids;
    haveLast_ = true;
  }
  shapes.insert(shapes.end(), added.begin(), added.end());
  for (const Marker& m : checkShapes(tech_, std::move(shapes), rawOptions())) {
    if (m.type == MarkerType::MinArea) continue;
    if (!std::binary_search(lastBaseline_.begin(), lastBaseline_.end(), m, markerLess)) return true;
  }
  return false;
}

bool AccessChecker::viaLegal(const Via& via, Point at, int32_t net, const std::vector<PinRect>& metal,
                             int32_t z) const {
  std::vector<DrcShape> added;
  bool covered = true;
  for (const ViaShape& s : via.shapes) {
    const Rect r = s.rect.translated(at);
    if (s.layer == via.cut && !inside(r, die_)) return false;
    if (s.layer == via.cut) covered = covered && coveredBy(metal, z, r);
    added.push_back({s.layer, r, net, ShapeOrigin::Via});
  }
  if (added.empty()) return false;
  if (!covered) {
    if (cell_.xlo >= cell_.xhi || cell_.ylo >= cell_.yhi) return false;
    const Dbu m = keepIn_[*via.bottom];
    const Rect keep{cell_.xlo + m, cell_.ylo + m, cell_.xhi - m, cell_.yhi - m};
    for (const DrcShape& s : added)
      if (s.layer == via.bottom && !inside(s.rect, keep)) return false;
  }
  return !addsMarker(added);
}

bool AccessChecker::stubLegal(const LayerAccess& layer, Point at, AccessDir dir, int32_t net) const {
  const Dbu w = layer.stubWidth, h = w / 2, len = layer.stubLength;
  Rect r;
  switch (dir) {
    case kAccessEast: r = {at.x - h, at.y - h, at.x + len, at.y - h + w}; break;
    case kAccessWest: r = {at.x - len, at.y - h, at.x - h + w, at.y - h + w}; break;
    case kAccessNorth: r = {at.x - h, at.y - h, at.x - h + w, at.y + len}; break;
    case kAccessSouth: r = {at.x - h, at.y - len, at.x - h + w, at.y - h + w}; break;
    default: return false;
  }
  if (!inside(r, die_)) return false;
  return !addsMarker({DrcShape{layer.layer, r, net, ShapeOrigin::Wire}});
}

}  // namespace xroute::pa
