// Python view of the design-rule checker: shapes as an int32 numpy array in,
// markers as a list of small dicts out. The check itself runs without the GIL.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>

#include <algorithm>
#include <optional>
#include <string>
#include <tuple>

#include "db/database.hpp"
#include "bindings/marker_list.hpp"
#include "drc/design_check.hpp"
#include "drc/drc.hpp"

namespace nb = nanobind;
using namespace nb::literals;

namespace xroute {
namespace {

using ShapeArray = nb::ndarray<const int32_t, nb::ndim<2>, nb::c_contig, nb::device::cpu>;
using OriginArray = nb::ndarray<const int32_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>;

DrcOptions makeOptions(bool skipFixed, const std::optional<std::tuple<int, int, int, int>>& window) {
  DrcOptions o;
  o.skipFixedPairs = skipFixed;
  if (window) {
    const auto& [x0, y0, x1, y1] = *window;
    o.window = Rect{x0, y0, x1, y1};
  }
  return o;
}

}  // namespace
}  // namespace xroute

using namespace xroute;

void bindDrc(nb::module_& m) {
  nb::list markerTypes;
  for (int t = 0; t < kMarkerTypes; ++t) markerTypes.append(std::string(markerTypeName(static_cast<MarkerType>(t))));
  m.attr("MARKER_TYPES") = nb::tuple(markerTypes);
  m.def(
      "check_shapes",
      [](const Database& db, ShapeArray shapes, std::optional<OriginArray> origins, bool skip_fixed_pairs,
         std::optional<std::tuple<int, int, int, int>> window) {
        const size_t n = shapes.shape(0);
        if (shapes.shape(1) != 6) throw nb::value_error("shapes must have 6 columns: layer, xlo, ylo, xhi, yhi, net");
        if (origins && origins->shape(0) != n)
          throw nb::value_error("origins must have one entry per shape");
        std::vector<DrcShape> list(n);
        const int32_t* p = shapes.data();
        const int32_t layers = int32_t(db.tech.layers.size());
        for (size_t i = 0; i < n; ++i, p += 6) {
          if (p[0] < 0 || p[0] >= layers) throw nb::index_error("layer index out of range");
          DrcShape& s = list[i];
          s.layer = LayerId(p[0]);
          s.rect = Rect::fromCorners({p[1], p[2]}, {p[3], p[4]});
          s.net = p[5];
          if (origins) {
            const int32_t o = origins->data()[i];
            if (o < 0 || o > int(ShapeOrigin::SpecialNet)) throw nb::value_error("origin must be 0..4");
            s.origin = ShapeOrigin(o);
          } else {
            s.origin = s.net < 0 ? ShapeOrigin::Obstruction : ShapeOrigin::Wire;
          }
        }
        std::vector<Marker> markers;
        {
          nb::gil_scoped_release release;
          markers = checkShapes(db.tech, std::move(list), makeOptions(skip_fixed_pairs, window));
        }
        return markerList(db.tech, markers);
      },
      "db"_a, "shapes"_a, "origins"_a = nb::none(), "skip_fixed_pairs"_a = false, "window"_a = nb::none(),
      "Design-rule check of a set of shapes against the technology of `db`.\n\n"
      "shapes: int32[N, 6] rows (LEF layer index, xlo, ylo, xhi, yhi, net) in DBU; net < 0 marks an\n"
      "obstruction. origins: optional int[N], 0 wire, 1 via, 2 pin, 3 obstruction, 4 special net\n"
      "(default: 3 for net < 0, else 0). skip_fixed_pairs drops violations among pins, obstructions\n"
      "and special nets only. window: optional (xlo, ylo, xhi, yhi); only markers touching it.\n"
      "Returns markers sorted, as dicts {type, layer, box: (xlo, ylo, xhi, yhi), nets: (n1, n2)}.");

  nb::class_<Database> cls = nb::borrow<nb::class_<Database>>(nb::type<Database>());
  cls.def(
      "check_drc",
      [](const Database& db, bool skip_fixed_pairs, std::optional<std::tuple<int, int, int, int>> window,
         int64_t band_shapes, int threads) {
        if (band_shapes < 0) throw nb::value_error("band_shapes must be >= 0");
        std::vector<Marker> markers;
        {
          nb::gil_scoped_release release;
          DrcOptions options = makeOptions(skip_fixed_pairs, window);
          options.ndrSpacing = ndrSpacingByNet(db.tech, db.design);  // the nets' NONDEFAULTRULE spacing
          options.bandShapes = band_shapes;
          options.threads = std::max(1, threads);
          markers = checkDesign(db.tech, db.design, options);
        }
        return markerList(db.tech, markers);
      },
      "skip_fixed_pairs"_a = true, "window"_a = nb::none(), "band_shapes"_a = kCheckBandShapes, "threads"_a = 1,
      "Design-rule check of the whole design (pins, OBS, blockages, special and regular routing).\n"
      "Net ids in the markers: regular nets 0..nets-1, special nets next, then pins on no net;\n"
      "-1 = obstruction. Same marker dicts as check_shapes. band_shapes: a design of more shapes\n"
      "is checked in horizontal bands of about this many (0: at once; not with skip_fixed_pairs off\n"
      "or a window); threads: layers checked at once. Neither changes the markers.");
  cls.def(
      "drc_shapes",
      [](const Database& db) {
        std::vector<DrcShape> shapes;
        {
          nb::gil_scoped_release release;
          shapes = collectDesignShapes(db.tech, db.design);
        }
        nb::list out;
        for (const DrcShape& s : shapes)
          out.append(nb::make_tuple(*s.layer, s.rect.xlo, s.rect.ylo, s.rect.xhi, s.rect.yhi, s.net, int(s.origin)));
        return out;
      },
      "The shapes check_drc checks: (layer index, xlo, ylo, xhi, yhi, net, origin) tuples.");
}
