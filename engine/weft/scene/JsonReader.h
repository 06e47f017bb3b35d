#pragma once
// Strict, path-aware reading of a JSON document: every access knows its JSON path, so every
// error reads `<file>: <path>: <what>`, and every object is checked for unknown keys.

#include <weft/core/Error.h>
#include <weft/core/Types.h>

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace weft {

class JsonReader {
 public:
  JsonReader(const nlohmann::json& value, std::string file, std::string path)
      : value_(&value), file_(std::move(file)), path_(std::move(path)) {}

  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  const nlohmann::json& value() const { return *value_; }
  [[noreturn]] void fail(const std::string& what) const;

  // Objects.
  JsonReader object() const;  // checks that this is an object
  bool has(const std::string& key) const;
  JsonReader at(const std::string& key) const;  // required key
  std::optional<JsonReader> optional(const std::string& key) const;
  void allowOnly(std::initializer_list<const char*> keys) const;
  // Exactly one of the keys must be present; returns it.
  std::string oneOf(std::initializer_list<const char*> keys) const;

  // Arrays.
  std::size_t size() const;  // checks that this is an array
  JsonReader operator[](std::size_t i) const;

  // Scalars, with inclusive range checks and finite numbers only.
  double number(double min = -std::numeric_limits<double>::infinity(),
                double max = std::numeric_limits<double>::infinity()) const;
  double positive() const;  // > 0
  int integer(long long min, long long max) const;
  bool boolean() const;
  std::string string() const;
  std::string choice(std::initializer_list<const char*> options) const;
  Vec3 vec3() const;
  Vec3 unitVec3() const;                                 // nonzero, normalised
  std::vector<double> numbers(std::size_t count) const;  // fixed-length numeric array
  std::vector<int> indices(int count) const;             // array of integers in [0, count)

  // Convenience: value of an optional key or a default.
  double number(const std::string& key, double fallback, double min, double max) const;

 private:
  std::string child(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  std::string describe() const;  // short rendering of the value for messages
  const nlohmann::json* value_;
  std::string file_, path_;
};

}  // namespace weft
