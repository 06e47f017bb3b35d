#include "Usage.h"

#include <weft/bench/BenchNames.h>
#include "CliReference.h"

#include <utility>

namespace weft::cli {
namespace {

// Verb and its arguments, continuation lines indented under the verb.
const std::vector<std::pair<std::string, std::string>>& usages() {
  static const std::vector<std::pair<std::string, std::string>> list = {
      {"simulate",
       "SCENE [--steps N] [--out DIR] [--set PATH=VALUE ...] [--threads N] [--strict] [--quiet]"},
      {"render",
       "SCENE|RUNDIR [--frames A:B:S] [--size WxH] [--camera front|side|top|auto]\n"
       "    [--overlay contacts|strain|speed|none] [--wireframe] [--out DIR] [--video FILE.mp4]\n"
       "    [--backend auto|osmesa|egl] [--set PATH=VALUE ...] [--quiet]"},
      {"bench", "NAME [--out DIR] [--quick] [--threads N] [NAME's options]\n    (NAME: " +
                    bench::benchNameList() + ")"},
      {"gradcheck",
       "SCENE [--param PATH ...] [--eps E] [--json] [--set PATH=VALUE ...]\n"
       "    [--backward gmres|fixed_point|direct] [--forward-tolerance T] [--backward-tolerance "
       "T]"},
      {"gradient", "SCENE [--param PATH ...] [--json] [--set PATH=VALUE ...] [--threads N]"},
      {"optimize",
       "SCENE [--method lbfgsb|cmaes|es1p1|adam] [--seed S] [--budget STEPS] [--out DIR]\n"
       "    [--max-evaluations N] [--learning-rate R] [--first-step L]\n"
       "    [--min-curvature-step L] [--set PATH=VALUE ...]"},
      {"landscape",
       "SCENE --param A [--param B] [--grid N] [--range PATH=LO:HI ...] [--out DIR]\n"
       "    [--set PATH=VALUE ...] [--threads N] [--quiet]"},
      {"sweep",
       "SCENE --set-grid PATH=A,B,... [--set-grid ...] [--set PATH=VALUE ...] [--steps N]\n"
       "    [--out DIR] [--threads N] [--quiet]"},
  };
  return list;
}

// The usage text of one verb with its continuation lines indented by `indent` more spaces.
std::string indented(const std::string& text, const std::string& indent) {
  std::string out;
  for (char c : text) {
    out += c;
    if (c == '\n') out += indent;
  }
  return out;
}

}  // namespace

const std::vector<std::string>& verbNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& u : usages()) n.push_back(u.first);
    return n;
  }();
  return names;
}

bool isVerb(const std::string& verb) {
  for (const std::string& v : verbNames())
    if (v == verb) return true;
  return false;
}

std::string generalUsage() {
  std::string text = "usage: weft <verb> [arguments]\n";
  for (const auto& [verb, args] : usages())
    text += "  " + verb + " " + indented(args, std::string(verb.size() + 3, ' ')) + "\n";
  text +=
      "  help [VERB]       (this list; with a verb, its usage and reference, as VERB --help)\n"
      "  --version         (the commit this build was made from)\n"
      "Exit codes: 0 success, 2 bad input or usage, 3 numerical failure.\n";
  return text;
}

std::string verbHelp(const std::string& verb) {
  for (const auto& [name, args] : usages())
    if (name == verb) {
      std::string text = "usage: weft " + name + " " + indented(args, "  ") + "\n";
      const std::string reference = cliReferenceSection(verb);
      if (!reference.empty()) text += "\n" + reference;
      return text;
    }
  return "";
}

}  // namespace weft::cli
