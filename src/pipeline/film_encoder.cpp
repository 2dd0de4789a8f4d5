#include "src/pipeline/film_encoder.h"

#include <cstdio>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/subprocess.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string last_lines(const std::string& text, int lines) {
  std::size_t pos = text.size();
  while (pos > 0 && (text[pos - 1] == '\n' || text[pos - 1] == '\r')) --pos;
  const std::size_t end = pos;
  for (int i = 0; i < lines && pos != std::string::npos && pos > 0; ++i)
    pos = text.rfind('\n', pos - 1);
  std::string tail = text.substr(pos == std::string::npos ? 0 : pos + (pos > 0 ? 1 : 0), end);
  for (char& c : tail)
    if (c == '\n') c = ' ';
  return tail;
}

void check_request(const FilmRequest& r) {
  if (r.frame_count < 1) throw UserError(r.frame_pattern.string(), "", "no frames to encode");
  if (!(r.fps > 0)) throw UserError(r.frame_pattern.string(), "fps", "must be positive");
}

void require_ffmpeg(const fs::path& out, const FilmRequest& r) {
  if (!find_executable("ffmpeg"))
    throw UserError(out.string(), "",
                    "ffmpeg not found on PATH (install it with scripts/setup); the frames are kept "
                    "in " +
                        r.frame_pattern.parent_path().string());
}

void run_encoder(std::vector<std::string> args, const fs::path& out) {
  const fs::path temp = temporary_sibling(out);
  args.push_back(temp.string());
  const ProcessResult result = run_process(args);
  std::error_code ec;
  const auto size = fs::exists(temp, ec) ? fs::file_size(temp, ec) : 0;
  if (result.exit_code != 0 || size == 0) {
    fs::remove(temp, ec);
    throw UserError(out.string(), "",
                    "ffmpeg failed (exit " + std::to_string(result.exit_code) +
                        "): " + last_lines(result.output, 3));
  }
  fs::rename(temp, out, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw UserError(out.string(), "", "cannot move film into place: " + ec.message());
  }
}

std::vector<std::string> input_args(const FilmRequest& r) {
  return {"ffmpeg",
          "-nostdin",
          "-y",
          "-v",
          "error",
          "-framerate",
          number(r.fps),
          "-start_number",
          std::to_string(r.first_frame),
          "-i",
          r.frame_pattern.string(),
          "-frames:v",
          std::to_string(r.frame_count)};
}

}  // namespace

void encode_mp4(const FilmRequest& r, const fs::path& out_mp4) {
  check_request(r);
  require_ffmpeg(out_mp4, r);
  auto args = input_args(r);
  for (const char* a : {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt",
                        "yuv420p", "-movflags", "+faststart", "-f", "mp4"})
    args.emplace_back(a);
  args.insert(args.end() - 2, {"-crf", std::to_string(r.crf)});
  run_encoder(std::move(args), out_mp4);
}

void encode_gif(const FilmRequest& r, const fs::path& out_gif) {
  check_request(r);
  require_ffmpeg(out_gif, r);
  auto args = input_args(r);
  // One palette for the whole film (palettegen/paletteuse) avoids GIF's banding on smooth ice.
  for (const char* a :
       {"-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse", "-loop", "0", "-f", "gif"})
    args.emplace_back(a);
  run_encoder(std::move(args), out_gif);
}

int count_video_frames(const fs::path& video) {
  if (!find_executable("ffprobe")) throw UserError(video.string(), "", "ffprobe not found on PATH");
  const ProcessResult r =
      run_process({"ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
                   "-show_entries", "stream=nb_read_frames", "-of", "csv=p=0", video.string()});
  if (r.exit_code != 0)
    throw UserError(video.string(), "", "ffprobe failed: " + last_lines(r.output, 2));
  try {
    return std::stoi(r.output);
  } catch (const std::exception&) {
    throw UserError(video.string(), "", "ffprobe gave no frame count: " + last_lines(r.output, 2));
  }
}

}  // namespace thaw::pipeline
