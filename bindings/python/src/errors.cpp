// The library's exceptions → Python's: InvalidInput → ValueError, IoError → OSError (its message
// names the path; setting OSError.filename would turn str(e) into "[Errno None] None: path").
// Everything else keeps pybind11's mapping (std::bad_alloc → MemoryError, other std::exception →
// RuntimeError); nothing reaches Python as a crash.
#include <exception>

#include "bindings.h"
#include "breastfit/core/errors.h"

namespace breastfit::python {

void register_exceptions(py::module_&) {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const IoError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const InvalidInput& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

}  // namespace breastfit::python
