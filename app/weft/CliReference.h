#pragma once
// The command-line reference, docs/cli.md, embedded in the binary at build time
// (cmake/EmbedCliReference.cmake), so that `weft help VERB` prints the documentation's own text.

#include <string>

namespace weft::cli {

// docs/cli.md as it was when this binary was built.
const char* cliReferenceText();

// The section of docs/cli.md for `verb`: the lines after its heading "## `weft VERB ...`" up to
// the next heading of that level, without leading and trailing blank lines; "" if it has none.
std::string cliReferenceSection(const std::string& verb);

}  // namespace weft::cli
