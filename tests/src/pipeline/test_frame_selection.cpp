#include "src/pipeline/frame_selection.h"

#include <gtest/gtest.h>

#include "base/error.h"

namespace thaw::pipeline {
namespace {

std::vector<long> frames(const std::string& text, long count) {
  return parse_frame_selection(text).resolve(count);
}

TEST(FrameSelection, SingleFramesRangesAndSteps) {
  EXPECT_EQ(frames("7", 52), (std::vector<long>{7}));
  EXPECT_EQ(frames("10-13", 52), (std::vector<long>{10, 11, 12, 13}));
  EXPECT_EQ(frames("3:11:2", 52), (std::vector<long>{3, 5, 7, 9, 11}));
  EXPECT_EQ(frames("3:12:4", 52), (std::vector<long>{3, 7, 11}));  // last only when reached
  EXPECT_EQ(frames("0:2", 52), (std::vector<long>{0, 1, 2}));
}

TEST(FrameSelection, RangesPastTheLastFrameAreCutThere) {
  // A Slurm array's last chunk may reach past the film's end.
  EXPECT_EQ(frames("48-59", 52), (std::vector<long>{48, 49, 50, 51}));
}

TEST(FrameSelection, StridedSubsetsTileTheFilm) {
  // What GNU parallel or a job array with a stride hands out: every frame exactly once.
  std::vector<int> seen(52, 0);
  for (const char* part : {"0:51:3", "1:51:3", "2:51:3"})
    for (long k : frames(part, 52)) ++seen[static_cast<std::size_t>(k)];
  for (int n : seen) EXPECT_EQ(n, 1);
}

TEST(FrameSelection, ListsOfFramesAndRangesMixed) {
  EXPECT_EQ(frames("17,36", 52), (std::vector<long>{17, 36}));
  EXPECT_EQ(frames("36,17", 52), (std::vector<long>{17, 36}));  // in order
  EXPECT_EQ(frames("0-2,10:16:3,51", 52), (std::vector<long>{0, 1, 2, 10, 13, 16, 51}));
  EXPECT_EQ(frames("1-3,2-4,3", 52), (std::vector<long>{1, 2, 3, 4}));  // each once
  EXPECT_EQ(frames("5,48-59", 52), (std::vector<long>{5, 48, 49, 50, 51}));
  // A huge step neither overflows nor loops.
  EXPECT_EQ(frames("3:9223372036854775807:9223372036854775807", 52), (std::vector<long>{3}));
}

TEST(FrameSelection, AListPartPastTheFilmIsNamed) {
  try {
    frames("17,60", 52);
    ADD_FAILURE() << "accepted a frame past the film";
  } catch (const UserError& e) {
    EXPECT_EQ(e.where(), "--frames");
    EXPECT_NE(std::string(e.what()).find("\"60\" in \"17,60\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("0-51"), std::string::npos) << e.what();
  }
}

TEST(FrameSelection, BadPartsAreNamed) {
  try {
    parse_frame_selection("17,x,36");
    ADD_FAILURE() << "accepted x";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("in \"x\""), std::string::npos) << e.what();
  }
}

TEST(FrameSelection, BadTextIsAUserErrorNamingTheOption) {
  for (const char* bad : {"",       "x",     "10-",     "-3",   "3-1", "1:3:0",
                          "1:3:-1", "1-3:2", "1:2:3:4", "1..3", "4 ",  "99999999999999999999999",
                          ",",      "1,",    ",1",      "1,,2", "1;2", "1, 2",
                          "--1",    "1--2"}) {
    try {
      parse_frame_selection(bad);
      ADD_FAILURE() << "accepted \"" << bad << "\"";
    } catch (const UserError& e) {
      EXPECT_EQ(e.where(), "--frames") << bad;
    }
  }
}

TEST(FrameSelection, StartingPastTheFilmIsAUserError) {
  EXPECT_THROW(frames("52-60", 52), UserError);
  EXPECT_THROW(frames("52", 52), UserError);
  EXPECT_NO_THROW(frames("51", 52));
}

}  // namespace
}  // namespace thaw::pipeline
