// The private compiled module xroute_cli._engine. Translation only: C++
// errors become xroute_cli.errors.InputError; work releases the GIL.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>

#include "io/input_error.hpp"

namespace nb = nanobind;

void bindDatabase(nb::module_& m);
void bindDrc(nb::module_& m);
void bindVerify(nb::module_& m);
void bindRouter(nb::module_& m);
void bindPinAccess(nb::module_& m);
void bindRegion(nb::module_& m);
void bindGlobalRouter(nb::module_& m);

NB_MODULE(_engine, m) {
  m.doc() = "xroute's compiled engine (private; use the xroute_cli Python API).";

  nb::register_exception_translator([](const std::exception_ptr& p, void*) {
    try {
      std::rethrow_exception(p);
    } catch (const xroute::InputError& e) {
      nb::object cls = nb::module_::import_("xroute_cli.errors").attr("InputError");
      nb::object err = cls(e.message(), e.path(), e.line());
      PyErr_SetObject(cls.ptr(), err.ptr());
    }
  });

  bindDatabase(m);
  bindDrc(m);
  bindVerify(m);
  bindRouter(m);
  bindPinAccess(m);
  bindRegion(m);
  bindGlobalRouter(m);
}
