// The iteration loop's design-rule check: the whole design after the first iteration, and after a
// later one only what the nets it rerouted changed, giving the markers a whole check would.
//
// An iteration changes the routing of the nets its regions rip up and nothing else. Before a net's
// routing changes, remember() keeps its shapes; update() compares them with the net's shapes now.
// Where they differ (on each layer, the conductors with a changed rect, widened by the layer's
// CheckZone::reach) the rules judge again, from the shapes near that zone: the changed net on that
// layer and every conductor with metal near the zone, whole, and the fixed shapes there or under
// that routing, each fixed shape joined to the rest of its input conductor. The last check's
// markers outside the zone stay.
// A marker depends only on shapes within reach of its box, or for MinArea on its own conductor, so
// the result is the whole check's; tests compare the two on every iteration of routed designs.
// On a design whose whole check ran in bands (drc/design_check.hpp), the zone is judged in the same
// bands, one at a time.
#pragma once

#include <cstdint>
#include <vector>

#include "drc/design_check.hpp"
#include "drc/drc.hpp"
#include "region/route_context.hpp"

namespace xroute {

class IncrementalCheck {
 public:
  IncrementalCheck(const RouteContext& ctx, DrcOptions options);

  // Every marker of the design, by a whole check; the next update() starts from them.
  std::vector<Marker> full();
  // Net n's routing is about to change (once is enough until the next check).
  void remember(int32_t net);
  bool remembered(int32_t net) const { return size_t(net) < kept_.size() && kept_[net]; }
  // Every marker of the design, judging again near what changed in the remembered nets since the
  // last check; by a whole check when more than maxShare of the nets changed. Requires an earlier full().
  std::vector<Marker> update(double maxShare);
  // How many shapes the last check looked at.
  int64_t lastShapes() const { return lastShapes_; }

 private:
  void forget();  // no net remembered
  void changeZone(CheckZone& zone);
  FixedShapeView fixedView();  // ctx_'s fixed shapes, with this check's lists of them
  // The zone's markers from the shapes near it (unmerged); adds the shapes looked at to lastShapes_.
  std::vector<Marker> checkZone(const CheckZone& zone);

  const RouteContext& ctx_;
  DrcOptions options_;
  Rect area_;                            // DBU: the die and every fixed shape
  std::vector<int32_t> fixedConductor_;  // per ctx_.fixedShapes: fixedConductorIds over them (when first needed)
  std::vector<int32_t> netFixedStart_;   // regular net n's pin shapes: netFixed_[start[n] .. start[n+1])
  std::vector<int32_t> netFixed_;        // indices into ctx_.fixedShapes
  std::vector<Marker> unmerged_;         // the last check's markers before merging
  std::vector<Dbu> bandCuts_;            // the last whole check's band rows (DesignCheckStats::cuts)
  struct ChangedNet {
    int32_t net;
    LayerId layer;
    Dbu y;  // DBU: the middle of a rect of one of its changed conductors
  };
  std::vector<ChangedNet> changed_;      // the nets of the last changeZone, by layer
  std::vector<uint8_t> kept_;            // per net: its shapes are in old_
  std::vector<int32_t> keptNets_;
  std::vector<std::vector<NetShape>> old_;  // per net of keptNets_, in that order
  int64_t lastShapes_ = 0;
};

}  // namespace xroute
