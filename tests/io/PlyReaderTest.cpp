// Weft's own PLY reader (engine/weft/io/PlyReader.cpp), through readMesh as every caller uses
// it: the file's vertex order and count kept, the three encodings, the header's variety, and a
// clear InputError for every malformed file the fuzzer or a user can make (docs/hardening.md).

#include "MeshFileFixtures.h"

#include <support/TempDir.h>
#include <weft/core/Error.h>
#include <weft/io/MeshReader.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <sstream>

namespace weft {
namespace {

using test::expectScrambledStrip;
using test::kPositions;
using test::kTriangles;
using test::TempDir;

// Appends `value` to `out` as big-endian bytes.
template <class T>
void appendBigEndian(std::string& out, T value) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) out += static_cast<char>(raw[sizeof(T) - 1 - i]);
}

TEST(PlyReader, AsciiKeepsVertexOrderAndCount) {
  TempDir dir;
  std::ostringstream s;
  s << "ply\nformat ascii 1.0\ncomment scrambled strip\nelement vertex 7\n"
       "property float x\nproperty float y\nproperty float z\n"
       "element face 5\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : kPositions) s << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (const auto& t : kTriangles) s << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  expectScrambledStrip(readMesh(dir.write("strip.ply", s.str())));
}

TEST(PlyReader, BinaryLittleEndianKeepsVertexOrderAndCount) {
  TempDir dir;
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 7\n"
      "property double x\nproperty double y\nproperty double z\n"
      "element face 5\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : kPositions) s.append(reinterpret_cast<const char*>(p), sizeof p);
  for (const auto& t : kTriangles) {
    s += static_cast<char>(3);
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = t[k];
      s.append(reinterpret_cast<const char*>(&v), 4);
    }
  }
  expectScrambledStrip(readMesh(dir.write("strip-binary.ply", s)));
}

// Big-endian, with properties and elements Weft does not use around the ones it reads: normals
// and a colour between the coordinates, an `edge` element between vertices and faces, a face
// property after the list, the index list spelt `vertex_index`, CRLF line ends in the header.
TEST(PlyReader, BinaryBigEndianReadsPastPropertiesAndElementsItDoesNotUse) {
  TempDir dir;
  std::string s =
      "ply\r\nformat binary_big_endian 1.0\r\ncomment from a scanner\r\nobj_info v1\r\n"
      "element vertex 7\r\nproperty float32 nx\r\nproperty double x\r\nproperty uchar red\r\n"
      "property double y\r\nproperty list uint8 int16 misc\r\nproperty double z\r\n"
      "element edge 2\r\nproperty int vertex1\r\nproperty int vertex2\r\n"
      "element face 5\r\nproperty list uchar uint vertex_index\r\nproperty short flags\r\n"
      "end_header\r\n";
  for (const auto& p : kPositions) {
    appendBigEndian(s, 0.25f);
    appendBigEndian(s, p[0]);
    s += static_cast<char>(200);
    appendBigEndian(s, p[1]);
    s += static_cast<char>(2);
    appendBigEndian(s, std::int16_t{-7});
    appendBigEndian(s, std::int16_t{9});
    appendBigEndian(s, p[2]);
  }
  for (int e = 0; e < 2; ++e) {
    appendBigEndian(s, std::int32_t{e});
    appendBigEndian(s, std::int32_t{e + 1});
  }
  for (const auto& t : kTriangles) {
    s += static_cast<char>(3);
    for (int k = 0; k < 3; ++k) appendBigEndian(s, static_cast<std::uint32_t>(t[k]));
    appendBigEndian(s, std::int16_t{1});
  }
  expectScrambledStrip(readMesh(dir.write("strip-big.ply", s)));
}

TEST(PlyReader, PolygonsAreFanTriangulatedWithoutNewVertices) {
  TempDir dir;
  const std::string path = dir.write(
      "quad.ply",
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n1 0 1\n0 0 1\n0.5 0 1.5\n3 3 2 4\n4 0 3 2 1\n");
  test::expectTriangleAndQuadFan(readMesh(path));
}

// Each malformed file ends in an InputError whose reason names what is wrong, at once: a count
// the file cannot hold is refused before anything is allocated or read.
TEST(PlyReader, MalformedFilesAreRefusedNamingTheFault) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::string hugeList =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uint int vertex_indices\nend_header\n" +
      std::string(36, '\0');
  hugeList += std::string("\xff\xff\xff\xff", 4) + std::string(12, '\0');
  const std::vector<test::MalformedFile> cases = {
      {"no_end_header.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n",
       "no 'end_header'"},
      {"not_ply.ply", "this is not a mesh\n", "does not begin with 'ply'"},
      {"no_format.ply", "ply\nelement vertex 0\nend_header\n", "no 'format' line"},
      {"format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown format"},
      {"keyword.ply", "ply\nformat ascii 1.0\nelephant 3\nend_header\n", "unknown keyword"},
      {"type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n",
       "not a PLY type"},
      {"orphan_property.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n",
       "before any element"},
      {"no_z.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n"
       "0 0\n",
       "no scalar property 'z'"},
      {"no_vertex.ply", "ply\nformat ascii 1.0\nend_header\n", "no 'vertex' element"},
      {"huge_count.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 700000000\nproperty double x\n"
       "property double y\nproperty double z\nend_header\n0123456789",
       "more than the rest of the file can hold"},
      {"huge_list.ply", hugeList, "runs past the end of the file"},
      // An element without properties takes no bytes: a huge count of it is read past at once
      // (here the face element after it then fails, proving it was reached).
      {"empty_element.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nelement nothing 700000000\nelement face 1\n"
       "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n",
       "vertex index 9 is out of range"},
      {"short.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "ends inside element 'face' 0"},
      {"index.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "vertex index 3 is out of range"},
      {"negative.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
       "vertex index -1 is out of range"},
      {"two_corners.ply", header + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "has 2 corners"},
      {"nan.ply", header + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "coordinate y is not a finite"},
      {"overflow.ply", header + "0 0 0\n1 1e400 0\n0 1 0\n3 0 1 2\n", "out of the range"},
      {"word.ply", header + "0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n", "'abc' is not a number"},
      {"uchar_range.ply", header + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n", "out of the range"},
      {"float_count.ply", header + "0 0 0\n1 0 0\n0 1 0\n3.5 0 1 2\n", "not a whole number"},
  };
  TempDir dir;
  test::expectRefused(dir, cases, "PLY: ");
}

}  // namespace
}  // namespace weft
