// libFuzzer target: arbitrary bytes as a DEF file, read against a real LEF
// (XROUTE_FUZZ_LEF). Bad input must end in an InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_context.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const xroute::Tech& tech = xroute::fuzz::context().tech;
  xroute::Design design;
  try {
    xroute::readDefText("fuzz.def", std::string(reinterpret_cast<const char*>(data), size), tech, design);
    // What was read must also be writable.
    (void)xroute::writeDefText(tech, design);
  } catch (const xroute::InputError&) {
  }
  return 0;
}
