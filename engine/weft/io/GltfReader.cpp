#include "GltfReader.h"

#include <weft/core/Error.h>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <vector>

namespace weft {
namespace {

using nlohmann::json;

// More vertices than this in all placed primitives together is refused: far beyond what Weft
// simulates, and it bounds what a small file with many instances can make the reader allocate.
constexpr std::uint64_t kMaxVertices = std::uint64_t{1} << 24;
// The same for triangles: primitives can share one large index accessor, so the file's size
// alone does not bound the work.
constexpr std::uint64_t kMaxTriangles = std::uint64_t{1} << 25;

// glTF 2.0 componentType codes (glTF 2.0 spec, "Accessor Data Types").
constexpr int kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126;

// GLB container (glTF 2.0 spec, "Binary glTF Layout").
constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;

// A value for a message: a scalar as written, an array or object by its kind (dumping one would
// recurse as deep as the file nests it).
std::string describe(const json& v) {
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  const std::string text = v.dump();
  return text.size() > 40 ? text.substr(0, 40) + "..." : text;
}

std::uint32_t littleEndian32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i)
    v = (v << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
  return v;
}

class GltfParser {
 public:
  explicit GltfParser(std::string path) : path_(std::move(path)) {}

  TriangleMesh parse() {
    std::string bytes = readFile(path_, std::nullopt);
    std::string text = bytes;
    if (bytes.size() >= 4 && littleEndian32(bytes, 0) == kGlbMagic) text = splitGlb(bytes);
    try {
      doc_ = json::parse(text);
    } catch (const json::exception& e) {
      fail(std::string("not valid JSON: ") + e.what());
    }
    if (!doc_.is_object()) fail("the document is not a JSON object");
    const json* asset = member(doc_, "asset");
    const json* version = asset ? member(*asset, "version") : nullptr;
    if (!version || !version->is_string()) fail("asset.version is missing (not a glTF file?)");
    const std::string v = version->get<std::string>();
    if (v.rfind("2.", 0) != 0)
      fail("asset.version is '" + v + "'; only glTF 2.0 is read (re-export as glTF 2.0)");
    if (const json* required = member(doc_, "extensionsRequired"); required && required->is_array())
      for (const json& name : *required)
        fail("the file requires the extension " +
             (name.is_string() ? name.get<std::string>() : describe(name)) +
             ", which Weft does not read");
    buffers_.resize(arrayOf("buffers").size());
    return assemble();
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_, "mesh", "glTF: " + what);
  }

  static const json* member(const json& object, const char* key) {
    if (!object.is_object()) return nullptr;
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  // The top-level array `name` (empty when absent).
  const json& arrayOf(const char* name) const {
    static const json empty = json::array();
    const json* a = member(doc_, name);
    if (!a) return empty;
    if (!a->is_array()) fail(std::string(name) + " is not an array");
    return *a;
  }

  // The object `name`[index], refused when out of range or not an object.
  const json& item(const char* name, std::uint64_t index) const {
    const json& a = arrayOf(name);
    if (index >= a.size())
      fail(std::string(name) + "[" + std::to_string(index) + "] does not exist (" +
           std::to_string(a.size()) + " in the file)");
    const json& o = a[static_cast<std::size_t>(index)];
    if (!o.is_object())
      fail(std::string(name) + "[" + std::to_string(index) + "] is not an object");
    return o;
  }

  // A whole number >= 0 (at most 2^53) at object.key; `fallback` when absent, if given.
  std::uint64_t count(const json& object, const char* key, const std::string& where,
                      std::optional<std::uint64_t> fallback = std::nullopt) const {
    const json* v = member(object, key);
    if (!v) {
      if (fallback) return *fallback;
      fail(where + "." + key + " is missing");
    }
    if (v->is_number_unsigned() && v->get<std::uint64_t>() <= (std::uint64_t{1} << 53))
      return v->get<std::uint64_t>();
    fail(where + "." + key + " must be a whole number >= 0, got " + describe(*v));
  }

  // `n` finite numbers at object.key, or nothing when absent.
  std::optional<std::vector<double>> numbers(const json& object, const char* key, std::size_t n,
                                             const std::string& where) const {
    const json* v = member(object, key);
    if (!v) return std::nullopt;
    if (!v->is_array() || v->size() != n)
      fail(where + "." + key + " must be an array of " + std::to_string(n) + " numbers");
    std::vector<double> out;
    for (const json& x : *v) {
      if (!x.is_number() || !std::isfinite(x.get<double>()))
        fail(where + "." + key + " must hold finite numbers, got " + describe(x));
      out.push_back(x.get<double>());
    }
    return out;
  }

  // Reads a whole regular file, or its first `limit` bytes.
  std::string readFile(const std::string& file, std::optional<std::uint64_t> limit) const {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) fail("'" + file + "' is not a readable file");
    std::ifstream in(file, std::ios::binary);
    if (!in) fail("cannot open '" + file + "'");
    if (!limit) return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    // Never more than the file holds: a stated length is not trusted with an allocation.
    const std::uint64_t size = std::filesystem::file_size(file, ec);
    std::string data(static_cast<std::size_t>(ec ? 0 : std::min(*limit, size)), '\0');
    in.read(data.data(), static_cast<std::streamsize>(data.size()));
    data.resize(static_cast<std::size_t>(in.gcount()));
    return data;
  }

