// The engine's typed errors that are not about input files (bad input is InputError,
// io/input_error.hpp). The bindings translate them to Python exceptions of xroute.errors
// (bindings/module.cpp): the Python side never has to recognise an error by its text.
#pragma once

#include <stdexcept>

namespace xroute {

// A setting the engine cannot honour for this design (e.g. a region too large for the grid
// limit) -> xroute.errors.RouteArgumentError.
class SettingError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A net-order policy whose answer is unusable (not a permutation of the candidates)
// -> xroute.errors.PolicyError.
class PolicyOrderError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace xroute
