#pragma once
// The engine's warning texts ("warning: ...\n" lines, as the CLI prints them) as a list.

#include <string>
#include <vector>

namespace weft::python {

// Appends each non-empty line of `text` to `warnings`, without its "warning: " prefix.
void addWarningLines(const std::string& text, std::vector<std::string>& warnings);

}  // namespace weft::python
