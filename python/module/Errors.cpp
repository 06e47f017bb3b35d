// Weft's two failure kinds as Python exceptions: InputError (a ValueError; the CLI exits 2) and
// NumericalError (a RuntimeError; the CLI exits 3). str(exception) is the CLI's message after its
// "error: " prefix: `<file>: <json path or option>: <what is wrong>` and `numerical failure:
// step <n>: <module>: <quantity>`. The parts are attributes too (file, path, reason; step,
// module, quantity).

#include "Bindings.h"

#include <weft/core/Error.h>

namespace weft::python {

namespace py = pybind11;

namespace {

// The exception types, owned by the module (its attributes keep them alive).
py::handle inputErrorType, numericalErrorType;

// Raises `type` with `message` and the attributes, from a C++ exception handler.
void raise(py::handle type, const std::string& message, const py::dict& attributes) {
  py::object exception = type(message);
  for (auto item : attributes) py::setattr(exception, item.first, item.second);
  PyErr_SetObject(type.ptr(), exception.ptr());
}

}  // namespace

void bindErrors(py::module_& m) {
  m.attr("InputError") = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("weft.InputError",
                                "Bad input: a scene, parameter or option that cannot be used "
                                "(the CLI exits 2).",
                                PyExc_ValueError, nullptr));
  m.attr("NumericalError") = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("weft.NumericalError",
                                "A numerical failure: names the step, the module and the "
                                "quantity (the CLI exits 3).",
                                PyExc_RuntimeError, nullptr));
  inputErrorType = m.attr("InputError");
  numericalErrorType = m.attr("NumericalError");
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const InputError& e) {
      raise(inputErrorType, e.what(),
            py::dict(py::arg("file") = e.file(), py::arg("path") = e.path(),
                     py::arg("reason") = e.reason()));
    } catch (const NumericalError& e) {
      raise(numericalErrorType, std::string("numerical failure: ") + e.what(),
            py::dict(py::arg("step") = e.step(), py::arg("module") = e.module(),
                     py::arg("quantity") = e.quantity()));
    }
  });
}

void checkInterrupt() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

}  // namespace weft::python
