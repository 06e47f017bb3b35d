#include <weft/io/Npy.h>

#include <weft/core/Error.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <numeric>
#include <regex>
#include <sstream>
#include <utility>

namespace weft {

NpyWriter::NpyWriter(std::string path, const std::vector<std::size_t>& shape)
    : path_(std::move(path)),
      expected_(std::accumulate(shape.begin(), shape.end(), std::size_t{1}, std::multiplies<>())) {
  std::ostringstream dict;
  dict << "{'descr': '<f8', 'fortran_order': False, 'shape': (";
  for (std::size_t i = 0; i < shape.size(); ++i)
    dict << shape[i] << (shape.size() == 1 || i + 1 < shape.size() ? ", " : "");
  dict << "), }";
  std::string header = dict.str();
  // Magic (6) + version (2) + header length (2) + header, padded with spaces to 64 bytes + '\n'.
  const std::size_t unpadded = 10 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header.push_back('\n');
  out_.open(path_, std::ios::binary);
  if (!out_) throw InputError(path_, "output", "cannot open for writing");
  const char magic[8] = {'\x93', 'N', 'U', 'M', 'P', 'Y', 1, 0};
  out_.write(magic, 8);
  const std::uint16_t len = static_cast<std::uint16_t>(header.size());
  const char lenBytes[2] = {static_cast<char>(len & 0xff), static_cast<char>(len >> 8)};
  out_.write(lenBytes, 2);
  out_.write(header.data(), static_cast<std::streamsize>(header.size()));
  if (!out_) throw InputError(path_, "output", "write failed");
}

void NpyWriter::append(const double* data, std::size_t count) {
  if (written_ + count > expected_)
    throw InputError(path_, "output", "more values than the array's shape holds");
  out_.write(reinterpret_cast<const char*>(data),
             static_cast<std::streamsize>(count * sizeof(double)));
  if (!out_) throw InputError(path_, "output", "write failed");
  written_ += count;
}

void NpyWriter::close() {
  if (written_ != expected_)
    throw InputError(
        path_, "output",
        "holds " + std::to_string(written_) + " values, its shape " + std::to_string(expected_));
  out_.close();
  if (!out_) throw InputError(path_, "output", "write failed");
}

void writeNpy(const std::string& path, const std::vector<std::size_t>& shape, const double* data) {
  NpyWriter out(path, shape);
  out.append(data,
             std::accumulate(shape.begin(), shape.end(), std::size_t{1}, std::multiplies<>()));
  out.close();
}

NpyArray readNpy(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path, "npy", "cannot open file");
  // Every size the file states is checked against the bytes it has before anything is allocated
  // (a 100-byte file may claim a 4 GB header or a shape of 2^64 values).
  const std::streamoff fileSize = in.tellg();
  in.seekg(0);
  char magic[8];
  in.read(magic, 8);
  if (!in || std::memcmp(magic, "\x93NUMPY", 6) != 0)
    throw InputError(path, "npy", "not a .npy file");
  std::size_t headerLen = 0;
  if (magic[6] == 1) {
    unsigned char b[2];
    in.read(reinterpret_cast<char*>(b), 2);
    headerLen = b[0] | (b[1] << 8);
  } else {
    unsigned char b[4];
    in.read(reinterpret_cast<char*>(b), 4);
    headerLen = b[0] | (b[1] << 8) | (b[2] << 16) | (static_cast<std::size_t>(b[3]) << 24);
  }
  if (!in || static_cast<std::streamoff>(headerLen) > fileSize - in.tellg())
    throw InputError(path, "npy", "truncated header");
  std::string header(headerLen, '\0');
  in.read(header.data(), static_cast<std::streamsize>(headerLen));
  if (!in) throw InputError(path, "npy", "truncated header");
  std::smatch m;
  if (!std::regex_search(header, m, std::regex("'descr':\\s*'([<|=]?)(f[48])'")))
    throw InputError(path, "npy", "only little-endian float32/float64 arrays are supported");
  const bool isDouble = m[2] == "f8";
  if (std::regex_search(header, std::regex("'fortran_order':\\s*True")))
    throw InputError(path, "npy", "Fortran-order arrays are not supported");
  if (!std::regex_search(header, m, std::regex("'shape':\\s*\\(([^)]*)\\)")))
    throw InputError(path, "npy", "header has no shape");
  NpyArray array;
  std::string dims = m[1];
  std::regex num("[0-9]+");
  const std::size_t elementSize = isDouble ? 8 : 4;
  const std::size_t available = static_cast<std::size_t>(fileSize - in.tellg()) / elementSize;
  for (auto it = std::sregex_iterator(dims.begin(), dims.end(), num); it != std::sregex_iterator();
       ++it) {
    const std::string digits = it->str();
    if (digits.size() > 18) throw InputError(path, "npy", "a dimension beyond 10^18");
    array.shape.push_back(std::stoull(digits));
  }
  // The product may not exceed the values the file holds (checked without overflowing); a zero
  // dimension makes an empty array whatever the others say.
  std::size_t count = 1;
  const bool empty = std::find(array.shape.begin(), array.shape.end(), 0) != array.shape.end();
  for (std::size_t d : array.shape) {
    if (empty) {
      count = 0;
      break;
    }
    if (count > available / d) throw InputError(path, "npy", "file shorter than its shape says");
    count *= d;
  }
  array.data.resize(count);
  if (isDouble) {
    in.read(reinterpret_cast<char*>(array.data.data()), static_cast<std::streamsize>(count * 8));
  } else {
    std::vector<float> tmp(count);
    in.read(reinterpret_cast<char*>(tmp.data()), static_cast<std::streamsize>(count * 4));
    std::copy(tmp.begin(), tmp.end(), array.data.begin());
  }
  if (!in) throw InputError(path, "npy", "file shorter than its shape says");
  return array;
}

}  // namespace weft
