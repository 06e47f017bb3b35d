#pragma once
// The parts of the extension module _weft, each defined in its own file and added to the module
// by Module.cpp. The Python package weft (python/weft/__init__.py) wraps them.

#include <pybind11/pybind11.h>

namespace weft::python {

void bindErrors(pybind11::module_& m);     // Errors.cpp: InputError, NumericalError
void bindSimulate(pybind11::module_& m);   // Simulate.cpp: simulate
void bindSimulator(pybind11::module_& m);  // SimulatorBinding.cpp: Simulator
void bindGradient(pybind11::module_& m);   // Gradient.cpp: gradient

// Raises KeyboardInterrupt (and the like) between steps of a loop that runs without the GIL.
void checkInterrupt();

}  // namespace weft::python
