#include "src/common/progress.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace thaw
