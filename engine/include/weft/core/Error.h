#pragma once
// The two failure kinds of Weft's contract: bad input (exit 2) and numerical failure (exit 3).

#include <stdexcept>
#include <string>

namespace weft {

// Bad input: a scene, mesh, option or file that cannot be used. The message follows the
// contract `<file>: <json path or option>: <what is wrong>`; the CLI prefixes "error: ".
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string path, std::string what)
      : std::runtime_error(file + ": " + path + ": " + what),
        file_(std::move(file)),
        path_(std::move(path)),
        what_(std::move(what)) {}
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  const std::string& reason() const { return what_; }

 private:
  std::string file_, path_, what_;
};

// A numerical failure: names the step, the module that produced it and the quantity.
class NumericalError : public std::runtime_error {
 public:
  NumericalError(int step, std::string module, std::string quantity)
      : std::runtime_error("step " + std::to_string(step) + ": " + module + ": " + quantity),
        step_(step),
        module_(std::move(module)),
        quantity_(std::move(quantity)) {}
  int step() const { return step_; }
  const std::string& module() const { return module_; }
  const std::string& quantity() const { return quantity_; }

 private:
  int step_;
  std::string module_, quantity_;
};

}  // namespace weft
