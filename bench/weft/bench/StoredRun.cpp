#include "StoredRun.h"

#include "StoredParameters.h"

#include <weft/core/Error.h>
#include <weft/io/AtomicFile.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace weft::bench {

const std::vector<std::string> kRunColumns = {"task",  "method", "seed", "evaluation",
                                              "steps", "wall_s", "loss"};

std::string joinCsvLine(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + fields[i];
  return line + "\n";
}

int bestEvaluation(const ApplicationRun& run) {
  const auto best = std::min_element(run.curve.loss.begin(), run.curve.loss.end());
  return std::stoi(run.rows[static_cast<std::size_t>(best - run.curve.loss.begin())][3]);
}

void writeRunFile(const std::string& path, const ApplicationRun& run) {
  std::string text = joinCsvLine(kRunColumns);
  for (const auto& row : run.rows) text += joinCsvLine(row);
  writeFileAtomically(path, text);
}

ApplicationRun readRunFile(const std::string& path, const ApplicationTask& task, int method,
                           int seed) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "<file>", "cannot read the stored run");
  ApplicationRun run;
  run.method = method;
  run.seed = seed;
  run.resumed = true;
  run.stop = "resumed";
  std::string line;
  if (!std::getline(in, line) || joinCsvLine(kRunColumns) != line + "\n")
    throw InputError(path, "line 1",
                     "expected the header " + joinCsvLine(kRunColumns).substr(0, 44));
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::vector<std::string> f = splitCsvLine(line);
    const std::string where = "line " + std::to_string(number);
    if (f.size() != kRunColumns.size())
      throw InputError(path, where, "expected " + std::to_string(kRunColumns.size()) + " fields");
    if (f[0] != task.name || f[1] != kApplicationMethods[method].name ||
        f[2] != std::to_string(seed))
      throw InputError(path, where,
                       "a row of another run (" + f[0] + ", " + f[1] + ", seed " + f[2] + ")");
    char* end = nullptr;
    const long evaluation = std::strtol(f[3].c_str(), &end, 10);
    if (f[3].empty() || *end || evaluation < 1 || evaluation > 1000000000)
      throw InputError(path, where, "evaluation is not a positive integer: '" + f[3] + "'");
    const long long steps = std::strtoll(f[4].c_str(), &end, 10);
    if (f[4].empty() || *end)
      throw InputError(path, where, "steps is not an integer: '" + f[4] + "'");
    const double wall = std::strtod(f[5].c_str(), &end);
    if (f[5].empty() || *end)
      throw InputError(path, where, "wall_s is not a number: '" + f[5] + "'");
    const double loss = std::strtod(f[6].c_str(), &end);
    if (f[6].empty() || *end) throw InputError(path, where, "loss is not a number: '" + f[6] + "'");
    if (!run.curve.steps.empty() && steps < run.curve.steps.back())
      throw InputError(path, where, "steps decrease");
    run.curve.steps.push_back(steps);
    run.curve.loss.push_back(loss);
    run.seconds = wall;
    run.rows.push_back(f);
  }
  return run;
}

}  // namespace weft::bench
