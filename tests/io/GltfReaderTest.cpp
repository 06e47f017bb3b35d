// Weft's own glTF 2.0 reader (engine/weft/io/GltfReader.cpp), through readMesh as every caller
// uses it: vertex order and count kept, node placements, the GLB container, buffers in files,
// every topology and layout, and a clear InputError for every malformed file (docs/hardening.md).

#include "MeshFileFixtures.h"

#include <support/TempDir.h>
#include <weft/core/Error.h>
#include <weft/io/MeshReader.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <functional>
#include <sstream>

namespace weft {
namespace {

using nlohmann::json;
using test::expectScrambledStrip;
using test::kPositions;
using test::kTriangles;
using test::TempDir;

std::string base64(const std::string& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t chunk = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) chunk |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) chunk |= static_cast<unsigned char>(bytes[i + 2]);
    out += alphabet[(chunk >> 18) & 63];
    out += alphabet[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? alphabet[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? alphabet[chunk & 63] : '=';
  }
  return out;
}

// glTF 2.0 holding the scrambled strip as mesh 0 (an embedded buffer: float32 positions, uint16
// indices), placed by `nodes` (a JSON array) of which scene 0 lists `roots`.
std::string stripGltf(const std::string& nodes = R"([{"mesh": 0}])",
                      const std::string& roots = "[0]") {
  std::string buffer;
  for (const auto& p : kPositions)
    for (double c : p) {
      const float f = static_cast<float>(c);
      buffer.append(reinterpret_cast<const char*>(&f), 4);
    }
  const std::size_t positionBytes = buffer.size();
  for (const auto& t : kTriangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint16_t i = static_cast<std::uint16_t>(t[k]);
      buffer.append(reinterpret_cast<const char*>(&i), 2);
    }
  std::ostringstream g;
  g << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": )" << roots << R"(}],
  "nodes": )"
    << nodes << R"(,
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
  "buffers": [{"byteLength": )"
    << buffer.size() << R"(, "uri": "data:application/octet-stream;base64,)" << base64(buffer)
    << R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": )"
    << positionBytes << R"(},
                  {"buffer": 0, "byteOffset": )"
    << positionBytes << R"(, "byteLength": )" << buffer.size() - positionBytes << R"(}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 7, "type": "VEC3",
                 "min": [0, 0, 0], "max": [2, 0.5, 1]},
                {"bufferView": 1, "componentType": 5123, "count": 15, "type": "SCALAR"}]})";
  return g.str();
}

TEST(GltfReader, KeepsVertexOrderAndCount) {
  TempDir dir;
  expectScrambledStrip(readMesh(dir.write("strip.gltf", stripGltf())));
}

// An exporter stores an object's placement in its nodes, not in its vertices: the strip is read
// where the node hierarchy puts it (parent then child transform), once per node that references
// it, and a mirroring node lists each triangle's corners the other way round.
TEST(GltfReader, AppliesNodeTransformsAndInstances) {
  // Node 0 (root): translation (10, 0, 0) and uniform scale 2; its child node 1: a quarter turn
  // about z (quaternion (0, 0, sin 45, cos 45)) holding the mesh. Node 2 (a second root): the same
  // mesh mirrored in x.
  const std::string nodes = R"([
    {"translation": [10, 0, 0], "scale": [2, 2, 2], "children": [1]},
    {"rotation": [0, 0, 0.7071067811865476, 0.7071067811865476], "mesh": 0},
    {"scale": [-1, 1, 1], "mesh": 0}])";
  TempDir dir;
  const TriangleMesh mesh = readMesh(dir.write("placed.gltf", stripGltf(nodes, "[0, 2]")));
  ASSERT_EQ(mesh.vertexCount(), 14);
  ASSERT_EQ(mesh.triangleCount(), 10);
  for (int i = 0; i < 7; ++i) {
    SCOPED_TRACE(i);
    const double x = kPositions[i][0], y = kPositions[i][1], z = kPositions[i][2];
    // First instance: x' = 10 + 2 R_z(90) x = (10 - 2y, 2x, 2z); float precision.
    EXPECT_NEAR(mesh.vertices(i, 0), 10.0 - 2.0 * y, 1e-5);
    EXPECT_NEAR(mesh.vertices(i, 1), 2.0 * x, 1e-5);
    EXPECT_NEAR(mesh.vertices(i, 2), 2.0 * z, 1e-5);
    // Second: mirrored, (-x, y, z).
    EXPECT_EQ(mesh.vertices(7 + i, 0), -x);
    EXPECT_EQ(mesh.vertices(7 + i, 1), y);
    EXPECT_EQ(mesh.vertices(7 + i, 2), z);
  }
  for (int t = 0; t < 5; ++t) {
    SCOPED_TRACE(t);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mesh.triangles(t, k), kTriangles[t][k]);
    // The mirrored copy: the same corners, second and third swapped.
    EXPECT_EQ(mesh.triangles(5 + t, 0), 7 + kTriangles[t][0]);
    EXPECT_EQ(mesh.triangles(5 + t, 1), 7 + kTriangles[t][2]);
    EXPECT_EQ(mesh.triangles(5 + t, 2), 7 + kTriangles[t][1]);
  }
}

