// The check of a whole design, band by band when it is large, and the shapes that the markers of
// one zone of a design depend on (the iteration loop's partial checks read them too).
//
// A large design is not checked from one list of all its shapes: the shapes, their copies by layer
// and each layer's index and conductors would hold every net's metal at once. It is cut into
// horizontal bands across the whole die, about DrcOptions::bandShapes shapes each, and each band is
// judged as a CheckZone: from the shapes near it, every conductor near it whole, keeping the markers
// whose box touches it. A marker depends only on the shapes within reach of its box, and a
// MinArea one on its own conductor, so the bands together give the whole check's markers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "drc/drc.hpp"
#include "geom/box_index.hpp"

namespace xroute {

// A design's fixed shapes (collectFixedShapes) as the checks of part of a design read them. The
// owner keeps the vectors; `conductor` is filled on first use when it is empty.
struct FixedShapeView {
  const std::vector<DrcShape>* shapes = nullptr;
  const BoxIndex* index = nullptr;                 // over the shapes' rects, ids = indices
  const std::vector<int32_t>* netStart = nullptr;  // regular net n's shapes: byNet[netStart[n] .. netStart[n + 1])
  const std::vector<int32_t>* byNet = nullptr;
  std::vector<int32_t>* conductor = nullptr;       // fixedConductorIds over the shapes
};

// Regular net n's shapes among `shapes` (their indices, ascending): byNet[start[n] .. start[n + 1]).
void shapesByNet(const std::vector<DrcShape>& shapes, size_t nets, std::vector<int32_t>& start,
                 std::vector<int32_t>& byNet);

// Owns what a FixedShapeView shows: fixed shapes (some of a design's, in its order) with their
// conductor ids (fixedConductorIds over all of the design's), indexed.
class FixedShapeSet {
 public:
  FixedShapeSet(std::vector<DrcShape> shapes, std::vector<int32_t> conductor, size_t nets);
  FixedShapeView view() {
    return FixedShapeView{&shapes_, &index_, &netStart_, &byNet_, &conductor_};
  }

 private:
  std::vector<DrcShape> shapes_;
  BoxIndex index_;
  std::vector<int32_t> netStart_, byNet_, conductor_;
};

// The conductors of one net's rects on one layer, as the checker joins them (sharesSegment): a
// root per rect (the same root, the same conductor).
std::vector<int32_t> sameNetConductors(const std::vector<Rect>& rects);

// Per fixed shape, an id shared by the shapes of one conductor on its layer (same-net shapes joined
// as the checker joins them; an obstruction alone; -1 for a shape on no checked layer or of no
// area): a shape's index, unique across layers. One net's shapes of one layer are held at a time.
std::vector<int32_t> fixedConductorIds(const Tech& tech, const std::vector<DrcShape>& shapes);

// The shapes the zone's markers depend on, on each layer with a zone: every shape within twice the
// reach of a zone cell, with the whole conductor it belongs to (routing and pins), and on a layer
// where a net changed (CheckZone::addNet), all of that net's metal; the fixed shapes there and
// under that routing, each linked to its conductor of fixed shapes (links: one per shape, -1 for
// routing; a special net's rail that leaves the zone stays one conductor). `routedNear`: at least
// every regular net with routing within twice the reach of a zone cell (more is harmless).
std::vector<DrcShape> zoneShapes(const Tech& tech, const Design& design, const FixedShapeView& fixed,
                                 const CheckZone& zone, std::vector<int32_t> routedNear, std::vector<int32_t>& links);

// What a design check looked at.
struct DesignCheckStats {
  int64_t shapes = 0;  // shapes checked, summed over the bands (a shape near two bands counts twice)
  std::vector<Dbu> cuts;  // with bands: their rows, bands + 1 y values ascending; empty: at once
};

// checkShapesUnmerged over collectDesignShapes, band by band when the design has more than
// options.bandShapes shapes (and fixed pairs are skipped, and no window is set): the same markers,
// each once. `fixed`: the design's fixed shapes when the caller has them (else they are collected
// when bands are needed). netNames as collectDesignShapes gives them.
std::vector<Marker> checkDesignUnmerged(const Tech& tech, const Design& design, const DrcOptions& options,
                                        const FixedShapeView* fixed = nullptr,
                                        std::vector<std::string>* netNames = nullptr,
                                        DesignCheckStats* stats = nullptr);

// checkShapes(collectDesignShapes(...)): every marker of the design, merged and sorted.
std::vector<Marker> checkDesign(const Tech& tech, const Design& design, const DrcOptions& options,
                                std::vector<std::string>* netNames = nullptr, DesignCheckStats* stats = nullptr);

}  // namespace xroute
