#pragma once
// Turns numbered PNG frames into a film with the real ffmpeg: H.264 in MP4, yuv420p (plays
// everywhere), even dimensions enforced by padding (libx264 rejects odd sizes), optional GIF.
// Checks ffmpeg's exit status, that the container is complete (the MP4's moov atom, the GIF's
// trailer: ffmpeg exits 0 on a full disk without them) and holds every frame; writes to a
// temporary name and renames only a checked film, so a failure keeps the previous film.
#include <filesystem>
#include <string>

namespace thaw::pipeline {

struct FilmRequest {
  std::filesystem::path frame_pattern;  ///< printf-style, e.g. DIR/frames/frame_%06d.png
  int first_frame = 0;                  ///< number of the first frame in the pattern
  int frame_count = 0;                  ///< frames to encode (>= 1)
  double fps = 12.0;                    ///< frames per second of the film
  int crf = 18;                         ///< x264 constant rate factor (lower = better)
};

/// Encodes an MP4 to `out_mp4`. Throws thaw::UserError (naming ffmpeg and its last output
/// lines) if ffmpeg is missing, fails, or produces an empty, incomplete or short file; `out_mp4`
/// is then untouched.
void encode_mp4(const FilmRequest& request, const std::filesystem::path& out_mp4);
/// Encodes an animated GIF (palette generated from the frames) to `out_gif`.
void encode_gif(const FilmRequest& request, const std::filesystem::path& out_gif);

/// Number of video frames in `video`, counted by ffprobe (decoding every frame).
int count_video_frames(const std::filesystem::path& video);

}  // namespace thaw::pipeline
