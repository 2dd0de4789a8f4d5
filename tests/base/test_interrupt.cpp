// base/interrupt: the flag set by SIGINT/SIGTERM, the safe-point check, and the child
// program (ffmpeg) that is ended with thaw.
#include "base/interrupt.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <thread>

#include "base/subprocess.h"

namespace thaw {
namespace {

class Interrupt : public ::testing::Test {
 protected:
  void SetUp() override { clear_interrupt_request(); }
  void TearDown() override { clear_interrupt_request(); }
};

TEST_F(Interrupt, RequestIsSeenAndThrownAtTheSafePointWithTheResumeMessage) {
  EXPECT_FALSE(interrupt_requested());
  EXPECT_NO_THROW(throw_if_interrupted());
  request_interrupt();
  EXPECT_TRUE(interrupt_requested());
  try {
    throw_if_interrupted();
    FAIL() << "no exception";
  } catch (const Interrupted& e) {
    EXPECT_STREQ(e.what(), "interrupted; run the same command again to resume");
  }
}

TEST_F(Interrupt, SignalsSetTheFlagInsteadOfEndingTheProcess) {
  for (const int s : {SIGINT, SIGTERM}) {
    clear_interrupt_request();
    install_interrupt_handlers();  // SA_RESETHAND: reinstalled for each signal
    ASSERT_EQ(::raise(s), 0);
    EXPECT_TRUE(interrupt_requested()) << s;
  }
  signal(SIGINT, SIG_DFL);
  signal(SIGTERM, SIG_DFL);
}

// Issue 12: a signal that arrives while thaw-full is still loading its libraries (held back by
// the launcher, across execve) reaches the handler once it is installed, instead of ending the
// process by the default action (exit 143 without a message).
TEST_F(Interrupt, SignalHeldBeforeTheHandlersReachesThemOnceInstalled) {
  for (const int s : {SIGINT, SIGTERM}) {
    clear_interrupt_request();
    signal(s, SIG_DFL);  // as in a freshly executed program
    hold_interrupt_signals();
    ASSERT_EQ(::raise(s), 0);  // pending, not delivered (the default action would end the test)
    EXPECT_FALSE(interrupt_requested()) << s;
    install_interrupt_handlers();
    EXPECT_TRUE(interrupt_requested()) << s;
  }
  signal(SIGINT, SIG_DFL);
  signal(SIGTERM, SIG_DFL);
}

TEST_F(Interrupt, InterruptibleCallbackThrowsBeforeReporting) {
  int calls = 0;
  const ProgressCallback cb = interruptible([&](std::int64_t, std::int64_t) { ++calls; });
  cb(1, 2);
  EXPECT_EQ(calls, 1);
  request_interrupt();
  EXPECT_THROW(cb(2, 2), Interrupted);
  EXPECT_EQ(calls, 1);
}

TEST_F(Interrupt, RunningChildProgramIsEndedAndTheInterruptReported) {
  // A request from another thread (as the signal handler would make) ends `sleep 30` at once.
  std::thread requester([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    request_interrupt();
  });
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(run_process({"sleep", "30"}), Interrupted);
  requester.join();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 10.0);
}

TEST_F(Interrupt, RequestBeforeTheChildStartsEndsItToo) {
  request_interrupt();
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(run_process({"sleep", "30"}), Interrupted);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

}  // namespace
}  // namespace thaw
