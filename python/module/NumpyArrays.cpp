#include "NumpyArrays.h"

namespace weft::python {

namespace py = pybind11;

py::array_t<double> stateArray(std::size_t states, std::size_t nodes) {
  return py::array_t<double>(
      {static_cast<py::ssize_t>(states), static_cast<py::ssize_t>(nodes), py::ssize_t{3}});
}

void copyState(double* states, std::size_t index, const NodeMatrix& x) {
  // Row by row, as RunWriter writes positions.npy: node i's x, y, z.
  double* row = states + index * static_cast<std::size_t>(x.rows()) * 3;
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (int c = 0; c < 3; ++c) *row++ = x(i, c);
}

py::array_t<double> nodeArray(const NodeMatrix& x) {
  py::array_t<double> out = stateArray(1, static_cast<std::size_t>(x.rows()));
  copyState(out.mutable_data(), 0, x);
  return out.reshape({static_cast<py::ssize_t>(x.rows()), py::ssize_t{3}});
}

}  // namespace weft::python