// The strip's buffer (float32 positions then uint16 indices) and its glTF without the buffer's
// uri, for the container and file tests.
std::string stripBuffer() {
  std::string buffer;
  for (const auto& p : kPositions)
    for (double c : p) {
      const float f = static_cast<float>(c);
      buffer.append(reinterpret_cast<const char*>(&f), 4);
    }
  for (const auto& t : kTriangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint16_t i = static_cast<std::uint16_t>(t[k]);
      buffer.append(reinterpret_cast<const char*>(&i), 2);
    }
  return buffer;
}

json stripDocument() {
  json doc = json::parse(stripGltf());
  doc["buffers"][0].erase("uri");
  return doc;
}

void append32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
}

// A GLB container: header, the JSON chunk (space-padded) and a BIN chunk (zero-padded).
std::string glb(const json& doc, const std::string& bin) {
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  std::string data = bin;
  while (data.size() % 4) data += '\0';
  std::string out = "glTF";
  append32(out, 2);
  append32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + data.size()));
  append32(out, static_cast<std::uint32_t>(text.size()));
  append32(out, 0x4E4F534A);
  out += text;
  append32(out, static_cast<std::uint32_t>(data.size()));
  append32(out, 0x004E4942);
  out += data;
  return out;
}

// A .glb with its buffer in the BIN chunk, placed by a node matrix (column-major, a translation
// by (1, 2, 3)).
TEST(GltfReader, GlbContainerAndNodeMatrix) {
  json doc = stripDocument();
  doc["nodes"] = json::parse(R"([{"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 1,2,3,1]}])");
  TempDir dir;
  const TriangleMesh mesh = readMesh(dir.write("strip.glb", glb(doc, stripBuffer())));
  ASSERT_EQ(mesh.vertexCount(), 7);
  for (int i = 0; i < 7; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(mesh.vertices(i, c), kPositions[i][c] + 1.0 + c);
  for (int t = 0; t < 5; ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mesh.triangles(t, k), kTriangles[t][k]);
}

// A buffer in a file beside the .gltf, named by a relative URI with an escaped space.
TEST(GltfReader, BufferInAFileBesideIt) {
  json doc = stripDocument();
  doc["buffers"][0]["uri"] = "strip%20data.bin";
  TempDir dir;
  dir.write("strip data.bin", stripBuffer());
  expectScrambledStrip(readMesh(dir.write("strip.gltf", doc.dump())));
}

