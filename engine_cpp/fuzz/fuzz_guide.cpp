// libFuzzer target: arbitrary bytes as a guide file for a real design
// (XROUTE_FUZZ_LEF + XROUTE_FUZZ_DEF). Bad input must end in an InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_context.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  xroute::fuzz::Context& ctx = xroute::fuzz::context();
  xroute::Design design = ctx.design;  // a fresh copy: guides are written into it
  try {
    xroute::readGuidesText("fuzz.guide", std::string(reinterpret_cast<const char*>(data), size), ctx.tech, design);
  } catch (const xroute::InputError&) {
  }
  return 0;
}
