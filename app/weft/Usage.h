#pragma once
// What `weft` prints for `weft help`, `weft help VERB` and `weft VERB --help`: each verb's usage
// line (here) followed by its section of the reference (docs/cli.md, CliReference.h).

#include <string>
#include <vector>

namespace weft::cli {

// The verbs, in the order `weft help` lists them.
const std::vector<std::string>& verbNames();
bool isVerb(const std::string& verb);
// Every verb's usage, the options every verb takes, and the exit codes.
std::string generalUsage();
// "usage: weft VERB ..." and, after a blank line, the verb's section of docs/cli.md.
std::string verbHelp(const std::string& verb);

}  // namespace weft::cli
