// `weft`: the command-line face of the engine. Exit codes: 0 success, 2 bad input or usage,
// 3 numerical failure (the contract of the product spec).

#include "../process/PassiveOpenMpWait.h"
#include "BuildInfo.h"
#include "Commands.h"
#include "Usage.h"

#include <weft/bench/BuildRecord.h>
#include <weft/core/Error.h>
#include <weft/distributed/WorkDistributor.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

int runVerb(const std::string& verb, const std::vector<std::string>& args) {
  if (verb == "simulate") return weft::cli::simulateCommand(args);
  if (verb == "render") return weft::cli::renderCommand(args);
  if (verb == "bench") return weft::cli::benchCommand(args);
  if (verb == "gradcheck") return weft::cli::gradcheckCommand(args);
  if (verb == "gradient") return weft::cli::gradientCommand(args);
  if (verb == "optimize") return weft::cli::optimizeCommand(args);
  if (verb == "landscape") return weft::cli::landscapeCommand(args);
  if (verb == "sweep") return weft::cli::sweepCommand(args);
  std::fprintf(stderr, "error: weft: %s: unknown verb\n%s", verb.c_str(),
               weft::cli::generalUsage().c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  weft::process::preferPassiveOpenMpWait(argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::fputs(weft::cli::generalUsage().c_str(), stderr);
    return 2;
  }
  if (args[0] == "--help" || args[0] == "-h" || (args[0] == "help" && args.size() == 1)) {
    std::fputs(weft::cli::generalUsage().c_str(), stdout);
    return 0;
  }
  if (args[0] == "--version") {
    std::printf("weft %s, %s\n", WEFT_VERSION,
                weft::bench::describeBuild(weft::cli::buildInfoJson()).c_str());
    return 0;
  }
  // `weft help VERB` and `weft VERB --help` (or -h anywhere among its arguments): the verb's
  // usage and its section of docs/cli.md.
  if (args[0] == "help") {
    if (args.size() > 2 || !weft::cli::isVerb(args[1])) {
      std::fprintf(stderr, "error: weft: help %s: %s\n%s", args[1].c_str(),
                   args.size() > 2 ? "help takes one verb" : "unknown verb",
                   weft::cli::generalUsage().c_str());
      return 2;
    }
    std::fputs(weft::cli::verbHelp(args[1]).c_str(), stdout);
    return 0;
  }
  if (weft::cli::isVerb(args[0]))
    for (std::size_t i = 1; i < args.size(); ++i)
      if (args[i] == "--help" || args[i] == "-h") {
        std::fputs(weft::cli::verbHelp(args[0]).c_str(), stdout);
        return 0;
      }
  const std::string verb = args[0];
  args.erase(args.begin());
  // Under mpirun every rank runs the command (weft/distributed/WorkDistributor.h); rank 0 alone
  // prints errors, and MPI ends on every way out.
  const bool printErrors = weft::launchRank() == 0;
  // The verbs that do not distribute run on rank 0 alone; the other ranks leave at once (before
  // MPI starts, which they would otherwise have to join).
  const bool distributes =
      verb == "sweep" || verb == "landscape" || verb == "optimize" || verb == "bench";
  if (!distributes && !printErrors) return 0;
  const auto finish = [](int code, bool quiet = true) {
    weft::endProcessWorkers(code, quiet || weft::failureIsShared());
    return code;
  };
  try {
    return finish(runVerb(verb, args));
  } catch (const weft::QuietExit& e) {
    return finish(e.code);
  } catch (const weft::InputError& e) {
    if (printErrors) std::fprintf(stderr, "error: %s\n", e.what());
    return finish(2, false);
  } catch (const weft::NumericalError& e) {
    if (printErrors) std::fprintf(stderr, "error: numerical failure: %s\n", e.what());
    return finish(3, false);
  } catch (const std::bad_alloc&) {
    if (printErrors) std::fprintf(stderr, "error: out of memory\n");
    return finish(3, false);
  } catch (const std::exception& e) {
    if (printErrors) std::fprintf(stderr, "error: internal: %s\n", e.what());
    return finish(1, false);
  }
}
