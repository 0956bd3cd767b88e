// The Database class's bindings in two parts: database_bind.cpp (summary,
// nets, library, DEF objects, routing, loading) and database_tech_bind.cpp
// (the technology: layers, tracks, GCell grid, LEF vias, via rules, sites).
#pragma once

#include <nanobind/nanobind.h>

#include "db/database.hpp"

namespace xroute {

using DatabaseClass = nanobind::class_<Database>;

// (xlo, ylo, xhi, yhi) in DBU.
inline nanobind::tuple rectTuple(const Rect& r) { return nanobind::make_tuple(r.xlo, r.ylo, r.xhi, r.yhi); }

// Database: layers, tracks, GCell grid.
void bindDatabaseTechnology(DatabaseClass& cls);
// Database: LEF vias, via rules, sites, macro names.
void bindDatabaseVias(DatabaseClass& cls);

}  // namespace xroute