  // A GLB container: checks its header and chunk lengths, keeps the BIN chunk as buffer 0's
  // bytes and returns the JSON chunk.
  std::string splitGlb(const std::string& bytes) {
    if (bytes.size() < 20) fail("GLB: the file ends inside its header");
    if (littleEndian32(bytes, 4) != 2)
      fail("GLB: container version " + std::to_string(littleEndian32(bytes, 4)) +
           " (only 2 is read)");
    const std::uint64_t total = littleEndian32(bytes, 8);
    if (total > bytes.size())
      fail("GLB: the header states " + std::to_string(total) + " bytes, the file has " +
           std::to_string(bytes.size()));
    std::string jsonText;
    bool first = true;
    for (std::uint64_t at = 12; at + 8 <= total;) {
      const std::uint64_t length = littleEndian32(bytes, static_cast<std::size_t>(at));
      const std::uint32_t type = littleEndian32(bytes, static_cast<std::size_t>(at + 4));
      if (at + 8 + length > total) fail("GLB: a chunk runs past the end of the file");
      const std::string data =
          bytes.substr(static_cast<std::size_t>(at + 8), static_cast<std::size_t>(length));
      if (first && type != kJsonChunk) fail("GLB: the first chunk is not JSON");
      if (first)
        jsonText = data;
      else if (type == kBinChunk && !glbBin_)
        glbBin_ = data;
      first = false;
      at += 8 + length;
    }
    if (first) fail("GLB: the file has no JSON chunk");
    return jsonText;
  }

  static std::optional<std::string> decodeBase64(const std::string& text, std::size_t from) {
    std::string out;
    std::uint32_t acc = 0;
    int bits = 0;
    std::size_t i = from;
    for (; i < text.size() && text[i] != '='; ++i) {
      const char c = text[i];
      int v;
      if (c >= 'A' && c <= 'Z')
        v = c - 'A';
      else if (c >= 'a' && c <= 'z')
        v = c - 'a' + 26;
      else if (c >= '0' && c <= '9')
        v = c - '0' + 52;
      else if (c == '+')
        v = 62;
      else if (c == '/')
        v = 63;
      else
        return std::nullopt;
      acc = ((acc << 6) | static_cast<std::uint32_t>(v)) & 0xFFFFFF;
      bits += 6;
      if (bits >= 8) {
        bits -= 8;
        out += static_cast<char>((acc >> bits) & 0xFF);
      }
    }
    for (; i < text.size(); ++i)
      if (text[i] != '=') return std::nullopt;
    return out;
  }

