// The film stage: melt.mp4 (and melt.gif) encoded by ffmpeg from every frame, by the leader. It
// waits until every frame of the run is rendered (--frames parts render them apart).
#include "base/progress.h"
#include "src/pipeline/film_encoder.h"
#include "src/pipeline/stages.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

fs::path film_file(const PipelineRun& r) {
  return r.out / "melt.mp4";
}
fs::path gif_file(const PipelineRun& r) {
  return r.out / "melt.gif";
}

StageDone film(PipelineRun& r, const StageCall& call) {
  const std::string count = std::to_string(r.frame_count);
  say(r.o, call.title + ": encoding " + count + " frames with ffmpeg");
  FilmRequest request{r.frames_dir / "frame_%06d.png", 0, static_cast<int>(r.frame_count),
                      r.sc.film.film_fps(), 18};
  encode_mp4(request, film_file(r));
  if (r.sc.film.gif) encode_gif(request, gif_file(r));
  say(r.o, call.title + ": " + count + "/" + count + " done in " +
               ProgressReporter::format_duration(call.elapsed_s()));
  return {1};
}

}  // namespace

Stage film_stage() {
  Stage s;
  s.name = s.tag = "film";
  s.runs_on = StageRunsOn::leader;
  s.reads = "render";
  s.fingerprint = [](PipelineRun& r, ContentHash& hash) {
    hash.add(r.sc.film_text).add(static_cast<double>(r.frame_count));
  };
  s.outputs_exist = [](const PipelineRun& r) {
    return fs::exists(film_file(r)) && (!r.sc.film.gif || fs::exists(gif_file(r)));
  };
  s.run = film;
  s.waits = [](const PipelineRun& r) -> std::string {
    if (r.all_frames_done) return "";
    long rendered = 0;
    for (long k = 0; k < r.frame_count; ++k)
      rendered += r.manifest.item_done("render", frame_name(k));
    return "waits for every frame (" + std::to_string(rendered) + " of " +
           std::to_string(r.frame_count) +
           " rendered); render the rest with --frames, then run thaw run again";
  };
  s.read = [](PipelineRun& r) {
    if (!r.wanted("film")) return;
    r.report.film = film_file(r);
    if (r.sc.film.gif) r.report.gif = gif_file(r);
  };
  return s;
}

}  // namespace thaw::pipeline
