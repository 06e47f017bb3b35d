#include "CommandLine.h"
#include "Commands.h"

namespace weft::cli {

int benchCommand(const std::vector<std::string>& args) {
  CommandLine cl(args, {"--out"}, {"--quick"});
  cl.fail("NAME", "no benchmark yet");
}

}  // namespace weft::cli
