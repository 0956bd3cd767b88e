// libFuzzer target: arbitrary bytes as a LEF file. Bad input must end in an
// InputError; anything else (crash, hang, sanitizer report) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/input_error.hpp"
#include "io/readers.hpp"
#include "io/validate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  xroute::Tech tech;
  try {
    xroute::readLefText("fuzz.lef", std::string(reinterpret_cast<const char*>(data), size), tech);
    xroute::validateTech(tech, {"fuzz.lef"});  // the checks run after reading (positive widths, pitches, ...)
  } catch (const xroute::InputError&) {
  }
  return 0;
}
