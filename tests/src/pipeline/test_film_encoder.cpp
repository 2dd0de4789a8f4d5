#include "src/pipeline/film_encoder.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <string>

#include "base/error.h"
#include "base/subprocess.h"
#include "tests/base/file_size_limit.h"

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

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Issue 27: when the disk fills while ffmpeg writes the film, ffmpeg exits 0 and leaves a stub
// without its moov atom; thaw reported success, the good film was gone, and the next run called
// the stub up to date. Now it is an error naming the missing moov, the previous film is kept
// byte for byte, and no temporary is left. The full disk: a file size limit (RLIMIT_FSIZE,
// inherited by ffmpeg) below the film's size.
TEST_F(FilmEncoder, FullDiskIsAnErrorAndKeepsThePreviousFilm) {
  const auto r =
      run_process({"ffmpeg", "-v", "error", "-f", "lavfi", "-i", "testsrc=size=320x240:rate=12",
                   "-frames:v", "24", "-start_number", "0", (m_dir / "big_%06d.png").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const FilmRequest req{m_dir / "big_%06d.png", 0, 24, 12.0, 18};
  const fs::path film = m_dir / "melt.mp4";
  encode_mp4(req, film);
  const std::string good = bytes_of(film);
  ASSERT_GT(good.size(), 12000u);  // larger than the limit below
  const fs::path gif = m_dir / "melt.gif";
  encode_gif(req, gif);
  const std::string good_gif = bytes_of(gif);
  ASSERT_GT(good_gif.size(), 12000u);
  {
    const thaw::testing::FileSizeLimit full_disk(8192);
    try {
      encode_mp4(req, film);
      FAIL() << "a truncated film was accepted";
    } catch (const UserError& e) {
      EXPECT_EQ(e.file(), film.string());
      EXPECT_NE(e.problem().find("moov"), std::string::npos) << e.what();
    }
    EXPECT_THROW(encode_gif(req, gif), UserError);
  }
  EXPECT_EQ(bytes_of(film), good);
  EXPECT_EQ(bytes_of(gif), good_gif);
  EXPECT_EQ(count_video_frames(film), 24);
  for (const auto& e : fs::directory_iterator(m_dir))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

// Fewer frames on disk than requested: ffmpeg stops at the first missing one and exits 0; the
// film would be silently short.
TEST_F(FilmEncoder, ShortFilmIsAnError) {
  const FilmRequest req{m_dir / "frame_%06d.png", 0, 9, 8.0, 18};  // 5 frames exist
  try {
    encode_mp4(req, m_dir / "short.mp4");
    FAIL() << "a short film was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(e.problem().find("9 were encoded"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(m_dir / "short.mp4"));
}

}  // namespace
}  // namespace thaw::pipeline
