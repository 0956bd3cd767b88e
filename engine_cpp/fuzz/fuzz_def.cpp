// libFuzzer target: arbitrary bytes as a DEF file, read against a real LEF
// (XROUTE_FUZZ_LEF). Bad input must end in an InputError. What was read must
// also survive a round trip: written back, re-read without error, and equal.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "db/compare.hpp"
#include "fuzz_context.hpp"
#include "io/validate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const xroute::Tech& tech = xroute::fuzz::context().tech;
  xroute::Design design;
  try {
    xroute::readDefText("fuzz.def", std::string(reinterpret_cast<const char*>(data), size), tech, design);
    xroute::validateDesign(tech, design, "fuzz.def");  // the checks run after reading (die area, ...)
  } catch (const xroute::InputError&) {
    return 0;
  }
  const std::string text = xroute::writeDefText(tech, design);
  xroute::Design again;
  try {
    xroute::readDefText("written.def", text, tech, again);
    xroute::validateDesign(tech, again, "written.def");
  } catch (const xroute::InputError& e) {
    std::fprintf(stderr, "written DEF does not re-read: %s\n%s\n", e.what(), text.c_str());
    std::abort();
  }
  const std::vector<std::string> diffs = xroute::compareDesigns(design, again, 5);
  if (!diffs.empty()) {
    for (const std::string& d : diffs) std::fprintf(stderr, "round trip differs: %s\n", d.c_str());
    std::abort();
  }
  return 0;
}
