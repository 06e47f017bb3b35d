#include "StoredParameters.h"

#include <weft/core/Error.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace weft::bench {
std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream items(line);
  for (std::string item; std::getline(items, item, ',');) out.push_back(item);
  return out;
}

Eigen::VectorXd storedParameterValues(const std::string& file, const ParameterSet& parameters,
                                      int evaluation) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "<file>", "cannot read the stored parameter values");
  std::string line;
  std::vector<std::string> expected{"evaluation"};
  for (const SceneParameter& p : parameters.parameters()) expected.push_back(p.path);
  if (!std::getline(in, line) || splitCsvLine(line) != expected)
    throw InputError(file, "line 1",
                     "expected the header 'evaluation' and the task's " +
                         std::to_string(parameters.size()) + " parameter paths in order");
  const std::string wanted = std::to_string(evaluation);
  for (int number = 2; std::getline(in, line); ++number) {
    const std::vector<std::string> f = splitCsvLine(line);
    if (f.empty() || f[0] != wanted) continue;
    const std::string where = "line " + std::to_string(number);
    if (f.size() != expected.size())
      throw InputError(file, where, "expected " + std::to_string(expected.size()) + " fields");
    Eigen::VectorXd values(parameters.size());
    for (int i = 0; i < parameters.size(); ++i) {
      char* end = nullptr;
      values[i] = std::strtod(f[i + 1].c_str(), &end);
      if (f[i + 1].empty() || *end)
        throw InputError(file, where, expected[i + 1] + " is not a number: '" + f[i + 1] + "'");
    }
    return values;
  }
  throw InputError(file, "evaluation " + wanted, "not stored");
}

}  // namespace weft::bench
