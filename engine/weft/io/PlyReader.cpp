#include "PlyReader.h"

#include <weft/core/Error.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

namespace weft {
namespace {

// The PLY scalar types, with both spellings of each (the original and the sized one).
enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct ScalarName {
  const char* name;
  Scalar type;
};
const ScalarName kScalarNames[] = {
    {"char", Scalar::Int8},      {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},
    {"uint8", Scalar::UInt8},    {"short", Scalar::Int16},     {"int16", Scalar::Int16},
    {"ushort", Scalar::UInt16},  {"uint16", Scalar::UInt16},   {"int", Scalar::Int32},
    {"int32", Scalar::Int32},    {"uint", Scalar::UInt32},     {"uint32", Scalar::UInt32},
    {"float", Scalar::Float32},  {"float32", Scalar::Float32}, {"double", Scalar::Float64},
    {"float64", Scalar::Float64}};

std::size_t bytesOf(Scalar s) {
  switch (s) {
    case Scalar::Int8:
    case Scalar::UInt8:
      return 1;
    case Scalar::Int16:
    case Scalar::UInt16:
      return 2;
    case Scalar::Int32:
    case Scalar::UInt32:
    case Scalar::Float32:
      return 4;
    case Scalar::Float64:
      return 8;
  }
  return 8;
}

bool isInteger(Scalar s) {
  return s != Scalar::Float32 && s != Scalar::Float64;
}

struct Property {
  std::string name;
  bool list = false;
  Scalar count = Scalar::UInt8;   // a list's length type
  Scalar item = Scalar::Float32;  // the value type (a list's item type)
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

class PlyParser {
 public:
  PlyParser(std::string path, std::string bytes)
      : path_(std::move(path)), bytes_(std::move(bytes)) {}

  TriangleMesh parse() {
    readHeader();
    const Element* vertex = nullptr;
    const Element* face = nullptr;
    for (const Element& e : elements_) {
      if (e.name == "vertex" && !vertex) vertex = &e;
      if (e.name == "face" && !face) face = &e;
    }
    if (!vertex) fail("the header declares no 'vertex' element");
    int axis[3] = {-1, -1, -1};
    for (int p = 0; p < static_cast<int>(vertex->properties.size()); ++p) {
      const Property& prop = vertex->properties[static_cast<std::size_t>(p)];
      for (int c = 0; c < 3; ++c)
        if (prop.name == std::string(1, static_cast<char>('x' + c)) && !prop.list) axis[c] = p;
    }
    for (int c = 0; c < 3; ++c)
      if (axis[c] < 0)
        fail(std::string("the 'vertex' element has no scalar property '") +
             static_cast<char>('x' + c) + "'");
    int indices = -1;
    if (face)
      for (int p = 0; p < static_cast<int>(face->properties.size()); ++p) {
        const Property& prop = face->properties[static_cast<std::size_t>(p)];
        if (prop.list && (prop.name == "vertex_indices" || prop.name == "vertex_index"))
          indices = p;
      }
    if (face && indices < 0) fail("the 'face' element has no 'vertex_indices' list");
    if (face && !isInteger(face->properties[static_cast<std::size_t>(indices)].item))
      fail("the 'face' element's vertex indices are not of an integer type");

    TriangleMesh mesh;
    std::vector<int> tri;
    std::vector<double> values;
    for (const Element& e : elements_) {
      checkCountFits(e);
      if (e.properties.empty()) continue;  // an element without properties takes no bytes
      if (&e == vertex) mesh.vertices.resize(static_cast<Eigen::Index>(e.count), 3);
      for (std::uint64_t k = 0; k < e.count; ++k) {
        for (std::size_t p = 0; p < e.properties.size(); ++p) {
          const Property& prop = e.properties[p];
          if (!prop.list) {
            const double v = readValue(prop.item, e, k);
            if (&e == vertex)
              for (int c = 0; c < 3; ++c)
                if (static_cast<int>(p) == axis[c]) {
                  if (!std::isfinite(v))
                    fail("vertex " + std::to_string(k) + ": coordinate " +
                         static_cast<char>('x' + c) + " is not a finite number");
                  mesh.vertices(static_cast<Eigen::Index>(k), c) = v;
                }
            continue;
          }
          const double length = readValue(prop.count, e, k);
          if (!(length >= 0) || length != std::floor(length))
            fail("element '" + e.name + "' " + std::to_string(k) + ": list length " +
                 std::to_string(length) + " is not a count");
          const auto n = static_cast<std::uint64_t>(length);
          // Every item takes at least one byte (binary) or two (a digit and a separator).
          const std::size_t itemBytes = format_ == Format::Ascii ? 1 : bytesOf(prop.item);
          if (n > remaining() / itemBytes + 1)
            fail("element '" + e.name + "' " + std::to_string(k) + ": a list of " +
                 std::to_string(n) + " items runs past the end of the file");
          const bool corners = &e == face && static_cast<int>(p) == indices;
          values.clear();
          for (std::uint64_t i = 0; i < n; ++i) {
            const double v = readValue(prop.item, e, k);
            if (corners) values.push_back(v);
          }
          if (!corners) continue;
          if (n < 3)
            fail("face " + std::to_string(k) + " has " + std::to_string(n) +
                 " corners (a face needs at least 3)");
          for (std::size_t j = 1; j + 1 < values.size(); ++j)
            for (double corner : {values[0], values[j], values[j + 1]}) {
              if (corner < 0 || corner >= static_cast<double>(vertex->count))
                fail("face " + std::to_string(k) + ": vertex index " +
                     std::to_string(static_cast<long long>(corner)) + " is out of range (" +
                     std::to_string(vertex->count) + " vertices)");
              tri.push_back(static_cast<int>(corner));
            }
        }
      }
    }
    mesh.triangles =
        Eigen::Map<TriangleIndices>(tri.data(), static_cast<Eigen::Index>(tri.size() / 3), 3);
    return mesh;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_, "mesh", "PLY: " + what);
  }

