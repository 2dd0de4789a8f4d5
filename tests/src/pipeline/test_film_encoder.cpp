#include "src/pipeline/film_encoder.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include "base/error.h"
#include "base/subprocess.h"

namespace thaw::pipeline {
namespace {
namespace fs = std::filesystem;

class FilmEncoder : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(find_executable("ffmpeg").has_value()) << "ffmpeg is a dependency: scripts/setup";
    m_dir = fs::temp_directory_path() / ("thaw_test_film_" + std::to_string(::getpid()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
    // Real PNG frames of an odd size (63x47), which libx264 would reject without padding.
    const auto r =
        run_process({"ffmpeg", "-v", "error", "-f", "lavfi", "-i", "testsrc=size=63x47:rate=4",
                     "-frames:v", "5", "-start_number", "0", (m_dir / "frame_%06d.png").string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  void TearDown() override { fs::remove_all(m_dir); }
  fs::path m_dir;
};

TEST_F(FilmEncoder, Mp4HasEveryFrameAndNoTemporaryLeftBehind) {
  FilmRequest req{m_dir / "frame_%06d.png", 0, 4, 8.0, 18};
  encode_mp4(req, m_dir / "melt.mp4");
  EXPECT_GT(fs::file_size(m_dir / "melt.mp4"), 0u);
  EXPECT_EQ(count_video_frames(m_dir / "melt.mp4"), 4);
  for (const auto& e : fs::directory_iterator(m_dir))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(FilmEncoder, Gif) {
  encode_gif({m_dir / "frame_%06d.png", 0, 5, 4.0, 18}, m_dir / "melt.gif");
  EXPECT_EQ(count_video_frames(m_dir / "melt.gif"), 5);
}

TEST_F(FilmEncoder, MissingFramesAreAClearErrorAndNoFilm) {
  FilmRequest req{m_dir / "nothing_%06d.png", 0, 3, 8.0, 18};
  EXPECT_THROW(encode_mp4(req, m_dir / "bad.mp4"), UserError);
  EXPECT_FALSE(fs::exists(m_dir / "bad.mp4"));
}

}  // namespace
}  // namespace thaw::pipeline
