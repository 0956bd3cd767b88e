// Python view of pin access: Database.pin_access(...) computes the access
// points of every net pin (without the GIL) and returns numpy arrays.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>

#include <vector>

#include "bindings/arrays.hpp"
#include "db/database.hpp"
#include "grid/tracks.hpp"
#include "pa/pin_access.hpp"

namespace nb = nanobind;
using namespace nb::literals;

namespace xroute {
namespace {

nb::dict pinAccessDict(const Database& db, int maxPointsPerPin, int threads, bool shareClasses, bool checkInContext) {
  if (maxPointsPerPin < 1) throw nb::value_error("max_points_per_pin must be >= 1");
  if (threads < 1) throw nb::value_error("threads must be >= 1");
  PinAccessTable table;
  {
    nb::gil_scoped_release release;
    const TrackSet tracks = buildTracks(db.tech, db.design);
    table = computePinAccess(db.tech, db.design, tracks, PinAccessSettings{maxPointsPerPin, threads, shareClasses, checkInContext});
  }
  std::vector<int32_t> points, vias;
  points.reserve(table.points.size() * 5);
  vias.reserve(table.points.size());
  for (const AccessPoint& p : table.points) {
    const int32_t row[5] = {p.at.x, p.at.y, p.z, p.dirs, p.cost};
    points.insert(points.end(), row, row + 5);
    vias.push_back(p.upVia.value);
  }
  nb::list viaNames;
  for (const Via& v : db.tech.vias) viaNames.append(v.name);
  nb::dict d;
  d["start"] = ownedInt32(std::move(table.start), 1);
  d["points"] = ownedInt32(std::move(points), 5);
  d["via"] = ownedInt32(std::move(vias), 1);
  d["via_names"] = viaNames;
  d["fallback_pins"] = table.fallbackPins;
  d["classes"] = table.classes;
  return d;
}

}  // namespace
}  // namespace xroute

using namespace xroute;

void bindPinAccess(nb::module_& m) {
  m.attr("ACCESS_UP") = int(kAccessUp);
  m.attr("ACCESS_EAST") = int(kAccessEast);
  m.attr("ACCESS_WEST") = int(kAccessWest);
  m.attr("ACCESS_NORTH") = int(kAccessNorth);
  m.attr("ACCESS_SOUTH") = int(kAccessSouth);

  nb::class_<Database> cls = nb::borrow<nb::class_<Database>>(nb::type<Database>());
  cls.def("pin_access", &pinAccessDict, "max_points_per_pin"_a = PinAccessSettings{}.maxPointsPerPin, "threads"_a = 1, "share_classes"_a = true,
          "check_in_context"_a = true,
          "Access points of every net pin (every entry of pin_refs), best first.\n\n"
          "Returns a dict:\n"
          "  start: int32[pin_refs + 1]; pin ref i owns rows start[i] .. start[i+1] of points.\n"
          "  points: int32[n, 5] rows (x, y, z, dirs, cost): x, y in DBU; z = routing layer index;\n"
          "    dirs = OR of ACCESS_UP (1), ACCESS_EAST (2), ACCESS_WEST (4), ACCESS_NORTH (8),\n"
          "    ACCESS_SOUTH (16); cost: 0 = on-track in x and y, 1 per half-track coordinate, 2 per\n"
          "    shape-centre coordinate, 3 per enclosed-edge coordinate, +8 when only planar exits are\n"
          "    legal on a layer with vias up, 100 = fallback (no legal point found).\n"
          "  via: int32[n], LEF via index (into via_names) of the ACCESS_UP exit, -1 for none.\n"
          "  via_names: list of every LEF via name, by index.\n"
          "  fallback_pins: number of pin refs whose only point is a fallback.\n"
          "  classes: number of component classes computed (same macro, orientation and track phase).\n"
          "threads > 1 splits the classes over worker threads; the result is the same.\n"
          "share_classes=False computes every component on its own (slow; to check the classes):\n"
          "the points are the same, classes is then the number of components with net pins.\n"
          "check_in_context=True checks each component pin's access vias again against the shapes its class\n"
          "did not see (neighbouring cells, special nets, blockages): one too close loses ACCESS_UP (+8 cost).");
}
