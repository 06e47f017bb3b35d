// NumPy .npy: what weft writes must be a valid format-1.0 float64 C-order file that reads back
// bit for bit, and foreign files must be read or rejected cleanly.

#include <support/TempDir.h>
#include <weft/core/Error.h>
#include <weft/io/Npy.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace weft {
namespace {

using test::readFile;
using test::TempDir;

std::vector<double> sampleValues(std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i)
    v[i] = (i % 2 ? -1.0 : 1.0) * (0.1 + 1.7 * i) * std::pow(10.0, int(i % 7) - 3);
  return v;
}

// Builds a .npy file by hand, independently of writeNpy.
std::string handMadeNpy(const std::string& descr, const std::string& shape,
                        const std::string& payload, const std::string& order = "False") {
  std::string header =
      "{'descr': '" + descr + "', 'fortran_order': " + order + ", 'shape': " + shape + ", }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string file = std::string("\x93NUMPY\x01\x00", 8);
  file += static_cast<char>(header.size() & 0xff);
  file += static_cast<char>(header.size() >> 8);
  return file + header + payload;
}

TEST(Npy, WriteReadRoundTripIsBitExact) {
  TempDir dir;
  std::vector<double> values = sampleValues(2 * 3 * 4);
  values[5] = std::numeric_limits<double>::denorm_min();
  values[6] = -0.0;
  values[7] = 1e308;
  writeNpy(dir.file("a.npy"), {2, 3, 4}, values.data());
  const NpyArray a = readNpy(dir.file("a.npy"));
  EXPECT_EQ(a.shape, (std::vector<std::size_t>{2, 3, 4}));
  ASSERT_EQ(a.data.size(), values.size());
  EXPECT_EQ(std::memcmp(a.data.data(), values.data(), values.size() * sizeof(double)), 0);
}

TEST(Npy, HeaderFollowsFormatOne) {
  TempDir dir;
  const std::vector<double> values = sampleValues(5 * 7 * 3);
  writeNpy(dir.file("a.npy"), {5, 7, 3}, values.data());
  const std::string bytes = readFile(dir.file("a.npy"));
  ASSERT_GE(bytes.size(), 10u);
  EXPECT_EQ(bytes.substr(0, 6), "\x93NUMPY");
  EXPECT_EQ(bytes[6], 1);  // version 1.0
  EXPECT_EQ(bytes[7], 0);
  const std::size_t headerLength =
      static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8);
  // NumPy aligns the data to 64 bytes and ends the header with a newline.
  EXPECT_EQ((10 + headerLength) % 64, 0u);
  const std::string header = bytes.substr(10, headerLength);
  EXPECT_EQ(header.back(), '\n');
  EXPECT_NE(header.find("'descr': '<f8'"), std::string::npos) << header;
  EXPECT_NE(header.find("'fortran_order': False"), std::string::npos) << header;
  EXPECT_NE(header.find("'shape': (5, 7, 3)"), std::string::npos) << header;
  ASSERT_EQ(bytes.size(), 10 + headerLength + values.size() * 8);
  // C order, little endian: element [1, 2, 0] is at flat index (1 * 7 + 2) * 3.
  double v;
  std::memcpy(&v, bytes.data() + 10 + headerLength + 8 * ((1 * 7 + 2) * 3), 8);
  EXPECT_EQ(v, values[(1 * 7 + 2) * 3]);
}

TEST(Npy, OneDimensionalShapeIsAPythonTuple) {
  TempDir dir;
  const std::vector<double> values = {1, 2, 3, 4, 5};
  writeNpy(dir.file("a.npy"), {5}, values.data());
  const std::string bytes = readFile(dir.file("a.npy"));
  // (5,) or (5, ): either is a one-element tuple; (5) would be an integer.
  EXPECT_TRUE(bytes.find("'shape': (5,)") != std::string::npos ||
              bytes.find("'shape': (5, )") != std::string::npos)
      << bytes.substr(10, 100);
  const NpyArray a = readNpy(dir.file("a.npy"));
  EXPECT_EQ(a.shape, std::vector<std::size_t>{5});
  EXPECT_EQ(a.data, values);
}

