#include "base/progress.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include <string>

namespace thaw {
namespace {

TEST(Progress, FormatsDurations) {
  EXPECT_EQ(ProgressReporter::format_duration(0.42), "0.42 s");
  EXPECT_EQ(ProgressReporter::format_duration(185), "3 min 05 s");
  EXPECT_EQ(ProgressReporter::format_duration(3720), "1 h 02 min");
  EXPECT_EQ(ProgressReporter::format_duration(-1), "?");
}

TEST(Progress, CountsFromManyThreads) {
  ProgressReporter p("test", 1000, /*quiet=*/true);
#pragma omp parallel for
  for (int i = 0; i < 1000; ++i) p.advance();
  p.finish();
  SUCCEED();
}

TEST(Progress, FinalLinesSayDoneOrWhyTheWorkStoppedShort) {
  ::testing::internal::CaptureStderr();
  {
    ProgressReporter p("[3/5] render", 41);
    p.set_done(41);
    p.finish();
    ProgressReporter q("[1/5] simulate", 80);
    q.set_done(51);
    q.finish_early("steps: the ice is gone");
    q.finish();  // a second final line is never printed
  }
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("[3/5] render: 41/41 done in "), std::string::npos) << err;
  EXPECT_NE(err.find("[1/5] simulate: 51/80 steps: the ice is gone ("), std::string::npos) << err;
  EXPECT_EQ(err.find("51/80 done"), std::string::npos) << err;
}

// Found by the bad-input sweep: `thaw inspect` on a folder whose mesh file is missing printed
// "inspect: 0/3 done in 0.00 s" before its error line (the destructor's final line while the
// error unwound): two lines for one error, and a false "done".
TEST(Progress, NoFinalLineWhileAnErrorUnwinds) {
  ::testing::internal::CaptureStderr();
  try {
    ProgressReporter p("inspect", 3);
    throw std::runtime_error("mesh file missing");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace thaw