  // The header, up to and including its `end_header` line; pos_ is left at the body's first
  // byte.
  void readHeader() {
    bool first = true, formatSeen = false;
    for (int lineNumber = 1;; ++lineNumber) {
      if (pos_ >= bytes_.size()) fail("the header has no 'end_header' line (a truncated file?)");
      std::size_t end = bytes_.find('\n', pos_);
      if (end == std::string::npos) end = bytes_.size();
      std::string line = bytes_.substr(pos_, end - pos_);
      pos_ = end + 1;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const std::string where = "header line " + std::to_string(lineNumber) + ": ";
      std::istringstream fields(line);
      std::string keyword;
      fields >> keyword;
      if (first) {
        if (keyword != "ply" || fields >> keyword) fail("the file does not begin with 'ply'");
        first = false;
        continue;
      }
      if (keyword == "end_header") {
        if (!formatSeen) fail("the header has no 'format' line");
        if (pos_ > bytes_.size()) pos_ = bytes_.size();
        return;
      }
      if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
      std::vector<std::string> words{std::istream_iterator<std::string>(fields),
                                     std::istream_iterator<std::string>()};
      if (keyword == "format") {
        if (words.size() != 2 || words[1] != "1.0")
          fail(where + "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
        if (words[0] == "ascii")
          format_ = Format::Ascii;
        else if (words[0] == "binary_little_endian")
          format_ = Format::BinaryLittleEndian;
        else if (words[0] == "binary_big_endian")
          format_ = Format::BinaryBigEndian;
        else
          fail(where + "unknown format '" + words[0] + "'");
        formatSeen = true;
      } else if (keyword == "element") {
        Element e;
        const char* digits = words.size() == 2 ? words[1].data() : nullptr;
        if (!digits || std::from_chars(digits, digits + words[1].size(), e.count).ptr !=
                           digits + words[1].size())
          fail(where + "expected 'element NAME COUNT'");
        if (e.count > static_cast<std::uint64_t>(std::numeric_limits<int>::max() / 3))
          fail(where + "element '" + words[0] + "' has too many items (" + words[1] + ")");
        e.name = words[0];
        elements_.push_back(std::move(e));
      } else if (keyword == "property") {
        if (elements_.empty()) fail(where + "a property before any element");
        Property prop;
        const bool list = !words.empty() && words[0] == "list";
        if (words.size() != (list ? 4u : 2u))
          fail(where + "expected 'property TYPE NAME' or 'property list COUNT-TYPE TYPE NAME'");
        prop.list = list;
        if (list && (!scalar(words[1], prop.count) || !isInteger(prop.count)))
          fail(where + "'" + words[1] + "' is not an integer type for a list's length");
        if (!scalar(words[list ? 2 : 0], prop.item))
          fail(where + "'" + words[list ? 2 : 0] + "' is not a PLY type");
        prop.name = words.back();
        elements_.back().properties.push_back(std::move(prop));
      } else {
        fail(where + "unknown keyword '" + keyword + "'");
      }
    }
  }

  static bool scalar(const std::string& name, Scalar& out) {
    for (const ScalarName& s : kScalarNames)
      if (name == s.name) {
        out = s.type;
        return true;
      }
    return false;
  }

  std::size_t remaining() const { return bytes_.size() - pos_; }

  // Refuses an element whose stated count cannot fit in the bytes left, before any of it is
  // read or allocated: each item takes its scalars' bytes (binary) or two characters per value.
  void checkCountFits(const Element& e) const {
    std::size_t least = 0;
    for (const Property& p : e.properties)
      least += format_ == Format::Ascii ? 2 : bytesOf(p.list ? p.count : p.item);
    if (least > 0 && e.count > (remaining() + 1) / least)
      fail("element '" + e.name + "' states " + std::to_string(e.count) +
           " items, more than the rest of the file can hold");
  }

  double readValue(Scalar type, const Element& e, std::uint64_t k) {
    return format_ == Format::Ascii ? readText(type, e, k) : readBinary(type, e, k);
  }

  [[noreturn]] void endsInside(const Element& e, std::uint64_t k) const {
    fail("the file ends inside element '" + e.name + "' " + std::to_string(k));
  }

  double readBinary(Scalar type, const Element& e, std::uint64_t k) {
    const std::size_t n = bytesOf(type);
    if (remaining() < n) endsInside(e, k);
    unsigned char raw[8];
    std::memcpy(raw, bytes_.data() + pos_, n);
    pos_ += n;
    const bool swap = (format_ == Format::BinaryBigEndian) == hostIsLittleEndian();
    if (swap)
      for (std::size_t i = 0; i < n / 2; ++i) std::swap(raw[i], raw[n - 1 - i]);
    switch (type) {
      case Scalar::Int8:
        return static_cast<double>(static_cast<std::int8_t>(raw[0]));
      case Scalar::UInt8:
        return static_cast<double>(raw[0]);
      case Scalar::Int16:
        return static_cast<double>(as<std::int16_t>(raw));
      case Scalar::UInt16:
        return static_cast<double>(as<std::uint16_t>(raw));
      case Scalar::Int32:
        return static_cast<double>(as<std::int32_t>(raw));
      case Scalar::UInt32:
        return static_cast<double>(as<std::uint32_t>(raw));
      case Scalar::Float32:
        return static_cast<double>(as<float>(raw));
      case Scalar::Float64:
        return as<double>(raw);
    }
    return 0.0;
  }

  template <class T>
  static T as(const unsigned char* raw) {
    T value;
    std::memcpy(&value, raw, sizeof value);
    return value;
  }

  static bool hostIsLittleEndian() {
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
  }

  // The next whitespace-separated token, parsed as `type`: an integer type takes a whole
  // number within its range, a float type any number a double holds (`nan` and `inf` included;
  // coordinates are checked to be finite where they are used).
  double readText(Scalar type, const Element& e, std::uint64_t k) {
    const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    while (pos_ < bytes_.size() && space(bytes_[pos_])) ++pos_;
    if (pos_ >= bytes_.size()) endsInside(e, k);
    const std::size_t begin = pos_;
    while (pos_ < bytes_.size() && !space(bytes_[pos_])) ++pos_;
    const char* first = bytes_.data() + begin;
    const char* last = bytes_.data() + pos_;
    const auto bad = [&](const std::string& why) {
      fail("element '" + e.name + "' " + std::to_string(k) + ": '" +
           std::string(first, std::min<std::size_t>(static_cast<std::size_t>(last - first), 40)) +
           "' " + why);
    };
    if (isInteger(type)) {
      long long value = 0;
      const auto [end, ec] = std::from_chars(first, last, value);
      if (ec != std::errc() || end != last) bad("is not a whole number");
      const std::size_t bits = 8 * bytesOf(type);
      const bool isSigned = type == Scalar::Int8 || type == Scalar::Int16 || type == Scalar::Int32;
      const long long lo = isSigned ? -(1LL << (bits - 1)) : 0;
      const long long hi = isSigned ? (1LL << (bits - 1)) - 1 : (1LL << bits) - 1;
      if (value < lo || value > hi) bad("is out of the range of its type");
      return static_cast<double>(value);
    }
    double value = 0.0;
    const auto [end, ec] = std::from_chars(first, last, value);
    if (ec == std::errc::result_out_of_range) bad("is out of the range of a double");
    if (ec != std::errc() || end != last) bad("is not a number");
    return value;  // a float property's text is read at double precision, as written
  }

  std::string path_;
  std::string bytes_;
  std::size_t pos_ = 0;
  Format format_ = Format::Ascii;
  std::vector<Element> elements_;
};

}  // namespace

TriangleMesh readPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "mesh", "cannot open the file");
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return PlyParser(path, std::move(bytes)).parse();
}

}  // namespace weft
