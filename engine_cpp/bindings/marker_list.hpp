// Markers as the Python side sees them: a list of small dicts
// {type, layer, box: (xlo, ylo, xhi, yhi), nets: (n1, n2)}.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>

#include <string>
#include <vector>

#include "db/tech.hpp"
#include "drc/drc.hpp"

namespace xroute {

inline nanobind::list markerList(const Tech& tech, const std::vector<Marker>& markers) {
  nanobind::list out;
  for (const Marker& m : markers) {
    nanobind::dict d;
    d["type"] = std::string(markerTypeName(m.type));
    d["layer"] = tech.layer(m.layer).name;
    d["box"] = nanobind::make_tuple(m.box.xlo, m.box.ylo, m.box.xhi, m.box.yhi);
    d["nets"] = nanobind::make_tuple(m.net1, m.net2);
    out.append(d);
  }
  return out;
}

}  // namespace xroute
