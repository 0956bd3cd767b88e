#include "grid/region_grid.hpp"

#include "errors/engine_errors.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace xroute {

namespace {

void sortUnique(std::vector<Dbu>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

void rangeOpen(const std::vector<Dbu>& v, Dbu lo, Dbu hi, int& first, int& last) {
  first = static_cast<int>(std::upper_bound(v.begin(), v.end(), lo) - v.begin());
  last = static_cast<int>(std::lower_bound(v.begin(), v.end(), hi) - v.begin()) - 1;
}

int exactIndex(const std::vector<Dbu>& v, Dbu c) {
  auto it = std::lower_bound(v.begin(), v.end(), c);
  return (it != v.end() && *it == c) ? static_cast<int>(it - v.begin()) : -1;
}

}  // namespace

void regionGridLines(const TrackSet& tracks, const Rect& box, std::vector<Dbu>& xs, std::vector<Dbu>& ys) {
  xs.push_back(box.xlo);
  xs.push_back(box.xhi);
  ys.push_back(box.ylo);
  ys.push_back(box.yhi);
  for (const LayerTracks& lt : tracks.layers) {
    for (Dbu c : tracksIn(lt.pref, lt.horizontal ? box.ylo : box.xlo, lt.horizontal ? box.yhi : box.xhi)) {
      (lt.horizontal ? ys : xs).push_back(c);
    }
    for (Dbu c : tracksIn(lt.cross, lt.horizontal ? box.xlo : box.ylo, lt.horizontal ? box.xhi : box.yhi)) {
      (lt.horizontal ? xs : ys).push_back(c);
    }
  }
  std::erase_if(xs, [&](Dbu x) { return x < box.xlo || x > box.xhi; });
  std::erase_if(ys, [&](Dbu y) { return y < box.ylo || y > box.yhi; });
  sortUnique(xs);
  sortUnique(ys);
}

RegionGrid::RegionGrid(const TrackSet& tracks, const Rect& box, std::vector<Dbu> extraXs, std::vector<Dbu> extraYs)
    : box_(box), nz_(static_cast<int>(tracks.layers.size())), xs_(std::move(extraXs)), ys_(std::move(extraYs)) {
  regionGridLines(tracks, box, xs_, ys_);

  const size_t n = xs_.size() * ys_.size() * static_cast<size_t>(nz_);
  if (n > kMaxRegionNodes) {
    throw SettingError("a region of " + std::to_string(xs_.size()) + " x " + std::to_string(ys_.size()) +
                                " x " + std::to_string(nz_) + " grid nodes exceeds the limit of " +
                                std::to_string(kMaxRegionNodes) + "; use a smaller region size");
  }
  flags.assign(n, 0);
  fixedOwner.assign(n, kOwnerNone);
  viaFixedOwner.assign(n, kOwnerNone);
  wireUse.assign(n, 0);
  wireUseOwner.assign(n, kOwnerNone);
  viaUse.assign(n, 0);
  viaUseOwner.assign(n, kOwnerNone);
  cutUse.assign(n, 0);
  cutUseOwner.assign(n, kOwnerNone);
  markerCost.assign(n, 0);
  routedNet.assign(n, -1);

  horizontal_.resize(nz_);
  for (int z = 0; z < nz_; ++z) {
    const LayerTracks& lt = tracks.layers[z];
    horizontal_[z] = lt.horizontal ? 1 : 0;
    if (lt.horizontal) {
      for (int j = 0; j < ny(); ++j) {
        if (!onTrack(lt.pref, ys_[j])) continue;
        for (int i = 0; i < nx(); ++i) flags[index(i, j, z)] |= kOnTrack;
      }
    } else {
      for (int i = 0; i < nx(); ++i) {
        if (!onTrack(lt.pref, xs_[i])) continue;
        for (int j = 0; j < ny(); ++j) flags[index(i, j, z)] |= kOnTrack;
      }
    }
  }
}

static_assert(bytesPerNode<decltype(RegionGrid::flags), decltype(RegionGrid::fixedOwner),
                           decltype(RegionGrid::viaFixedOwner), decltype(RegionGrid::wireUse),
                           decltype(RegionGrid::wireUseOwner), decltype(RegionGrid::viaUse),
                           decltype(RegionGrid::viaUseOwner), decltype(RegionGrid::cutUse),
                           decltype(RegionGrid::cutUseOwner), decltype(RegionGrid::markerCost),
                           decltype(RegionGrid::routedNet)>() == kGridBytesPerNode,
              "a per-node array was added or changed: update kGridBytesPerNode");

const RegionGrid::Sparse RegionGrid::kNoSparse{};

const RegionGrid::Sparse& RegionGrid::lookup(int32_t n) const {
  const auto it = sparse_.find(n);
  return it == sparse_.end() ? kNoSparse : it->second;
}

void RegionGrid::setAccess(int32_t n, int32_t net, int32_t pin) {
  Sparse& s = sparse_[n];
  s.net = net;
  if (pin >= 0) s.pin = pin;
}

void RegionGrid::addAccessExits(int32_t n, uint8_t exits) {
  Sparse& s = sparse_[n];
  s.exits = s.exits == kAnyExit ? exits : uint8_t(s.exits | exits);
}

void RegionGrid::reserveLanding(int32_t n, int32_t net) { claimOwner(sparse_[n].reserved, net); }

int RegionGrid::xIndex(Dbu x) const { return exactIndex(xs_, x); }
int RegionGrid::yIndex(Dbu y) const { return exactIndex(ys_, y); }
void RegionGrid::xRangeOpen(Dbu lo, Dbu hi, int& first, int& last) const { rangeOpen(xs_, lo, hi, first, last); }
void RegionGrid::yRangeOpen(Dbu lo, Dbu hi, int& first, int& last) const { rangeOpen(ys_, lo, hi, first, last); }

NodeType RegionGrid::nodeType(int32_t n) const {
  if (!flags[n]) return NodeType::NotExist;
  if (flags[n] & kAccess) return NodeType::Access;
  if (fixedOwner[n] == kOwnerMixed) return NodeType::Blockage;
  return NodeType::Normal;
}

}  // namespace xroute
