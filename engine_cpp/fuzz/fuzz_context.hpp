// Shared setup of the DEF and guide fuzz targets: a real technology (and
// design) read once from the files named by XROUTE_FUZZ_LEF / XROUTE_FUZZ_DEF.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "io/input_error.hpp"
#include "io/readers.hpp"

namespace xroute::fuzz {

struct Context {
  Tech tech;
  Design design;
};

inline Context& context() {
  static Context* ctx = [] {
    auto* c = new Context();
    const char* lef = std::getenv("XROUTE_FUZZ_LEF");
    const char* def = std::getenv("XROUTE_FUZZ_DEF");
    if (!lef) {
      std::fprintf(stderr, "set XROUTE_FUZZ_LEF (and XROUTE_FUZZ_DEF for the guide target)\n");
      std::abort();
    }
    readLef(lef, c->tech);
    if (def) readDef(def, c->tech, c->design);
    return c;
  }();
  return *ctx;
}

}  // namespace xroute::fuzz
