#include "src/pipeline/film_encoder.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>

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

enum class Container { mp4, gif };

/// What is wrong with a film file, or nullopt when its container is complete. ffmpeg exits 0 when
/// the disk fills while it writes the trailer (the MP4's moov atom, the GIF's ';'), leaving a
/// 16-20 KB unplayable stub, so its exit status is not enough.
/// MP4 (ISO/IEC 14496-12, 4.2): top-level boxes of 32-bit big-endian size (1: a 64-bit size
/// follows the type; 0: to the end of the file) and a 4-character type must tile the file exactly,
/// starting with ftyp and holding an mdat (the frames) and a moov (the index, written last).
/// GIF (GIF89a specification, 27): "GIF8" at the start and the trailer byte 0x3B at the end.
std::optional<std::string> container_problem(const fs::path& file, Container kind) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return "cannot be read back";
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return "cannot be read back";
  if (kind == Container::gif) {
    if (bytes.size() < 14 || bytes.compare(0, 4, "GIF8") != 0) return "is not a GIF image";
    if (bytes.back() != ';') return "has no GIF trailer (the end of the file was not written)";
    return std::nullopt;
  }
  auto be = [&](std::size_t at, int n) {
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v = v << 8 | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  bool moov = false, mdat = false;
  std::size_t at = 0;
  while (at < bytes.size()) {
    if (bytes.size() - at < 8) return "ends inside an MP4 box header";
    std::uint64_t size = be(at, 4);
    const std::string type = bytes.substr(at + 4, 4);
    std::uint64_t header = 8;
    if (size == 1) {
      if (bytes.size() - at < 16) return "ends inside an MP4 box header";
      size = be(at + 8, 8);
      header = 16;
    } else if (size == 0) {
      size = bytes.size() - at;  // to the end of the file: as the last box only, never moov
    }
    if (at == 0 && type != "ftyp") return "does not start with an MP4 ftyp box";
    if (size < header || size > bytes.size() - at)
      return "has an MP4 '" + type + "' box that runs past the end of the file (" +
             std::to_string(bytes.size()) + " bytes)";
    moov = moov || type == "moov";
    mdat = mdat || type == "mdat";
    at += size;
  }
  if (!mdat) return "has no MP4 mdat box (no frames were written)";
  if (!moov) return "has no MP4 moov atom (the index that ffmpeg writes last)";
  return std::nullopt;
}

/// Frames the container says it holds (MP4: read from moov, nothing decoded; GIF: decoded).
std::optional<long> container_frames(const fs::path& file, Container kind) {
  if (kind == Container::gif) {
    try {
      return count_video_frames(file);
    } catch (const UserError&) {
      return std::nullopt;
    }
  }
  if (!find_executable("ffprobe")) return std::nullopt;
  const ProcessResult r =
      run_process({"ffprobe", "-v", "error", "-select_streams", "v:0", "-show_entries",
                   "stream=nb_frames", "-of", "csv=p=0", file.string()});
  try {
    return r.exit_code == 0 ? std::optional<long>(std::stol(r.output)) : std::nullopt;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

/// Runs ffmpeg into a temporary sibling of `out`, checks what it wrote (exit status, a complete
/// container, the requested number of frames) and only then renames it over `out`: a failed film
/// leaves the previous one in place and is an error, so the film stage is not recorded as done
/// and the next run encodes again.
void run_encoder(std::vector<std::string> args, const fs::path& out, Container kind,
                 int frame_count) {
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
  std::optional<std::string> problem = container_problem(temp, kind);
  if (!problem) {
    const auto frames = container_frames(temp, kind);
    if (!frames || *frames != frame_count)
      problem = "holds " +
                (frames ? std::to_string(*frames) : std::string("no readable count of")) +
                " frames, " + std::to_string(frame_count) + " were encoded";
  }
  if (problem) {
    fs::remove(temp, ec);
    const std::string said = last_lines(result.output, 2);
    throw UserError(out.string(), "",
                    "ffmpeg exited " + std::to_string(result.exit_code) + " but the film " +
                        *problem + " (disk full?)" + (said.empty() ? "" : ": " + said) +
                        "; nothing was replaced");
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
  run_encoder(std::move(args), out_mp4, Container::mp4, r.frame_count);
}

void encode_gif(const FilmRequest& r, const fs::path& out_gif) {
  check_request(r);
  require_ffmpeg(out_gif, r);
  auto args = input_args(r);
  // One palette for the whole film (palettegen/paletteuse) avoids GIF's banding on smooth ice.
  for (const char* a :
       {"-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse", "-loop", "0", "-f", "gif"})
    args.emplace_back(a);
  run_encoder(std::move(args), out_gif, Container::gif, r.frame_count);
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
