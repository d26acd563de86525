// The fatal-signal handler: a real fault (a write to a read-only page) and an abort end the
// process with their signal after one line naming the signal, the command and the last tick,
// and a backtrace that names the function that faulted.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdlib>

#include "tools/msbench/crash_handler.h"

// External linkage and not inlined: the backtrace must show it by name.
__attribute__((noinline)) void msbTestWriteToAReadOnlyPage();
__attribute__((noinline)) void msbTestWriteToAReadOnlyPage() {
  void* page = mmap(nullptr, 4096, PROT_READ, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(page, MAP_FAILED);
  *static_cast<volatile int*>(page) = 1;  // SIGSEGV
}

TEST(CrashHandlerDeathTest, ASegfaultWritesTheTickAndABacktraceAndEndsWithTheSignal) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        msb::installCrashHandler("run");
        msb::setCrashContext(123456, 123.4565);
        msbTestWriteToAReadOnlyPage();
      },
      testing::KilledBySignal(SIGSEGV),
      "msbench run: fatal signal 11 \\(SIGSEGV\\) after tick 123456 \\(t = 123\\.457 s simulated\\)\n"
      "backtrace:\n(.|\n)*msbTestWriteToAReadOnlyPage");
}

TEST(CrashHandlerDeathTest, AnAbortBeforeTheFirstTickIsReportedToo) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        msb::installCrashHandler("fly");
        std::abort();
      },
      testing::KilledBySignal(SIGABRT),
      "msbench fly: fatal signal 6 \\(SIGABRT\\) before the first tick\nbacktrace:\n");
}