// A strip (uint8 indices), a fan without indices (positions interleaved with normals, byteStride
// 24) and lines in one mesh: the strip's and the fan's triangles with the winding the glTF spec
// gives them, each primitive with its own vertices, the lines left out.
TEST(GltfReader, StripsFansAndInterleavedVerticesLinesLeftOut) {
  std::string buffer;
  const float strip[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  for (const auto& p : strip) buffer.append(reinterpret_cast<const char*>(p), 12);  // 0..47
  const unsigned char stripIndices[4] = {0, 1, 2, 3};
  buffer.append(reinterpret_cast<const char*>(stripIndices), 4);  // 48..51
  const float fan[4][3] = {{5, 0, 0}, {6, 0, 0}, {6, 1, 0}, {5, 1, 0}};
  const float normal[3] = {0, 0, 1};
  for (const auto& p : fan) {  // 52..147, interleaved
    buffer.append(reinterpret_cast<const char*>(p), 12);
    buffer.append(reinterpret_cast<const char*>(normal), 12);
  }
  json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scenes", json::array({{{"nodes", {0}}}})},
      {"nodes", json::array({{{"mesh", 0}}})},
      {"meshes",
       json::array({{{"primitives",
                      json::array({{{"attributes", {{"POSITION", 0}}}, {"mode", 1}},
                                   {{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", 5}},
                                   {{"attributes", {{"POSITION", 2}}}, {"mode", 6}}})}}})},
      {"buffers", json::array({{{"byteLength", buffer.size()}}})},
      {"bufferViews",
       json::array({{{"buffer", 0}, {"byteLength", 48}},
                    {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 4}},
                    {{"buffer", 0}, {"byteOffset", 52}, {"byteLength", 96}, {"byteStride", 24}}})},
      {"accessors",
       json::array(
           {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
            {{"bufferView", 1}, {"componentType", 5121}, {"count", 4}, {"type", "SCALAR"}},
            {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}}})}};
  TempDir dir;
  const TriangleMesh mesh = readMesh(dir.write("topologies.glb", glb(doc, buffer)));
  ASSERT_EQ(mesh.vertexCount(), 8);
  ASSERT_EQ(mesh.triangleCount(), 4);
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(mesh.vertices(i, c), strip[i][c]);
      EXPECT_EQ(mesh.vertices(4 + i, c), fan[i][c]);
    }
  EXPECT_EQ(mesh.triangles.row(0), Eigen::RowVector3i(0, 1, 2));  // strip: v0 v1 v2
  EXPECT_EQ(mesh.triangles.row(1), Eigen::RowVector3i(1, 3, 2));  // then v1 v3 v2
  EXPECT_EQ(mesh.triangles.row(2), Eigen::RowVector3i(5, 6, 4));  // fan: v1 v2 v0
  EXPECT_EQ(mesh.triangles.row(3), Eigen::RowVector3i(6, 7, 4));  // then v2 v3 v0
}

