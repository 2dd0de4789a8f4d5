// C++ exceptions as Python exceptions, translated once for every call of the module:
// thaw::UserError -> thaw.UserError (with .file, .key, .problem; str() is the CLI's line after
// "thaw: error: "), thaw::Interrupted -> KeyboardInterrupt, std::bad_alloc -> MemoryError, any
// other C++ exception -> thaw.InternalError (the CLI's exit code 3). The Python classes live in
// python/thaw/_errors.py. An internal check (THAW_CHECK) still aborts, as in the CLI.
#include <exception>
#include <new>

#include "base/error.h"
#include "base/interrupt.h"
#include "python/bindings.h"

namespace py = pybind11;

namespace thaw::python {
namespace {

void raise(const char* class_name, const py::object& instance) {
  const py::object type = py::module_::import("thaw._errors").attr(class_name);
  PyErr_SetObject(type.ptr(), instance.ptr());
}

void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const py::error_already_set&) {
    throw;  // a Python exception (a progress callback's): pybind11 restores it
  } catch (const py::builtin_exception&) {
    throw;  // pybind11's own (argument conversions): its translator sets them
  } catch (const UserError& e) {
    const py::object type = py::module_::import("thaw._errors").attr("UserError");
    raise("UserError", type(e.what(), e.file(), e.where(), e.problem()));
  } catch (const Interrupted& e) {
    PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
  } catch (const std::bad_alloc&) {
    PyErr_SetString(PyExc_MemoryError, "out of memory");
  } catch (const std::exception& e) {
    const py::object type = py::module_::import("thaw._errors").attr("InternalError");
    raise("InternalError", type(escape_control_characters(e.what())));
  }
}

}  // namespace

void bind_errors(py::module_&) {
  py::register_exception_translator(&translate);
}

}  // namespace thaw::python
