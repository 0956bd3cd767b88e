#include "region/candidate.hpp"

namespace xroute {

std::vector<int32_t> featureRows(const std::vector<NetCandidate>& candidates) {
  std::vector<int32_t> flat;
  flat.reserve(candidates.size() * kFeatureCount);
  for (const NetCandidate& k : candidates) {
    const int32_t row[kFeatureCount] = {k.net,         k.pins,        k.terminals,   k.accessPoints, k.bbox.xlo,
                                        k.bbox.ylo,    k.bbox.xhi,    k.bbox.yhi,    k.netPins,      k.crossings,
                                        k.guide.xlo,   k.guide.ylo,   k.guide.xhi,   k.guide.yhi,    k.routedNearby};
    flat.insert(flat.end(), row, row + kFeatureCount);
  }
  return flat;
}

}  // namespace xroute
