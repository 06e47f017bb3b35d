// Calls run in a child process (engine/weft/io/ChildProcess.cpp), as the assimp reader is: what
// the call returns or throws comes back whole, and a crash or a hang ends the child, not the test.

#include <weft/io/ChildProcess.h>

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

namespace weft {
namespace {

constexpr long long kMemory = 4LL << 30;

TEST(ChildProcess, ReturnsTheCallsBytesWholeEvenPastThePipeBuffer) {
  std::string big(5 << 20, '\0');  // 5 MiB, far past a pipe's 64 KiB
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 131 % 251);
  const ChildOutcome outcome = runInChildProcess([&] { return big; }, 60.0, kMemory);
  ASSERT_EQ(outcome.kind, ChildOutcome::Kind::Returned);
  EXPECT_EQ(outcome.bytes, big);
}

TEST(ChildProcess, AnExceptionComesBackAsItsMessage) {
  const ChildOutcome outcome = runInChildProcess(
      []() -> std::string { throw std::runtime_error("no faces here"); }, 60.0, kMemory);
  ASSERT_EQ(outcome.kind, ChildOutcome::Kind::Threw);
  EXPECT_EQ(outcome.bytes, "no faces here");
}

TEST(ChildProcess, ACrashEndsTheChildAndIsNamed) {
  const ChildOutcome outcome = runInChildProcess(
      []() -> std::string {
        std::raise(SIGSEGV);
        return "unreachable";
      },
      60.0, kMemory);
  ASSERT_EQ(outcome.kind, ChildOutcome::Kind::Died);
  EXPECT_NE(outcome.bytes.find("signal 11"), std::string::npos) << outcome.bytes;
}

TEST(ChildProcess, AnExitWithoutAnAnswerIsADeath) {
  const ChildOutcome outcome =
      runInChildProcess([]() -> std::string { std::_Exit(7); }, 60.0, kMemory);
  ASSERT_EQ(outcome.kind, ChildOutcome::Kind::Died);
  EXPECT_EQ(outcome.bytes, "exited with status 7");
}

TEST(ChildProcess, AHangIsKilledAtTheTimeout) {
  const ChildOutcome outcome = runInChildProcess(
      []() -> std::string {
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
      },
      0.5, kMemory);
  EXPECT_EQ(outcome.kind, ChildOutcome::Kind::TimedOut);  // killed: it would never end itself
}

}  // namespace
}  // namespace weft
