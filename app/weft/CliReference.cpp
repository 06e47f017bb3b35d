#include "CliReference.h"

#include <sstream>

namespace weft::cli {

std::string cliReferenceSection(const std::string& verb) {
  std::istringstream in(cliReferenceText());
  const std::string heading = "## `weft " + verb;
  std::string line, body;
  bool inside = false;
  while (std::getline(in, line)) {
    const bool sectionHeading = line.rfind("## ", 0) == 0 || line.rfind("# ", 0) == 0;
    if (inside && sectionHeading) break;
    if (inside) {
      body += line + "\n";
    } else if (line.rfind(heading, 0) == 0 &&
               (line.size() == heading.size() || line[heading.size()] == ' ' ||
                line[heading.size()] == '`')) {
      inside = true;
    }
  }
  const auto first = body.find_first_not_of('\n');
  if (first == std::string::npos) return "";
  const auto last = body.find_last_not_of('\n');
  return body.substr(first, last - first + 1) + "\n";
}

}  // namespace weft::cli