TEST(Npy, ReadsHandMadeFloat64AndFloat32) {
  TempDir dir;
  const double d[4] = {1.5, -2.25, 3e-7, 42.0};
  dir.write("d.npy",
            handMadeNpy("<f8", "(2, 2)", std::string(reinterpret_cast<const char*>(d), sizeof d)));
  const NpyArray a = readNpy(dir.file("d.npy"));
  EXPECT_EQ(a.shape, (std::vector<std::size_t>{2, 2}));
  EXPECT_EQ(a.data, std::vector<double>(d, d + 4));

  const float f[3] = {0.5f, -1.25f, 1e-3f};
  dir.write("f.npy",
            handMadeNpy("<f4", "(3,)", std::string(reinterpret_cast<const char*>(f), sizeof f)));
  const NpyArray b = readNpy(dir.file("f.npy"));
  EXPECT_EQ(b.shape, std::vector<std::size_t>{3});
  ASSERT_EQ(b.data.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(b.data[i], double(f[i]));
}

TEST(Npy, RejectsWhatItCannotRead) {
  TempDir dir;
  const double d[2] = {1, 2};
  const std::string payload(reinterpret_cast<const char*>(d), sizeof d);
  dir.write("big.npy", handMadeNpy(">f8", "(2,)", payload));
  dir.write("int.npy", handMadeNpy("<i8", "(2,)", payload));
  dir.write("fortran.npy", handMadeNpy("<f8", "(2,)", payload, "True"));
  dir.write("short.npy", handMadeNpy("<f8", "(3,)", payload));
  dir.write("text.npy", "not a numpy file at all");
  for (const char* name :
       {"big.npy", "int.npy", "fortran.npy", "short.npy", "text.npy", "missing.npy"}) {
    EXPECT_THROW(readNpy(dir.file(name)), InputError) << name;
  }
}

// Found by the NPY fuzzer: sizes the file states are checked against the bytes it has before
// anything is allocated (a 113-byte file claiming a 1 GB header took 20 s and 1 GB to refuse),
// and a dimension too large for 64 bits is an InputError, not std::out_of_range.
TEST(Npy, StatedSizesBeyondTheFileAreRefusedBeforeAllocating) {
  TempDir dir;
  const double d[2] = {1, 2};
  const std::string payload(reinterpret_cast<const char*>(d), sizeof d);
  std::string hugeHeader = std::string("\x93NUMPY\x02\x00", 8) + std::string("\x00\x00\x00\x40", 4);
  dir.write("huge_header.npy", hugeHeader + "{'descr': '<f8', 'shape': (2,), }\n" + payload);
  dir.write("huge_shape.npy", handMadeNpy("<f8", "(1000000000000, 3)", payload));
  dir.write("product_overflow.npy",
            handMadeNpy("<f8", "(4294967296, 4294967296, 4294967296)", payload));
  dir.write("too_many_digits.npy",
            handMadeNpy("<f8", "(123456789012345678901234567890,)", payload));
  const struct {
    const char* name;
    const char* what;
  } cases[] = {{"huge_header.npy", "truncated header"},
               {"huge_shape.npy", "file shorter than its shape says"},
               {"product_overflow.npy", "file shorter than its shape says"},
               {"too_many_digits.npy", "a dimension beyond 10^18"}};
  for (const auto& c : cases) {
    try {
      readNpy(dir.file(c.name));
      ADD_FAILURE() << c.name << " was read";
    } catch (const InputError& e) {
      EXPECT_EQ(e.reason(), c.what) << c.name;
    }
  }
  // A zero dimension is an empty array, whatever the others say.
  dir.write("empty.npy", handMadeNpy("<f8", "(0, 5)", ""));
  EXPECT_TRUE(readNpy(dir.file("empty.npy")).data.empty());
}

TEST(Npy, WriteToAnImpossiblePathIsAnInputError) {
  TempDir dir;
  const double d[1] = {1};
  EXPECT_THROW(writeNpy(dir.file("no/such/folder/a.npy"), {1}, d), InputError);
}

}  // namespace
}  // namespace weft
