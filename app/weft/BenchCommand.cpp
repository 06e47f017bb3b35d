#include "BenchNames.h"
#include "CommandLine.h"
#include "Commands.h"

namespace weft::cli {

int forwardBenchmark(const CommandLine& cl, const std::string& outDir);
int continuityBenchmark(const CommandLine& cl, const std::string& outDir);
int contactBenchmark(const CommandLine& cl, const std::string& outDir);
int backwardBenchmark(const CommandLine& cl, const std::string& outDir);
int applicationsBenchmark(const CommandLine& cl, const std::string& outDir);

int benchCommand(const std::vector<std::string>& arguments) {
  // The render benchmark has its own options (--frames, --size, --backend).
  if (!arguments.empty() && arguments[0] == "render")
    return renderBenchmark({arguments.begin() + 1, arguments.end()});
  // --paper-meshes takes an optional folder: the next argument, unless it is an option or a
  // benchmark name; bare, it is handed on with an empty value (the default folder).
  std::vector<std::string> args;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    if (arguments[i] != "--paper-meshes") {
      args.push_back(arguments[i]);
      continue;
    }
    const bool hasValue = i + 1 < arguments.size() && arguments[i + 1].rfind("-", 0) != 0 &&
                          arguments[i + 1] != "applications";
    args.push_back("--paper-meshes=" + (hasValue ? arguments[++i] : std::string()));
  }
  CommandLine cl(args,
                 {"--out", "--scene", "--scenes", "--threads", "--resolutions", "--tasks",
                  "--methods", "--seeds", "--budget", "--jobs", "--contact", "--paper-meshes",
                  "--subdivisions", "--resolution", "--first-step", "--min-curvature-step"},
                 {"--quick", "--resume", "--calibrate"});
  if (cl.positional().size() != 1)
    cl.fail("NAME", "bench takes one benchmark name (" + benchNameList() + ")");
  const std::string name = cl.positional()[0];
  const std::string out = cl.value("--out", "out/bench-" + name);
  for (const char* option : {"--subdivisions", "--resolution"})
    if (cl.has(option) && name != "continuity")
      cl.fail(option, "applies to the continuity benchmark only");
  if (cl.has("--calibrate") && name != "backward")
    cl.fail("--calibrate", "applies to the backward benchmark only");
  if (name == "applications") {
    if (cl.has("--resolutions"))
      cl.fail("--resolutions", "applies to the forward, backward and contact benchmarks only");
    if (cl.has("--contact")) cl.fail("--contact", "applies to the contact benchmark only");
    return applicationsBenchmark(cl, out);
  }
  for (const char* option : {"--tasks", "--methods", "--seeds", "--budget", "--jobs", "--resume",
                             "--paper-meshes", "--first-step", "--min-curvature-step"})
    if (cl.has(option)) cl.fail(option, "applies to the applications benchmark only");
  if (name == "contact") return contactBenchmark(cl, out);
  if (cl.has("--contact") && name != "continuity")
    cl.fail("--contact", "applies to the contact and continuity benchmarks only");
  if (name == "forward") return forwardBenchmark(cl, out);
  if (name == "backward") return backwardBenchmark(cl, out);
  if (cl.has("--resolutions"))
    cl.fail("--resolutions", "applies to the forward, backward and contact benchmarks only");
  if (name == "continuity") return continuityBenchmark(cl, out);
  cl.fail("NAME", "unknown benchmark '" + name + "' (known: " + benchNameList() + ")");
}

}  // namespace weft::cli
