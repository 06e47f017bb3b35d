#include <weft/scene/JsonReader.h>

#include <cmath>
#include <sstream>

namespace weft {

void JsonReader::fail(const std::string& what) const {
  throw InputError(file_, path_.empty() ? "<root>" : path_, what);
}

std::string JsonReader::describe() const {
  std::string s = value_->dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

JsonReader JsonReader::object() const {
  if (!value_->is_object()) fail("must be an object, got " + describe());
  return *this;
}

bool JsonReader::has(const std::string& key) const {
  object();
  return value_->contains(key);
}

JsonReader JsonReader::at(const std::string& key) const {
  object();
  auto it = value_->find(key);
  if (it == value_->end()) fail("missing required key '" + key + "'");
  return JsonReader(*it, file_, child(key));
}

std::optional<JsonReader> JsonReader::optional(const std::string& key) const {
  object();
  auto it = value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return JsonReader(*it, file_, child(key));
}

void JsonReader::allowOnly(std::initializer_list<const char*> keys) const {
  object();
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    bool known = false;
    for (const char* k : keys) known = known || it.key() == k;
    if (!known) {
      std::string list;
      for (const char* k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
      throw InputError(file_, child(it.key()), "unknown key (expected one of: " + list + ")");
    }
  }
}

std::string JsonReader::oneOf(std::initializer_list<const char*> keys) const {
  object();
  std::string found, list;
  for (const char* k : keys) {
    list += (list.empty() ? "" : ", ") + std::string(k);
    if (value_->contains(k)) {
      if (!found.empty()) fail("has both '" + found + "' and '" + k + "'; give exactly one");
      found = k;
    }
  }
  if (found.empty()) fail("needs exactly one of: " + list);
  return found;
}

std::size_t JsonReader::size() const {
  if (!value_->is_array()) fail("must be an array, got " + describe());
  return value_->size();
}

JsonReader JsonReader::operator[](std::size_t i) const {
  if (i >= size()) fail("needs at least " + std::to_string(i + 1) + " elements");
  return JsonReader((*value_)[i], file_, child(std::to_string(i)));
}

double JsonReader::number(double min, double max) const {
  if (!value_->is_number()) fail("must be a number, got " + describe());
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("must be a finite number");
  if (v < min || v > max) {
    std::ostringstream s;
    s << "must be in [" << min << ", " << max << "], got " << v;
    fail(s.str());
  }
  return v;
}

double JsonReader::positive() const {
  const double v = number();
  if (!(v > 0.0)) {
    std::ostringstream s;
    s << "must be > 0, got " << v;
    fail(s.str());
  }
  return v;
}

int JsonReader::integer(long long min, long long max) const {
  if (!value_->is_number_integer() && !value_->is_number_unsigned())
    fail("must be an integer, got " + describe());
  const long long v = value_->get<long long>();
  if (v < min || v > max)
    fail("must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
         std::to_string(v));
  return static_cast<int>(v);
}

bool JsonReader::boolean() const {
  if (!value_->is_boolean()) fail("must be true or false, got " + describe());
  return value_->get<bool>();
}

std::string JsonReader::string() const {
  if (!value_->is_string()) fail("must be a string, got " + describe());
  return value_->get<std::string>();
}

std::string JsonReader::choice(std::initializer_list<const char*> options) const {
  const std::string s = string();
  std::string list;
  for (const char* o : options) {
    if (s == o) return s;
    list += (list.empty() ? "" : ", ") + std::string(o);
  }
  fail("must be one of " + list + ", got '" + s + "'");
}

std::vector<double> JsonReader::numbers(std::size_t count) const {
  if (size() != count)
    fail("must be an array of " + std::to_string(count) + " numbers, got " + describe());
  std::vector<double> out(count);
  for (std::size_t i = 0; i < count; ++i) out[i] = (*this)[i].number();
  return out;
}

Vec3 JsonReader::vec3() const {
  const auto v = numbers(3);
  return Vec3(v[0], v[1], v[2]);
}

Vec3 JsonReader::unitVec3() const {
  const Vec3 v = vec3();
  if (!(v.norm() > 1e-12)) fail("must be a nonzero vector");
  return v.normalized();
}

std::vector<int> JsonReader::indices(int count) const {
  const std::size_t n = size();
  std::vector<int> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const JsonReader item = (*this)[i];
    if (!item.value().is_number_integer() && !item.value().is_number_unsigned())
      item.fail("must be a vertex index (integer), got " + item.describe());
    const long long v = item.value().get<long long>();
    if (v < 0 || v >= count)
      item.fail("vertex index " + std::to_string(v) + " out of range: the mesh has " +
                std::to_string(count) + " vertices");
    out[i] = static_cast<int>(v);
  }
  return out;
}

double JsonReader::number(const std::string& key, double fallback, double min, double max) const {
  auto v = optional(key);
  return v ? v->number(min, max) : fallback;
}

}  // namespace weft
