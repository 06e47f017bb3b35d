#include "CommandLine.h"
#include "Commands.h"

namespace weft::cli {

int forwardBenchmark(const CommandLine& cl, const std::string& outDir);
int continuityBenchmark(const CommandLine& cl, const std::string& outDir);
int contactBenchmark(const CommandLine& cl, const std::string& outDir);
int backwardBenchmark(const CommandLine& cl, const std::string& outDir);
int applicationsBenchmark(const CommandLine& cl, const std::string& outDir);

int benchCommand(const std::vector<std::string>& args) {
  // The render benchmark has its own options (--frames, --size, --backend).
  if (!args.empty() && args[0] == "render") return renderBenchmark({args.begin() + 1, args.end()});
  CommandLine cl(args, {"--out", "--scene", "--scenes", "--threads", "--resolutions", "--tasks", "--seeds", "--budget",
                        "--contact"},
                 {"--quick"});
  if (cl.positional().size() != 1)
    cl.fail("NAME", "bench takes one benchmark name: forward, backward, continuity, contact, applications or render");
  const std::string name = cl.positional()[0];
  const std::string out = cl.value("--out", "out/bench-" + name);
  if (name == "applications") {
    if (cl.has("--resolutions")) cl.fail("--resolutions", "applies to the forward, backward and contact benchmarks only");
    if (cl.has("--contact")) cl.fail("--contact", "applies to the contact benchmark only");
    return applicationsBenchmark(cl, out);
  }
  for (const char* option : {"--tasks", "--seeds", "--budget"})
    if (cl.has(option)) cl.fail(option, "applies to the applications benchmark only");
  if (name == "contact") return contactBenchmark(cl, out);
  if (cl.has("--contact") && name != "continuity")
    cl.fail("--contact", "applies to the contact and continuity benchmarks only");
  if (name == "forward") return forwardBenchmark(cl, out);
  if (name == "backward") return backwardBenchmark(cl, out);
  if (cl.has("--resolutions")) cl.fail("--resolutions", "applies to the forward, backward and contact benchmarks only");
  if (name == "continuity") return continuityBenchmark(cl, out);
  cl.fail("NAME", "unknown benchmark '" + name + "' (known: forward, backward, continuity, contact, applications, render)");
}

}  // namespace weft::cli
