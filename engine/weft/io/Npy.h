#pragma once
// NumPy .npy (format 1.0) reading and writing of float64 arrays, C order.

#include <cstdint>
#include <string>
#include <vector>

namespace weft {

struct NpyArray {
  std::vector<std::size_t> shape;
  std::vector<double> data;  // C (row-major) order
};

void writeNpy(const std::string& path, const std::vector<std::size_t>& shape, const double* data);
// Accepts little-endian float64 or float32 ('<f8', '<f4'), C order. Throws InputError.
NpyArray readNpy(const std::string& path);

}  // namespace weft
