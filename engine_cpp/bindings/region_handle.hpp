// The Python Region object's C++ side, shared by the region bindings (a
// region the caller opens) and the router bindings (a region the router
// lends to a Python policy that needs the grid, for the length of one call).
#pragma once

#include <nanobind/nanobind.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "loop/session.hpp"
#include "region/region_router.hpp"

namespace xroute {

// The engine's region (loop/session.hpp) and what Python may do with it.
struct RegionHandle {
  RoutingSession* session = nullptr;      // null for a lent region
  std::unique_ptr<SessionRegion> region;  // its router is null once a lent region is returned
  Rect box;                               // DBU
  bool lent = false;                      // lent by the router to a policy: no commit

  RegionRouter& get() const {
    if (region->router == nullptr) {
      throw std::runtime_error("this region was lent to a policy for one call and is gone (the router moved on)");
    }
    return *region->router;
  }
  void checkOpen() const {
    get();
    if (region->committed) throw std::runtime_error("this region was committed; open a new one");
  }
  int32_t candidate(int32_t i) const {
    const int32_t n = static_cast<int32_t>(get().candidates().size());
    if (i < 0 || i >= n) throw nanobind::index_error(("candidate index out of range 0.." + std::to_string(n - 1)).c_str());
    return i;
  }
};

}  // namespace xroute
