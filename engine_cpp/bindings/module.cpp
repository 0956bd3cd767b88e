// The private compiled module xroute._engine. Translation only: C++ errors
// become the typed exceptions of xroute.errors; work releases the GIL.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>

#include "errors/engine_errors.hpp"
#include "io/input_error.hpp"

namespace nb = nanobind;

void bindDatabase(nb::module_& m);
void bindDrc(nb::module_& m);
void bindVerify(nb::module_& m);
void bindSettings(nb::module_& m);
void bindRouter(nb::module_& m);
void bindPinAccess(nb::module_& m);
void bindRegion(nb::module_& m);
void bindFirstPass(nb::module_& m);
void bindGlobalRouter(nb::module_& m);
void bindDefaults(nb::module_& m);

NB_MODULE(_engine, m) {
  m.doc() = "xroute's compiled engine (private; use the xroute Python API).";

  nb::register_exception_translator([](const std::exception_ptr& p, void*) {
    try {
      std::rethrow_exception(p);
    } catch (const xroute::InputError& e) {
      nb::object cls = nb::module_::import_("xroute.errors").attr("InputError");
      nb::object err = cls(e.message(), e.path(), e.line());
      PyErr_SetObject(cls.ptr(), err.ptr());
    } catch (const xroute::SettingError& e) {
      nb::object cls = nb::module_::import_("xroute.errors").attr("RouteArgumentError");
      PyErr_SetObject(cls.ptr(), cls(e.what()).ptr());
    } catch (const xroute::PolicyOrderError& e) {
      nb::object cls = nb::module_::import_("xroute.errors").attr("PolicyError");
      PyErr_SetObject(cls.ptr(), cls(e.what()).ptr());
    }
  });

  bindDatabase(m);
  bindDrc(m);
  bindVerify(m);
  bindSettings(m);
  bindRouter(m);
  bindPinAccess(m);
  bindRegion(m);
  bindFirstPass(m);
  bindGlobalRouter(m);
  bindDefaults(m);
}
