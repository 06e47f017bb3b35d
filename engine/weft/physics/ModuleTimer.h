#pragma once
// The seconds each module of a simulation spends (the module columns of stats.csv), accumulated
// over the run and over the current step. Modules are the ones a scene builds ("solver", each
// constraint family and force, the contact modules), in the order they were added.

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace weft {

class ModuleTimer {
 public:
  using Clock = std::chrono::steady_clock;

  static double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

  // Adds a module; returns its index.
  int add(const std::string& name) {
    names_.push_back(name);
    seconds_.push_back(0.0);
    return static_cast<int>(names_.size()) - 1;
  }
  const std::vector<std::string>& names() const { return names_; }
  const std::vector<double>& seconds() const { return seconds_; }  // over the run
  const std::vector<double>& stepSeconds() const { return stepSeconds_; }

  // Starts a step: its seconds start at zero.
  void beginStep() { stepSeconds_.assign(names_.size(), 0.0); }
  // Adds seconds to a module, over the run and (once a step has begun) the step.
  void charge(int module, double seconds) {
    seconds_[module] += seconds;
    if (!stepSeconds_.empty()) stepSeconds_[module] += seconds;
  }
  template <class Fn>
  void timed(int module, Fn&& fn) {
    const auto start = Clock::now();
    std::forward<Fn>(fn)();
    charge(module, secondsSince(start));
  }

 private:
  std::vector<std::string> names_;
  std::vector<double> seconds_, stepSeconds_;
};

}  // namespace weft
