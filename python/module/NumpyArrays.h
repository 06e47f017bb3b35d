#pragma once
// Engine matrices and per-step values as NumPy arrays (float64, C order, owned by NumPy).

#include <weft/core/Types.h>

#include <pybind11/numpy.h>

#include <vector>

namespace weft::python {

// A [states, nodes, 3] array to fill state by state with copyState (allocated with the GIL held).
pybind11::array_t<double> stateArray(std::size_t states, std::size_t nodes);
// Copies x (nodes x 3) into state `index` of such an array; needs no GIL.
void copyState(double* states, std::size_t index, const NodeMatrix& x);
// A [nodes, 3] copy of x.
pybind11::array_t<double> nodeArray(const NodeMatrix& x);
// A 1-D copy of a vector.
template <typename T>
pybind11::array_t<T> vectorArray(const std::vector<T>& values) {
  return pybind11::array_t<T>(static_cast<pybind11::ssize_t>(values.size()), values.data());
}

}  // namespace weft::python
