#include "ChildProcess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <exception>
#include <stdexcept>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define WEFT_UNDER_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define WEFT_UNDER_SANITIZER 1
#endif
#endif

namespace weft {
namespace {

// The child's answer on the pipe: one tag byte ('R' returned, 'E' threw), then the bytes.
bool writeAll(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

[[noreturn]] void runChild(int fd, const std::function<std::string()>& call,
                           long long memoryLimitBytes) {
#ifndef WEFT_UNDER_SANITIZER
  const rlimit limit{static_cast<rlim_t>(memoryLimitBytes), static_cast<rlim_t>(memoryLimitBytes)};
  ::setrlimit(RLIMIT_AS, &limit);
#else
  (void)memoryLimitBytes;
#endif
  // A fault in the child ends the child: the handlers the parent installed (a sanitizer's, a
  // fuzzer's, an application's) are the parent's business and do not run here.
  for (const int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE}) ::signal(sig, SIG_DFL);
  // What the child would print (a sanitizer's report of the crash it is there to contain) is not
  // the caller's output: the outcome carries what happened.
  const int devNull = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (devNull >= 0) ::dup2(devNull, STDERR_FILENO);
  std::string answer;
  try {
    answer = "R" + call();
  } catch (const std::exception& e) {
    answer = std::string("E") + e.what();
  } catch (...) {
    answer = "Ean exception that is not a std::exception";
  }
  // _exit: no atexit handlers or static destructors of the parent's state run in the child.
  ::_exit(writeAll(fd, answer.data(), answer.size()) ? 0 : 1);
}

}  // namespace

std::string describeChildExit(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::strsignal(sig);
    return "killed by signal " + std::to_string(sig) + " (" + (name ? name : "unknown") + ")";
  }
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  return "ended with wait status " + std::to_string(status);
}

ChildOutcome runInChildProcess(const std::function<std::string()>& call, double timeoutSeconds,
                               long long memoryLimitBytes) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot make a pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("cannot start a child process: ") + std::strerror(err));
  }
  if (pid == 0) {
    ::close(fds[0]);
    runChild(fds[1], call, memoryLimitBytes);
  }
  ::close(fds[1]);

  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(timeoutSeconds));
  std::string answer;
  bool timedOut = false;
  char buffer[1 << 16];
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) {
      timedOut = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file: the child has exited (or closed its end)
    answer.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  if (timedOut) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }

  ChildOutcome outcome;
  if (timedOut) {
    outcome.kind = ChildOutcome::Kind::TimedOut;
    return outcome;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || answer.empty()) {
    outcome.kind = ChildOutcome::Kind::Died;
    outcome.bytes = describeChildExit(status);
    return outcome;
  }
  outcome.kind = answer[0] == 'R' ? ChildOutcome::Kind::Returned : ChildOutcome::Kind::Threw;
  outcome.bytes = answer.substr(1);
  return outcome;
}

}  // namespace weft
