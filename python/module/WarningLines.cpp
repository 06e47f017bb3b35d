#include "WarningLines.h"

#include <sstream>

namespace weft::python {

void addWarningLines(const std::string& text, std::vector<std::string>& warnings) {
  const std::string prefix = "warning: ";
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty())
      warnings.push_back(line.rfind(prefix, 0) == 0 ? line.substr(prefix.size()) : line);
}

}  // namespace weft::python
