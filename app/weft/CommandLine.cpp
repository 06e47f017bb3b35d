#include "CommandLine.h"

#include <weft/core/Error.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace weft::cli {

CommandLine::CommandLine(const std::vector<std::string>& args,
                         const std::vector<std::string>& valued,
                         const std::vector<std::string>& flags) {
  auto contains = [](const std::vector<std::string>& list, const std::string& s) {
    return std::find(list.begin(), list.end(), s) != list.end();
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.size() > 2 && a.compare(0, 2, "--") == 0) {
      std::string name = a, val;
      const auto eq = a.find('=');
      const bool inlineValue = eq != std::string::npos;
      if (inlineValue) name = a.substr(0, eq), val = a.substr(eq + 1);
      if (contains(valued, name)) {
        if (!inlineValue) {
          if (i + 1 >= args.size()) fail(name, "needs a value");
          val = args[++i];
        }
        options_.emplace_back(name, val);
      } else if (contains(flags, name)) {
        if (inlineValue) fail(name, "takes no value");
        options_.emplace_back(name, "");
      } else {
        fail(name, "unknown option");
      }
    } else {
      positional_.push_back(a);
    }
  }
}

void CommandLine::fail(const std::string& option, const std::string& what) const {
  throw InputError(context_, option, what);
}

bool CommandLine::has(const std::string& option) const {
  for (const auto& o : options_)
    if (o.first == option) return true;
  return false;
}

std::string CommandLine::value(const std::string& option, const std::string& fallback) const {
  std::string v = fallback;
  for (const auto& o : options_)
    if (o.first == option) v = o.second;
  return v;
}

std::vector<std::string> CommandLine::values(const std::string& option) const {
  std::vector<std::string> v;
  for (const auto& o : options_)
    if (o.first == option) v.push_back(o.second);
  return v;
}

int CommandLine::integer(const std::string& option, int fallback, int min, int max) const {
  if (!has(option)) return fallback;
  const std::string s = value(option, "");
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || v < min || v > max)
    fail(option, "must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                     "], got '" + s + "'");
  return static_cast<int>(v);
}

double CommandLine::number(const std::string& option, double fallback) const {
  if (!has(option)) return fallback;
  const std::string s = value(option, "");
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v))
    fail(option, "must be a number, got '" + s + "'");
  return v;
}

}  // namespace weft::cli
