#pragma once
// NumPy .npy (format 1.0) reading and writing of float64 arrays, C order.

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace weft {

struct NpyArray {
  std::vector<std::size_t> shape;
  std::vector<double> data;  // C (row-major) order
};

void writeNpy(const std::string& path, const std::vector<std::size_t>& shape, const double* data);

// A float64 .npy file written in pieces: the header for the whole shape first, then the data in
// C order as it comes (e.g. one state of a run at a time), so the array is never held whole.
// The bytes are those writeNpy writes for the same array. Throws InputError on I/O failure, and
// from close() unless exactly the shape's element count was appended.
class NpyWriter {
 public:
  NpyWriter(std::string path, const std::vector<std::size_t>& shape);
  void append(const double* data, std::size_t count);
  void close();

 private:
  std::string path_;
  std::ofstream out_;
  std::size_t expected_ = 0, written_ = 0;
};
// Accepts little-endian float64 or float32 ('<f8', '<f4'), C order. Throws InputError.
NpyArray readNpy(const std::string& path);

}  // namespace weft
