#include "ScriptCall.h"

#include "EditorApp.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <stdexcept>

namespace weft::editor {

void ScriptCall::fail(const std::string& what, int code) {
  failed_ = true;
  failure_ = what;
  exitCode_ = code;
}

std::optional<bool> ScriptCall::checkOutcome(const nlohmann::json& options,
                                             const std::string& error,
                                             const std::string& succeeded) {
  if (options.contains("expect_error")) {
    const std::string expected = options["expect_error"].get<std::string>();
    if (error.empty())
      fail("expected an error containing \"" + expected + "\", but " + succeeded);
    else if (error.find(expected) == std::string::npos)
      fail("expected an error containing \"" + expected + "\", got: " + error);
    return !failed_;
  }
  if (!error.empty()) {
    fail(error);
    return false;
  }
  return std::nullopt;
}

bool ScriptCall::reportOutcome(const std::string& error, const std::string& done) {
  app.report(error.empty() ? done : error, !error.empty());
  return checkOutcome(action, error, "it succeeded").value_or(true);
}

float ScriptCall::aspect() const {
  return float(app.viewportWidth()) / float(std::max(app.viewportHeight(), 1));
}

double scriptClock() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

Vec3 vec3Of(const nlohmann::json& j, const char* what) {
  if (!j.is_array() || j.size() != 3)
    throw std::invalid_argument(std::string(what) + " must be [x, y, z]");
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

int intOf(const nlohmann::json& j) {
  constexpr double lo = std::numeric_limits<int>::min(), hi = std::numeric_limits<int>::max();
  const bool whole = j.is_number_integer() ||
                     (j.is_number_float() && std::trunc(j.get<double>()) == j.get<double>());
  if (!whole || !(j.get<double>() >= lo && j.get<double>() <= hi))
    throw std::invalid_argument("expected a whole number from " + std::to_string(int(lo)) + " to " +
                                std::to_string(int(hi)) + ", got " + j.dump());
  return j.is_number_integer() ? int(j.get<std::int64_t>()) : int(j.get<double>());
}

std::vector<int> intsOf(const nlohmann::json& j) {
  if (!j.is_array())
    throw std::invalid_argument("expected a list of whole numbers, got " + j.dump());
  std::vector<int> out;
  out.reserve(j.size());
  for (const nlohmann::json& item : j) out.push_back(intOf(item));
  return out;
}

nlohmann::json jsonOf(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

std::string outputFile(const nlohmann::json& j) {
  const std::string file = j.get<std::string>();
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  return file;
}

}  // namespace weft::editor