// Each malformed file ends in an InputError whose reason names what is wrong; no stated length
// is trusted with an allocation or a read before it is checked against the bytes it names.
TEST(GltfReader, MalformedFilesAreRefusedNamingTheFault) {
  TempDir dir;
  dir.write("small.bin", stripBuffer());
  const auto with = [](const std::function<void(json&)>& change) {
    json doc = json::parse(stripGltf());
    change(doc);
    return doc.dump();
  };
  const std::vector<test::MalformedFile> cases = {
      {"not_json.gltf", "{\"asset\": ", "not valid JSON"},
      {"array.gltf", "[1, 2]", "not a JSON object"},
      {"no_asset.gltf", "{}", "asset.version is missing"},
      {"v1.gltf", with([](json& d) { d["asset"]["version"] = "1.0"; }), "only glTF 2.0"},
      {"extension.gltf",
       with([](json& d) { d["extensionsRequired"] = {"KHR_draco_mesh_compression"}; }),
       "requires the extension KHR_draco_mesh_compression"},
      {"sparse.gltf", with([](json& d) { d["accessors"][0]["sparse"] = json::object(); }),
       "sparse"},
      {"no_view.gltf", with([](json& d) { d["accessors"][0].erase("bufferView"); }),
       "no bufferView"},
      {"past_view.gltf", with([](json& d) { d["accessors"][0]["count"] = 8; }),
       "8 elements run past the end of bufferViews[0]"},
      {"past_buffer.gltf", with([](json& d) { d["bufferViews"][1]["byteLength"] = 31; }),
       "bufferViews[1] runs past the end of its buffer"},
      {"short_data.gltf", with([](json& d) { d["buffers"][0]["byteLength"] = 1000; }),
       "states 1000 bytes, its data has 114"},
      {"huge_file_length.gltf", with([](json& d) {
         d["buffers"][0]["uri"] = "small.bin";
         d["buffers"][0]["byteLength"] = std::uint64_t{1} << 50;
       }),
       "its data has 114"},
      {"no_file.gltf", with([](json& d) { d["buffers"][0]["uri"] = "missing.bin"; }),
       "is not a readable file"},
      {"directory.gltf", with([](json& d) { d["buffers"][0]["uri"] = "."; }),
       "is not a readable file"},
      {"base64.gltf",
       with([](json& d) { d["buffers"][0]["uri"] = "data:application/octet-stream;base64,@@@"; }),
       "not valid base64"},
      {"index.gltf", with([](json& d) { d["accessors"][0]["count"] = 6; }),
       "vertex index 6 is out of range (6 vertices)"},
      {"stride.gltf", with([](json& d) { d["bufferViews"][0]["byteStride"] = 8; }),
       "byteStride 8 does not fit"},
      {"component.gltf", with([](json& d) { d["accessors"][0]["componentType"] = 5123; }),
       "componentType 5123"},
      {"type.gltf", with([](json& d) { d["accessors"][0]["type"] = "VEC2"; }),
       "must be of type VEC3"},
      {"mode.gltf", with([](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 9; }),
       "mode 9 is not a glTF topology"},
      {"partial_triangle.gltf", with([](json& d) { d["accessors"][1]["count"] = 14; }),
       "14 indices are not whole triangles"},
      {"nested.gltf", with([](json& d) { d["accessors"][1]["count"] = json::parse("[[[[1]]]]"); }),
       "count must be a whole number >= 0, got an array"},
      {"triangles.gltf",
       with([](json& d) { d["accessors"][1]["count"] = 3 * (std::uint64_t{1} << 25) + 3; }),
       "more than 33554432 triangles in all"},
      {"negative.gltf", with([](json& d) { d["accessors"][1]["count"] = -1; }),
       "count must be a whole number >= 0"},
      {"cycle.gltf", with([](json& d) { d["nodes"][0]["children"] = {0}; }), "reached twice"},
      {"twice.gltf", with([](json& d) {
         d["scenes"][0]["nodes"] = {0, 0};
       }),
       "reached twice"},
      {"child.gltf", with([](json& d) { d["nodes"][0]["children"] = {5}; }),
       "not a node of the file"},
      {"mesh.gltf", with([](json& d) { d["nodes"][0]["mesh"] = 3; }), "mesh 3 does not exist"},
      {"matrix.gltf", with([](json& d) {
         d["nodes"][0]["matrix"] = {1, 2, 3};
       }),
       "matrix must be an array of 16 numbers"},
      {"rotation.gltf", with([](json& d) {
         d["nodes"][0]["rotation"] = {0, 0, 0, 0};
       }),
       "zero quaternion"},
      {"infinite.gltf", with([](json& d) {
         d["nodes"][0]["matrix"] = {1e308, 0, 0,     0, 0,     1e308, 0,     0,
                                    0,     0, 1e308, 0, 1e308, 1e308, 1e308, 1};
       }),
       "not finite"},
      {"glb_header.glb", std::string("glTF\x02\0\0\0", 8), "ends inside its header"},
      {"glb_chunk.glb",
       std::string("glTF\x02\0\0\0\x20\0\0\0\xff\0\0\0JSON\0\0\0\0\0\0\0\0\0\0\0\0", 32),
       "a chunk runs past the end"},
  };
  test::expectRefused(dir, cases, "glTF: ");
}

}  // namespace
}  // namespace weft