  // A relative URI's path: %XX escapes decoded (glTF 2.0 spec, "URIs").
  std::string uriPath(const std::string& uri) const {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
      if (uri[i] == '%' && i + 2 < uri.size() &&
          std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
          std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
        out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
        i += 2;
      } else {
        out += uri[i];
      }
    }
    return out;
  }

  // The bytes of buffers[index], loaded once: a data URI, a file beside the glTF, or the GLB's
  // BIN chunk; at least its stated byteLength long.
  const std::string& buffer(std::uint64_t index) {
    const json& b = item("buffers", index);
    const std::string where = "buffers[" + std::to_string(index) + "]";
    std::optional<std::string>& cached = buffers_[static_cast<std::size_t>(index)];
    if (cached) return *cached;
    const std::uint64_t length = count(b, "byteLength", where);
    const json* uri = member(b, "uri");
    if (!uri) {
      if (index != 0 || !glbBin_)
        fail(where + " has no uri and the file carries no GLB binary chunk");
      cached = *glbBin_;
    } else if (!uri->is_string()) {
      fail(where + ".uri is not a string");
    } else if (const std::string u = uri->get<std::string>(); u.rfind("data:", 0) == 0) {
      const auto comma = u.find(";base64,");
      if (comma == std::string::npos) fail(where + ".uri is a data URI without ';base64,'");
      cached = decodeBase64(u, comma + 8);
      if (!cached) fail(where + ".uri is not valid base64");
    } else {
      const std::filesystem::path file = std::filesystem::path(path_).parent_path() / uriPath(u);
      cached = readFile(file.string(), length);
    }
    if (cached->size() < length)
      fail(where + " states " + std::to_string(length) + " bytes, its data has " +
           std::to_string(cached->size()));
    cached->resize(static_cast<std::size_t>(length));
    return *cached;
  }

  // Accessor `index` as `components` values per element, checked to be `type` and one of the
  // `componentTypes`, each value converted to double. Every byte it names is checked first.
  std::vector<double> accessor(std::uint64_t index, const char* type, std::size_t components,
                               std::initializer_list<int> componentTypes, const std::string& use) {
    const json& a = item("accessors", index);
    const std::string where = "accessors[" + std::to_string(index) + "] (" + use + ")";
    const json* t = member(a, "type");
    if (!t || !t->is_string() || t->get<std::string>() != type)
      fail(where + " must be of type " + type);
    const std::uint64_t componentType = count(a, "componentType", where);
    bool known = false;
    for (int c : componentTypes) known = known || componentType == static_cast<std::uint64_t>(c);
    if (!known)
      fail(where + " has componentType " + std::to_string(componentType) +
           ", not one Weft reads there");
    if (member(a, "sparse")) fail(where + " is sparse, which Weft does not read");
    const std::uint64_t n = count(a, "count", where);
    if (!member(a, "bufferView")) fail(where + " has no bufferView");
    const std::uint64_t viewIndex = count(a, "bufferView", where);
    const json& view = item("bufferViews", viewIndex);
    const std::string viewWhere = "bufferViews[" + std::to_string(viewIndex) + "]";
    const std::string& data = buffer(count(view, "buffer", viewWhere));
    const std::uint64_t viewOffset = count(view, "byteOffset", viewWhere, 0);
    const std::uint64_t viewLength = count(view, "byteLength", viewWhere);
    if (viewOffset > data.size() || viewLength > data.size() - viewOffset)
      fail(viewWhere + " runs past the end of its buffer");
    const std::uint64_t size = componentType == kUnsignedByte    ? 1
                               : componentType == kUnsignedShort ? 2
                                                                 : 4;
    const std::uint64_t elementSize = size * components;
    const std::uint64_t stride = count(view, "byteStride", viewWhere, elementSize);
    if (stride < elementSize || stride > 252)
      fail(viewWhere + ".byteStride " + std::to_string(stride) + " does not fit " + where);
    const std::uint64_t offset = count(a, "byteOffset", where, 0);
    if (n > 0 && (n - 1 > viewLength / stride || offset > viewLength ||
                  (n - 1) * stride + elementSize > viewLength - offset))
      fail(where + ": " + std::to_string(n) + " elements run past the end of " + viewWhere);
    std::vector<double> out(static_cast<std::size_t>(n * components));
    const char* base = data.data() + viewOffset + offset;
    for (std::uint64_t e = 0; e < n; ++e)
      for (std::size_t c = 0; c < components; ++c) {
        const char* at = base + e * stride + c * size;
        double v = 0.0;
        if (componentType == kFloat) {
          float f;
          std::memcpy(&f, at, 4);
          v = f;
        } else if (componentType == kUnsignedInt) {
          std::uint32_t u;
          std::memcpy(&u, at, 4);
          v = u;
        } else if (componentType == kUnsignedShort) {
          std::uint16_t u;
          std::memcpy(&u, at, 2);
          v = u;
        } else {
          v = static_cast<unsigned char>(*at);
        }
        out[static_cast<std::size_t>(e * components + c)] = v;
      }
    return out;
  }

  // A node's local transform: its matrix, or translation * rotation * scale (glTF 2.0 spec,
  // "Transformations").
  Eigen::Matrix4d localTransform(const json& node, const std::string& where) const {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (const auto matrix = numbers(node, "matrix", 16, where)) {
      m = Eigen::Map<const Eigen::Matrix4d>(matrix->data());  // column-major, as glTF stores it
      return m;
    }
    Eigen::Affine3d t = Eigen::Affine3d::Identity();
    if (const auto v = numbers(node, "translation", 3, where))
      t.translate(Eigen::Vector3d((*v)[0], (*v)[1], (*v)[2]));
    if (const auto q = numbers(node, "rotation", 4, where)) {
      Eigen::Quaterniond r((*q)[3], (*q)[0], (*q)[1], (*q)[2]);  // glTF stores x, y, z, w
      if (!(r.norm() > 0.0)) fail(where + ".rotation is not a rotation (zero quaternion)");
      t.rotate(r.normalized());
    }
    if (const auto s = numbers(node, "scale", 3, where))
      t.scale(Eigen::Vector3d((*s)[0], (*s)[1], (*s)[2]));
    return t.matrix();
  }

  // The global transform of every node of the file's scene that references each mesh, in
  // depth-first order (an explicit stack: a long chain of nodes must not exhaust the C stack).
  std::vector<std::vector<Eigen::Matrix4d>> placements(std::size_t meshCount) const {
    std::vector<std::vector<Eigen::Matrix4d>> out(meshCount);
    const json& scenes = arrayOf("scenes");
    if (scenes.empty()) return out;
    const std::uint64_t sceneIndex = count(doc_, "scene", "document", 0);
    const json& scene = item("scenes", sceneIndex);
    const json* roots = member(scene, "nodes");
    if (!roots) return out;
    if (!roots->is_array())
      fail("scenes[" + std::to_string(sceneIndex) + "].nodes is not an array");
    const std::size_t nodeCount = arrayOf("nodes").size();
    std::vector<bool> reached(nodeCount, false);
    std::vector<std::pair<std::uint64_t, Eigen::Matrix4d>> stack;
    const auto pushChildren = [&](const json& list, const Eigen::Matrix4d& parent,
                                  const std::string& where) {
      for (auto it = list.rbegin(); it != list.rend(); ++it) {
        if (!it->is_number_unsigned() || it->get<std::uint64_t>() >= nodeCount)
          fail(where + " names " + describe(*it) + ", not a node of the file");
        stack.emplace_back(it->get<std::uint64_t>(), parent);
      }
    };
    pushChildren(*roots, Eigen::Matrix4d::Identity(),
                 "scenes[" + std::to_string(sceneIndex) + "].nodes");
    while (!stack.empty()) {
      const auto [index, parent] = stack.back();
      stack.pop_back();
      const std::string where = "nodes[" + std::to_string(index) + "]";
      if (reached[static_cast<std::size_t>(index)])
        fail(where + " is reached twice (glTF nodes form a tree)");
      reached[static_cast<std::size_t>(index)] = true;
      const json& node = item("nodes", index);
      const Eigen::Matrix4d global = parent * localTransform(node, where);
      if (member(node, "mesh")) {
        const std::uint64_t mesh = count(node, "mesh", where);
        if (mesh >= meshCount) fail(where + ".mesh " + std::to_string(mesh) + " does not exist");
        out[static_cast<std::size_t>(mesh)].push_back(global);
      }
      if (const json* children = member(node, "children")) {
        if (!children->is_array()) fail(where + ".children is not an array");
        pushChildren(*children, global, where + ".children");
      }
    }
    return out;
  }

  // The triangles of a primitive as corner triples: `indices` (or 0, 1, 2, ... without them)
  // read as a list, strip or fan (glTF 2.0 spec, "Primitive Topologies").
  std::vector<std::array<int, 3>> triangles(const std::vector<double>& indices, std::uint64_t mode,
                                            const std::string& where) const {
    std::vector<std::array<int, 3>> out;
    const std::size_t n = indices.size();
    const auto at = [&](std::size_t i) { return static_cast<int>(indices[i]); };
    if (mode == 4) {
      if (n % 3 != 0) fail(where + ": " + std::to_string(n) + " indices are not whole triangles");
      for (std::size_t i = 0; i + 2 < n; i += 3) out.push_back({at(i), at(i + 1), at(i + 2)});
    } else if (mode == 5) {
      for (std::size_t i = 0; i + 2 < n; ++i)
        out.push_back(i % 2 == 0 ? std::array<int, 3>{at(i), at(i + 1), at(i + 2)}
                                 : std::array<int, 3>{at(i), at(i + 2), at(i + 1)});
    } else {
      for (std::size_t i = 1; i + 1 < n; ++i) out.push_back({at(i), at(i + 1), at(0)});
    }
    return out;
  }

  TriangleMesh assemble() {
    const json& meshes = arrayOf("meshes");
    const auto placed = placements(meshes.size());
    TriangleMesh mesh;
    mesh.vertices.resize(0, 3);
    std::uint64_t total = 0, triangleTotal = 0;
    for (std::size_t k = 0; k < meshes.size(); ++k) {
      const std::string meshWhere = "meshes[" + std::to_string(k) + "]";
      const json& m = item("meshes", k);
      const json* primitives = member(m, "primitives");
      if (!primitives || !primitives->is_array()) fail(meshWhere + ".primitives is not an array");
      std::vector<Eigen::Matrix4d> instances = placed[k];
      if (instances.empty()) instances.push_back(Eigen::Matrix4d::Identity());
      for (std::size_t p = 0; p < primitives->size(); ++p) {
        const std::string where = meshWhere + ".primitives[" + std::to_string(p) + "]";
        const json& primitive = (*primitives)[p];
        const std::uint64_t mode = count(primitive, "mode", where, 4);
        if (mode > 6) fail(where + ".mode " + std::to_string(mode) + " is not a glTF topology");
        if (mode < 4) continue;  // points and lines: no surface
        const json* attributes = member(primitive, "attributes");
        if (!attributes || !member(*attributes, "POSITION"))
          fail(where + " has no POSITION attribute");
        const std::vector<double> positions = accessor(
            count(*attributes, "POSITION", where + ".attributes"), "VEC3", 3, {kFloat}, "POSITION");
        const std::size_t vertexCount = positions.size() / 3;
        total += vertexCount * instances.size();
        if (total > kMaxVertices)
          fail("more than " + std::to_string(kMaxVertices) +
               " vertices in all, beyond what Weft simulates");
        // The triangles this primitive will make, counted before its indices are read.
        const std::uint64_t cornerCount =
            member(primitive, "indices")
                ? count(item("accessors", count(primitive, "indices", where)), "count",
                        where + " indices")
                : vertexCount;
        const std::uint64_t perInstance = mode == 4         ? cornerCount / 3
                                          : cornerCount > 2 ? cornerCount - 2
                                                            : 0;
        if (perInstance > kMaxTriangles ||
            perInstance * instances.size() > kMaxTriangles - triangleTotal)
          fail("more than " + std::to_string(kMaxTriangles) +
               " triangles in all, beyond what Weft simulates");
        triangleTotal += perInstance * instances.size();
        std::vector<double> indices;
        if (member(primitive, "indices")) {
          indices = accessor(count(primitive, "indices", where), "SCALAR", 1,
                             {kUnsignedByte, kUnsignedShort, kUnsignedInt}, "indices");
        } else {
          for (std::size_t i = 0; i < vertexCount; ++i) indices.push_back(static_cast<double>(i));
        }
        for (double i : indices)
          if (i >= static_cast<double>(vertexCount))
            fail(where + ": vertex index " + std::to_string(static_cast<std::uint64_t>(i)) +
                 " is out of range (" + std::to_string(vertexCount) + " vertices)");
        const auto corners = triangles(indices, mode, where);
        for (const Eigen::Matrix4d& placement : instances) {
          TriangleMesh part;
          part.vertices.resize(static_cast<Eigen::Index>(vertexCount), 3);
          for (std::size_t i = 0; i < vertexCount; ++i) {
            const Eigen::Vector4d x(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2],
                                    1.0);
            part.vertices.row(static_cast<Eigen::Index>(i)) = (placement * x).head<3>().transpose();
          }
          // A mirroring placement would turn the surface inside out: corners listed the other
          // way round keep its outward side.
          const bool mirrored = placement.topLeftCorner<3, 3>().determinant() < 0.0;
          part.triangles.resize(static_cast<Eigen::Index>(corners.size()), 3);
          for (std::size_t t = 0; t < corners.size(); ++t) {
            const auto& c = corners[t];
            part.triangles.row(static_cast<Eigen::Index>(t)) << c[0], mirrored ? c[2] : c[1],
                mirrored ? c[1] : c[2];
          }
          if (!part.vertices.allFinite()) fail(where + ": a placed vertex is not finite");
          mesh.append(part);
        }
      }
    }
    return mesh;
  }

  std::string path_;
  json doc_;
  std::optional<std::string> glbBin_;
  std::vector<std::optional<std::string>> buffers_;
};

}  // namespace

TriangleMesh readGltf(const std::string& path) {
  return GltfParser(path).parse();
}

}  // namespace weft
