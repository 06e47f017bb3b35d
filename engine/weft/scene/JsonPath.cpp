#include <weft/scene/JsonPath.h>

#include <cstdlib>
#include <sstream>

namespace weft {

std::vector<std::string> splitJsonPath(const std::string& path) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(path);
  while (std::getline(in, part, '.')) parts.push_back(part);
  return parts;
}

namespace {

// A value in an error message (bytes that are not UTF-8 replaced, so that writing it cannot throw).
std::string shown(const nlohmann::json& value) {
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// An array index: digits only, and at most 18 of them (no array is longer; std::stoull would
// throw out_of_range past 2^64, found by the scene fuzzer in a task's parameter path).
bool parseIndex(const std::string& s, std::size_t& out) {
  if (s.empty() || s.size() > 18 || s.find_first_not_of("0123456789") != std::string::npos)
    return false;
  out = std::stoull(s);
  return true;
}

// One step down a path: an object's member or an array's element, or null where there is none.
template <class J>
J* child(J& node, const std::string& part) {
  if (node.is_object()) {
    auto it = node.find(part);
    return it == node.end() ? nullptr : &*it;
  }
  std::size_t i;
  if (node.is_array() && parseIndex(part, i) && i < node.size()) return &node[i];
  return nullptr;
}

template <class J>
J* walk(J& doc, const std::vector<std::string>& parts, std::size_t count) {
  J* node = &doc;
  for (std::size_t k = 0; k < count && node; ++k) node = child(*node, parts[k]);
  return node;
}

}  // namespace

const nlohmann::json* findJsonPath(const nlohmann::json& doc, const std::string& path) {
  const auto parts = splitJsonPath(path);
  return walk(doc, parts, parts.size());
}

nlohmann::json* findJsonPath(nlohmann::json& doc, const std::string& path) {
  const auto parts = splitJsonPath(path);
  return walk(doc, parts, parts.size());
}

bool isValidUtf8(const std::string& text) {
  try {
    (void)nlohmann::json(text).dump();
    return true;
  } catch (const nlohmann::json::type_error&) {
    return false;
  }
}

nlohmann::json parseOverrideValue(const std::string& text) {
  nlohmann::json v = nlohmann::json::parse(text, nullptr, false);
  if (!v.is_discarded()) return v;
  if (text.find(',') != std::string::npos) {
    nlohmann::json arr = nlohmann::json::array();
    std::istringstream in(text);
    std::string item;
    bool allNumbers = true;
    while (std::getline(in, item, ',')) {
      nlohmann::json n = nlohmann::json::parse(item, nullptr, false);
      if (n.is_discarded() || !n.is_number()) allNumbers = false;
      arr.push_back(n);
    }
    if (allNumbers) return arr;
  }
  return text;
}

std::string createJsonPathObjects(nlohmann::json& doc, const std::string& path) {
  const auto parts = splitJsonPath(path);
  if (parts.size() < 2) return "";
  nlohmann::json* node = &doc;
  std::size_t k = 0;
  for (; k + 1 < parts.size(); ++k) {
    nlohmann::json* next = child(*node, parts[k]);
    if (!next && node->is_object()) break;  // the first absent object
    if (!next) return "";
    node = next;
  }
  if (k + 1 == parts.size() || !node->is_object()) return "";  // every parent exists
  std::size_t unused;
  for (std::size_t j = k; j < parts.size(); ++j)
    if (parts[j].empty() || parseIndex(parts[j], unused)) return "";
  std::string created;
  for (std::size_t j = 0; j <= k; ++j) created += (j ? "." : "") + parts[j];
  for (; k + 1 < parts.size(); ++k) node = &((*node)[parts[k]] = nlohmann::json::object());
  return created;
}

std::string setJsonPath(nlohmann::json& doc, const std::string& path, const nlohmann::json& value) {
  const auto parts = splitJsonPath(path);
  if (parts.empty() || path.empty()) return "empty path";
  for (const auto& p : parts)
    if (p.empty()) return "malformed path (empty component)";
  nlohmann::json* parent = walk(doc, parts, parts.size() - 1);
  if (!parent) return "unknown path (no such object in the scene)";
  const std::string& last = parts.back();
  nlohmann::json* target = nullptr;
  if (parent->is_object()) {
    auto it = parent->find(last);
    if (it == parent->end()) {
      (*parent)[last] = value;  // a key the file omitted; the validator decides if it is known
      return "";
    }
    target = &*it;
  } else if (parent->is_array()) {
    std::size_t i;
    if (!parseIndex(last, i) || i >= parent->size()) return "unknown path (index out of range)";
    target = &(*parent)[i];
  } else {
    // (A one-part path's parent is the document itself, which is not an object when the file
    // is not a scene; found by the scene fuzzer, which read parts[-1] here.)
    const std::string parentName = parts.size() >= 2 ? parts[parts.size() - 2] : "the document";
    return "unknown path (" + parentName + " is not an object or array)";
  }
  if (target->is_number() && !value.is_number()) return "must be a number, got " + shown(value);
  if (target->is_array() && (!value.is_array() || value.size() != target->size()))
    return "must be an array of " + std::to_string(target->size()) + " values, got " + shown(value);
  if (target->is_object() || (target->is_array() && !value.is_array()))
    return "is not a scalar or vector";
  *target = value;
  return "";
}

}  // namespace weft
