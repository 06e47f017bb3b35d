// The extension module _weft, the compiled half of the Python package weft (docs/python.md).

#include "Bindings.h"

PYBIND11_MODULE(_weft, m) {
  m.doc() = "Weft's engine from Python: the compiled half of the package weft.";
  m.attr("__version__") = WEFT_VERSION;  // the project's version (python/CMakeLists.txt)
  weft::python::bindErrors(m);
  weft::python::bindSimulate(m);
  weft::python::bindSimulator(m);
  weft::python::bindGradient(m);
}
