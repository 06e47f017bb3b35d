#pragma once
// Minimal, strict option parsing for the weft verbs: unknown options and missing or malformed
// values are InputErrors (exit 2) naming the option.

#include <string>
#include <vector>

namespace weft::cli {

class CommandLine {
 public:
  // `valued` options take a value (--out DIR or --out=DIR); `flags` take none.
  CommandLine(const std::vector<std::string>& args, const std::vector<std::string>& valued,
              const std::vector<std::string>& flags);

  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& option) const;
  std::string value(const std::string& option, const std::string& fallback) const;  // last given
  std::vector<std::string> values(const std::string& option) const;                 // all given
  int integer(const std::string& option, int fallback, int min, int max) const;
  double number(const std::string& option, double fallback) const;
  // The file errors are reported against (the scene, when known).
  void setContext(std::string file) { context_ = std::move(file); }
  const std::string& context() const { return context_; }
  [[noreturn]] void fail(const std::string& option, const std::string& what) const;

 private:
  std::vector<std::string> positional_;
  std::vector<std::pair<std::string, std::string>> options_;
  std::string context_ = "weft";
};

}  // namespace weft::cli
