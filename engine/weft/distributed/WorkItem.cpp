#include <weft/core/Error.h>
#include <weft/distributed/WorkDistributor.h>

#include <exception>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace weft {

WorkItemResult runWorkItem(const WorkDistributor::Work& work, std::size_t item, int rank) {
  WorkItemResult r;
  r.rank = rank;
  // The exit codes and messages are the CLI's (app/weft/main.cpp), so that a failed item reads
  // as the same command run alone would.
  try {
    r.data = work(item);
    return r;
  } catch (const InputError& e) {
    r.exitCode = 2, r.message = e.what();
    r.detail = std::string("input") + '\0' + e.file() + '\0' + e.path() + '\0' + e.reason();
  } catch (const NumericalError& e) {
    r.exitCode = 3, r.message = std::string("numerical failure: ") + e.what();
    r.detail = std::string("numerical") + '\0' + std::to_string(e.step()) + '\0' + e.module() +
               '\0' + e.quantity();
  } catch (const std::bad_alloc&) {
    r.exitCode = 3, r.message = "out of memory";
  } catch (const std::exception& e) {
    r.exitCode = 1, r.message = std::string("internal: ") + e.what();
  }
  r.ok = false;
  return r;
}

namespace {
bool shared = false;
}  // namespace

bool failureIsShared() {
  return shared;
}

void rethrowFailure(const WorkItemResult& failed) {
  shared = true;
  std::vector<std::string> fields;
  for (std::size_t at = 0; !failed.detail.empty();) {
    const std::size_t end = failed.detail.find('\0', at);
    fields.push_back(failed.detail.substr(at, end == std::string::npos ? end : end - at));
    if (end == std::string::npos) break;
    at = end + 1;
  }
  if (fields.size() == 4 && fields[0] == "input") throw InputError(fields[1], fields[2], fields[3]);
  if (fields.size() == 4 && fields[0] == "numerical")
    throw NumericalError(std::stoi(fields[1]), fields[2], fields[3]);
  const std::string internal = "internal: ";
  throw std::runtime_error(failed.message.compare(0, internal.size(), internal) == 0
                               ? failed.message.substr(internal.size())
                               : failed.message);
}

const WorkItemResult* firstFailure(const std::vector<WorkItemResult>& results) {
  for (const WorkItemResult& r : results)
    if (!r.ok) return &r;
  return nullptr;
}

}  // namespace weft
