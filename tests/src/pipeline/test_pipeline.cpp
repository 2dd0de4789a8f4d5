// End-to-end tests of `thaw run` on a tiny scenario (tests/src/pipeline/data/tiny.toml): the real
// thaw binary, real CGAL, renderer, ffmpeg and VTK (under Xvfb), run as a separate process so a
// run can be killed like a user would.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "base/subprocess.h"
#include "src/pipeline/film_encoder.h"
#include "tests/src/pipeline/run_test_support.h"

namespace thaw::pipeline {
namespace {
using namespace test;

/// tiny.toml with `from` replaced by `to`, written to `dir`.
fs::path variant(const fs::path& dir, const std::string& from, const std::string& to) {
  return tiny_variant(dir, {{from, to}});
}

class ThawRun : public TempDirTest {
 protected:
  ThawRun() : TempDirTest("thaw_test_run") {}
  ProcessResult thaw(std::vector<std::string> args) {
    args.insert(args.begin(), kThaw.string());
    return run_process(args);
  }
};

TEST_F(ThawRun, TinyScenarioEndToEndThenNothingToDo) {
  const fs::path out = m_dir / "out";
  const auto first = thaw({"run", kTiny.string(), "--out", out.string()});
  ASSERT_EQ(first.exit_code, 0) << first.output;
  // Every stage's progress ends clearly (issue 13), and the events are printed.
  for (const char* end :
       {"[1/5] simulate: 4/4 ", "[2/5] mesh: ", "[3/5] render: 4/4 done in ",
        "[4/5] film: 4/4 done in ", "[5/5] inspect: 4/4 done in ", "event melt_onset at t = "})
    EXPECT_NE(first.output.find(end), std::string::npos) << end << "\n" << first.output;
  EXPECT_EQ(count_video_frames(out / "melt.mp4"), 4);
  EXPECT_GT(fs::file_size(out / "plot.png"), 1000u);
  EXPECT_NE(read_file(out / "meshes.pvd").find("<VTKFile type=\"Collection\""), std::string::npos);
  for (const char* path : {"melt.mp4", "plot.png", "meshes.pvd"})
    EXPECT_NE(first.output.find((out / path).string()), std::string::npos) << path;
  const auto frames = frames_of(out);
  EXPECT_EQ(frames.size(), 4u);
  expect_user_guide_lists(out);
  const auto manifest_before = read_file(out / "run_manifest.json");
  const auto film_time = fs::last_write_time(out / "melt.mp4");

  const auto second = thaw({"run", kTiny.string(), "--out", out.string()});
  ASSERT_EQ(second.exit_code, 0) << second.output;
  // Every stage reports "up to date" and nothing was rewritten.
  std::size_t up_to_date = 0;
  for (std::size_t p = second.output.find("up to date"); p != std::string::npos;
       p = second.output.find("up to date", p + 1))
    ++up_to_date;
  EXPECT_GE(up_to_date, 5u) << second.output;
  EXPECT_EQ(fs::last_write_time(out / "melt.mp4"), film_time);
  EXPECT_EQ(read_file(out / "run_manifest.json"), manifest_before);
  EXPECT_EQ(frames_of(out), frames);
}

TEST_F(ThawRun, ChangingOnlyTheCameraReRendersWithoutReSimulatingOrReMeshing) {
  const fs::path out = m_dir / "out";
  ASSERT_EQ(thaw({"run", kTiny.string(), "--out", out.string(), "-q"}).exit_code, 0);
  const auto sim_time = fs::last_write_time(out / "sim/interfaces.csv");
  const auto mesh_time = fs::last_write_time(out / "sim/mesh/manifest.json");
  const auto frames = frames_of(out);
  const fs::path moved =
      variant(m_dir, "position = [0.0, 0.03, 0.09]", "position = [0.02, 0.03, 0.09]");
  const auto r = thaw({"run", moved.string(), "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(fs::last_write_time(out / "sim/interfaces.csv"), sim_time);
  EXPECT_EQ(fs::last_write_time(out / "sim/mesh/manifest.json"), mesh_time);
  const auto new_frames = frames_of(out);
  ASSERT_EQ(new_frames.size(), frames.size());
  for (const auto& [name, bytes] : frames) EXPECT_NE(new_frames.at(name), bytes) << name;
  // A comment or layout edit is not a change.
  std::string text = read_file(moved);
  text.replace(text.find("[render.ambient]"), 16, "# a comment\n\n[render.ambient]");
  const fs::path commented = m_dir / "commented.toml";
  std::ofstream(commented) << text;
  const auto frame_time = fs::last_write_time(out / "frames/frame_000000.png");
  const auto again = thaw({"run", commented.string(), "--out", out.string()});
  ASSERT_EQ(again.exit_code, 0);
  EXPECT_NE(again.output.find("render: up to date"), std::string::npos) << again.output;
  EXPECT_EQ(fs::last_write_time(out / "frames/frame_000000.png"), frame_time);
}

/// A PNG's width and height (IHDR, big-endian, bytes 16..23).
std::pair<std::uint32_t, std::uint32_t> png_size(const fs::path& file) {
  const std::string png = read_file(file);
  if (png.size() < 24) return {0, 0};
  const auto be32 = [&](std::size_t at) {
    return (std::uint32_t(std::uint8_t(png[at])) << 24) |
           (std::uint32_t(std::uint8_t(png[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(png[at + 2])) << 8) |
           std::uint32_t(std::uint8_t(png[at + 3]));
  };
  return {be32(16), be32(20)};
}

TEST_F(ThawRun, SizeAndSppOverridesReRenderOnlyAndBadValuesAreOneLine) {
  const fs::path out = m_dir / "out";
  ASSERT_EQ(thaw({"run", kTiny.string(), "--out", out.string(), "-q"}).exit_code, 0);
  const auto sim_time = fs::last_write_time(out / "sim/interfaces.csv");
  const auto mesh_time = fs::last_write_time(out / "sim/mesh/manifest.json");
  const auto r =
      thaw({"run", kTiny.string(), "--out", out.string(), "--size", "40x30", "--spp", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(fs::last_write_time(out / "sim/interfaces.csv"), sim_time);
  EXPECT_EQ(fs::last_write_time(out / "sim/mesh/manifest.json"), mesh_time);
  EXPECT_NE(r.output.find("simulate: up to date"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mesh: up to date"), std::string::npos) << r.output;
  // Other settings than the finals': a preview, beside them.
  EXPECT_EQ(png_size(out / "preview/frames/frame_000000.png"),
            (std::pair<std::uint32_t, std::uint32_t>{40, 30}));
  EXPECT_EQ(png_size(out / "frames/frame_000000.png"),
            (std::pair<std::uint32_t, std::uint32_t>{64, 64}));
  // The same overrides again: nothing to do.
  const auto again =
      thaw({"run", kTiny.string(), "--out", out.string(), "--size", "40x30", "--spp", "2"});
  EXPECT_NE(again.output.find("render: up to date"), std::string::npos) << again.output;
  // Bad values: one line naming the option, exit code 2, no output folder.
  for (const std::vector<std::string>& bad : {std::vector<std::string>{"--size", "640"},
                                              {"--size", "0x480"},
                                              {"--size", "640x-1"},
                                              {"--size", "20000x20000"},
                                              {"--spp", "0"},
                                              {"--spp", "-3"},
                                              {"--spp", "9999999"}}) {
    std::vector<std::string> args{"run", kTiny.string(), "--out", (m_dir / "never").string()};
    args.insert(args.end(), bad.begin(), bad.end());
    const auto e = thaw(args);
    EXPECT_EQ(e.exit_code, 2) << bad[1];
    EXPECT_NE(e.output.find(bad[0]), std::string::npos) << e.output;
    EXPECT_EQ(std::count(e.output.begin(), e.output.end(), '\n'), 1) << e.output;
    EXPECT_FALSE(fs::exists(m_dir / "never")) << bad[1];
  }
}

// Issue 27 item 1: a preview (--size / --spp other than the finals') never touches the finals;
// --force replaces them; a final made with --size is kept from a plain rerun too.
TEST_F(ThawRun, PreviewsNeverOverwriteTheFinals) {
  const fs::path out = m_dir / "out";
  ASSERT_EQ(thaw({"run", kTiny.string(), "--out", out.string(), "-q"}).exit_code, 0);
  const auto frames = frames_of(out);
  const std::string film = read_file(out / "melt.mp4");
  ASSERT_EQ(frames.size(), 4u);
  const auto preview = thaw({"run", kTiny.string(), "--out", out.string(), "--size", "32x24",
                             "--spp", "1", "--frames", "1,3"});
  ASSERT_EQ(preview.exit_code, 0) << preview.output;
  EXPECT_NE(preview.output.find("preview: 32x24, 1 spp differs from the finals in " + out.string() +
                                " (64x64, 1 spp)"),
            std::string::npos)
      << preview.output;
  EXPECT_NE(preview.output.find("preview: " + (out / "preview").string()), std::string::npos)
      << preview.output;
  // The preview starts from the finals' simulation and meshes.
  EXPECT_NE(preview.output.find("simulate: up to date"), std::string::npos) << preview.output;
  EXPECT_NE(preview.output.find("mesh: up to date"), std::string::npos) << preview.output;
  EXPECT_EQ(frames_of(out / "preview").size(), 2u);
  EXPECT_EQ(png_size(out / "preview/frames/frame_000003.png"),
            (std::pair<std::uint32_t, std::uint32_t>{32, 24}));
  EXPECT_EQ(frames_of(out), frames);
  EXPECT_EQ(read_file(out / "melt.mp4"), film);
  // A whole preview makes its own film; the finals' stay.
  ASSERT_EQ(thaw({"run", kTiny.string(), "--out", out.string(), "--size", "32x24", "-q"}).exit_code,
            0);
  EXPECT_EQ(count_video_frames(out / "preview/melt.mp4"), 4);
  EXPECT_EQ(frames_of(out), frames);
  EXPECT_EQ(read_file(out / "melt.mp4"), film);
  // A plain rerun: the finals are up to date.
  const auto plain = thaw({"run", kTiny.string(), "--out", out.string()});
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_EQ(plain.output.find("preview"), std::string::npos) << plain.output;
  EXPECT_EQ(frames_of(out), frames);
  EXPECT_EQ(read_file(out / "melt.mp4"), film);
  // A folder the user names.
  const fs::path named = m_dir / "look";
  const auto there = thaw({"run", kTiny.string(), "--out", out.string(), "--preview-dir",
                           named.string(), "--frames", "2", "-q"});
  ASSERT_EQ(there.exit_code, 0) << there.output;
  EXPECT_TRUE(fs::exists(named / "frames/frame_000002.png"));
  EXPECT_EQ(frames_of(out), frames);
  const auto same =
      thaw({"run", kTiny.string(), "--out", out.string(), "--preview-dir", out.string(), "-q"});
  EXPECT_EQ(same.exit_code, 2) << same.output;
  EXPECT_NE(same.output.find("--preview-dir"), std::string::npos) << same.output;
  EXPECT_EQ(std::count(same.output.begin(), same.output.end(), '\n'), 1) << same.output;
  // --force replaces the finals.
  ASSERT_EQ(thaw({"run", kTiny.string(), "--out", out.string(), "--size", "48x36", "--force", "-q"})
                .exit_code,
            0);
  EXPECT_EQ(png_size(out / "frames/frame_000000.png"),
            (std::pair<std::uint32_t, std::uint32_t>{48, 36}));
  const auto large = frames_of(out);
  const std::string large_film = read_file(out / "melt.mp4");
  // Finals made with --size are kept from a plain rerun, which becomes the preview.
  const auto after = thaw({"run", kTiny.string(), "--out", out.string()});
  ASSERT_EQ(after.exit_code, 0) << after.output;
  EXPECT_NE(after.output.find("preview: 64x64, 1 spp differs"), std::string::npos) << after.output;
  EXPECT_EQ(frames_of(out), large);
  EXPECT_EQ(read_file(out / "melt.mp4"), large_film);
  EXPECT_EQ(png_size(out / "preview/frames/frame_000000.png"),
            (std::pair<std::uint32_t, std::uint32_t>{64, 64}));
  expect_no_temporaries(out);
  expect_user_guide_lists(out);
}

// Issue 27 item 2: the files a scenario names are inputs as much as its text.
/// A uniform Radiance .hdr, 8x4 texels of level `mantissa` / 256 (flat RGBE scanlines).
void write_hdr(const fs::path& p, unsigned char mantissa) {
  std::ofstream out(p, std::ios::binary);
  out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n";
  for (int i = 0; i < 32; ++i) out << mantissa << mantissa << mantissa << char(-128);
}

/// A closed cube of edge `edge_m` centred at (cx, edge / 2, 0), as an OBJ.
void write_cube(const fs::path& p, double edge_m, double cx) {
  std::ofstream out(p);
  for (int i = 0; i < 8; ++i)
    out << "v " << cx + ((i & 1) ? 0.5 : -0.5) * edge_m << " " << ((i & 2) ? edge_m : 0.0) << " "
        << ((i & 4) ? 0.5 : -0.5) * edge_m << "\n";
  // outward faces, vertex index = 1 + x + 2y + 4z
  for (const char* f : {"1 3 4", "1 4 2", "5 6 8", "5 8 7", "1 2 6", "1 6 5", "3 7 8", "3 8 4",
                        "1 5 7", "1 7 3", "2 4 8", "2 8 6"})
    out << "f " << f << "\n";
}

bool says(const ProcessResult& r, const std::string& part) {
  return r.output.find(part) != std::string::npos;
}

TEST_F(ThawRun, AChangedEnvironmentMapOrObjectMeshRedoesTheStagesThatReadIt) {
  const fs::path out = m_dir / "out";
  write_hdr(m_dir / "sky.hdr", 100);
  write_cube(m_dir / "cube.obj", 0.006, 0.025);
  const fs::path scenario = variant(m_dir, "[render.ambient]",
                                    "[render.environment]\nkind = \"latlong\"\nfile = \"sky.hdr\"\n"
                                    "\n[[render.objects]]\nshape = \"mesh\"\nfile = \"cube.obj\"\n"
                                    "material = \"floor\"\n\n[render.ambient]");
  const std::vector<std::string> run{"run", scenario.string(), "--out", out.string()};
  ASSERT_EQ(thaw(run).exit_code, 0);
  const auto frames = frames_of(out);
  const std::string film = read_file(out / "melt.mp4");
  const std::string sky = read_file(out / "handoff/environment.hdr");
  EXPECT_TRUE(says(thaw(run), "render: up to date"));
  // Another sky: the frames, the film and the hand-off's sky are redone; nothing else.
  write_hdr(m_dir / "sky.hdr", 200);
  const auto brighter = thaw(run);
  ASSERT_EQ(brighter.exit_code, 0) << brighter.output;
  EXPECT_TRUE(says(brighter, "simulate: up to date")) << brighter.output;
  EXPECT_TRUE(says(brighter, "mesh: up to date")) << brighter.output;
  EXPECT_FALSE(says(brighter, "render: up to date")) << brighter.output;
  EXPECT_FALSE(says(brighter, "film: up to date")) << brighter.output;
  const auto lit = frames_of(out);
  for (const auto& [name, bytes] : frames) EXPECT_NE(lit.at(name), bytes) << name;
  EXPECT_NE(read_file(out / "melt.mp4"), film);
  EXPECT_NE(read_file(out / "handoff/environment.hdr"), sky);
  // Another mesh of the object: the frames again.
  write_cube(m_dir / "cube.obj", 0.008, 0.025);
  const auto bigger = thaw(run);
  ASSERT_EQ(bigger.exit_code, 0) << bigger.output;
  EXPECT_TRUE(says(bigger, "mesh: up to date")) << bigger.output;
  EXPECT_FALSE(says(bigger, "render: up to date")) << bigger.output;
  EXPECT_NE(frames_of(out).at("frame_000000.png"), lit.at("frame_000000.png"));
  EXPECT_TRUE(says(thaw(run), "render: up to date"));
}

TEST_F(ThawRun, AChangedShapeObjResimulates) {
  const fs::path out = m_dir / "out";
  const fs::path cube = fs::path(THAW_SOURCE_DIR) / "tests/src/pipeline/data/tiny_cube.toml";
  std::string text = read_file(cube);
  const std::string box = "outer  = { kind = \"box\", size_m = [0.02, 0.02, 0.02] }";
  ASSERT_NE(text.find(box), std::string::npos);
  text.replace(text.find(box), box.size(),
               "outer = { kind = \"obj\", file = \"ice.obj\", translate_m = [0.0, -0.011, 0.0] }");
  text.replace(text.find("duration_s = 480.0"), 18, "duration_s = 120.0");
  std::ofstream(m_dir / "obj_cube.toml") << text;
  write_cube(m_dir / "ice.obj", 0.02, 0.0);
  const std::vector<std::string> run{
      "run", (m_dir / "obj_cube.toml").string(), "--out", out.string(), "--stage", "simulate"};
  const auto first = thaw(run);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string summary = read_file(out / "sim/summary.json");
  EXPECT_TRUE(says(thaw(run), "simulate: up to date"));
  write_cube(m_dir / "ice.obj", 0.022, 0.0);
  const auto bigger = thaw(run);
  ASSERT_EQ(bigger.exit_code, 0) << bigger.output;
  EXPECT_FALSE(says(bigger, "simulate: up to date")) << bigger.output;
  EXPECT_NE(read_file(out / "sim/summary.json"), summary);
  // A shape file that is gone is reported by the parser before any work (one line, exit 2).
  fs::remove(m_dir / "ice.obj");
  const auto gone = thaw(run);
  EXPECT_EQ(gone.exit_code, 2) << gone.output;
  EXPECT_TRUE(says(gone, "ice.obj")) << gone.output;
}

// Issue 27 item 4: one frame's progress counts its tiles, with an ETA before it ends.
TEST_F(ThawRun, OneFrameCountsItsTilesWithAnEta) {
  const fs::path out = m_dir / "out";
  const auto r =
      thaw({"run", kTiny.string(), "--out", out.string(), "--frames", "2", "--size", "160x96"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // 160x96 in 16-pixel tiles: 10 x 6.
  EXPECT_TRUE(says(r, "[3/5] render: frame 2, tiles: 60/60 done in ")) << r.output;
  // A line part-way, between the first tile and the last, has an ETA.
  std::istringstream lines(r.output);
  int part_way = 0;
  for (std::string line; std::getline(lines, line);) {
    const std::string head = "[3/5] render: frame 2, tiles: ";
    if (line.rfind(head, 0) != 0 || line.find("done in") != std::string::npos) continue;
    const long n = std::stol(line.substr(head.size()));
    if (n == 0 || n == 60) continue;
    ++part_way;
    EXPECT_EQ(line.find("ETA ?"), std::string::npos) << line;
    EXPECT_NE(line.find(" s elapsed, ETA "), std::string::npos) << line;
  }
  EXPECT_GE(part_way, 5) << r.output;
  // Several frames count frames.
  const auto two =
      thaw({"run", kTiny.string(), "--out", out.string(), "--frames", "0,1", "--size", "160x96"});
  EXPECT_TRUE(says(two, "[3/5] render: 2/2 done in ")) << two.output;
}

TEST_F(ThawRun, KilledDuringRenderAndRestartedGivesByteIdenticalFrames) {
  // Heavier frames so the render stage lasts long enough to be interrupted.
  const fs::path heavy = heavy_scenario(m_dir);
  const fs::path reference = m_dir / "reference", killed = m_dir / "killed";
  ASSERT_EQ(thaw({"run", heavy.string(), "--out", reference.string(), "-q"}).exit_code, 0);

  const int status = signal_once_a_frame_is_written(
      {kThaw.string(), "run", heavy.string(), "--out", killed.string(), "-q"}, killed, SIGKILL,
      false);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be killed";
  EXPECT_FALSE(fs::exists(killed / "melt.mp4"));

  const auto resumed = thaw({"run", heavy.string(), "--out", killed.string()});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("simulate: up to date"), std::string::npos) << resumed.output;
  EXPECT_EQ(frames_of(killed), frames_of(reference));
  EXPECT_EQ(count_video_frames(killed / "melt.mp4"), 6);
  expect_no_temporaries(killed);
}

// Ctrl-C (SIGINT) and SIGTERM end a run at its next safe point: exit code 130, one line saying
// how to resume, no temporary or half-written file; the rerun resumes and its frames are
// byte-identical to those of an uninterrupted run (issue 12).
TEST_F(ThawRun, InterruptedBySignalEndsCleanlyAndResumesByteIdentical) {
  const fs::path heavy = heavy_scenario(m_dir);
  const fs::path reference = m_dir / "reference";
  ASSERT_EQ(thaw({"run", heavy.string(), "--out", reference.string(), "-q"}).exit_code, 0);

  for (const int signal_number : {SIGINT, SIGTERM}) {
    const fs::path out = m_dir / ("interrupted_" + std::to_string(signal_number));
    const fs::path err = m_dir / "stderr.txt";
    const int status = signal_once_a_frame_is_written(
        {kThaw.string(), "run", heavy.string(), "--out", out.string(), "-q"}, out, signal_number,
        false, err);
    ASSERT_TRUE(WIFEXITED(status)) << "ended by the signal instead of handling it";
    EXPECT_EQ(WEXITSTATUS(status), 130);
    const std::string message = read_file(err);
    EXPECT_NE(message.find("thaw: interrupted; run the same command again to resume\n"),
              std::string::npos)
        << message;
    EXPECT_FALSE(fs::exists(out / "melt.mp4"));
    EXPECT_LT(frames_of(out).size(), 6u) << "the run finished before the signal";
    expect_no_temporaries(out);

    const auto resumed = thaw({"run", heavy.string(), "--out", out.string()});
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_NE(resumed.output.find("simulate: up to date"), std::string::npos) << resumed.output;
    EXPECT_EQ(frames_of(out), frames_of(reference));
    EXPECT_EQ(read_file(out / "sim/interfaces.csv"), read_file(reference / "sim/interfaces.csv"));
    EXPECT_EQ(read_file(out / "sim/mesh/manifest.json"),
              read_file(reference / "sim/mesh/manifest.json"));
    EXPECT_EQ(count_video_frames(out / "melt.mp4"), 6);
  }
}

TEST_F(ThawRun, MissingFfmpegIsAClearErrorAndTheFramesAreKept) {
  const fs::path empty_path = m_dir / "bin";
  fs::create_directories(empty_path);
  const fs::path out = m_dir / "out";
  const auto r = run_process({"env", "PATH=" + empty_path.string(), kThaw.string(), "run",
                              kTiny.string(), "--out", out.string(), "-q"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("ffmpeg not found"), std::string::npos) << r.output;
  EXPECT_EQ(frames_of(out).size(), 4u);
  EXPECT_FALSE(fs::exists(out / "melt.mp4"));
}

TEST_F(ThawRun, InvalidScenarioIsReportedBeforeAnyWork) {
  const fs::path bad = variant(m_dir, "[film]\nfps = 4.0", "[film]\nfsp = 4.0");
  const fs::path out = m_dir / "out";
  const auto r = thaw({"run", bad.string(), "--out", out.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("film.fsp"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("unknown key"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));

  const fs::path bad_medium =
      variant(m_dir, "[render.shell]", "[render.shell]\nice_medium = \"glass\"");
  const auto m = thaw({"run", bad_medium.string(), "--out", out.string()});
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_NE(m.output.find("render.shell.ice_medium"), std::string::npos) << m.output;
}

TEST_F(ThawRun, OutputFolderThatIsAFile) {
  const fs::path file = m_dir / "file";
  std::ofstream(file) << "x";
  const auto r = thaw({"run", kTiny.string(), "--out", file.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("not a directory"), std::string::npos) << r.output;
}

TEST_F(ThawRun, ExrFramesBesideThePngsWithLayersAndFrameTimes) {
  // [film] frames_format = "exr" (issue 13): each frame also as EXR, read back by OpenEXR; the
  // film is still made (from the PNGs). The frame times are the film's: 0 first, increasing.
  const fs::path out = m_dir / "out";
  const fs::path scenario = variant(m_dir, "frames = 4", "frames = 4\nframes_format = \"exr\"");
  const auto r = thaw({"run", scenario.string(), "--out", out.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(count_video_frames(out / "melt.mp4"), 4);
  double previous_time = -1.0;
  for (int k = 0; k < 4; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d", k);
    ASSERT_TRUE(fs::exists(out / "frames" / (std::string(name) + ".png"))) << name;
    const fs::path exr = out / "frames" / (std::string(name) + ".exr");
    ASSERT_TRUE(fs::exists(exr)) << name;
    Imf::InputFile in(exr.c_str());
    const Imf::Header& h = in.header();
    for (const char* c : {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z", "id.object", "id.medium"})
      EXPECT_NE(h.channels().findChannel(c), nullptr) << c;
    const double t = h.typedAttribute<Imf::DoubleAttribute>("thaw.simulatedTime_s").value();
    if (k == 0) {
      EXPECT_EQ(t, 0.0);
    }
    EXPECT_GT(t, previous_time);
    previous_time = t;
    EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("thaw.sceneFile").value(), scenario.string());
  }
  // Unknown formats: one line naming the file and the key, exit code 2, nothing written.
  const fs::path bad = variant(m_dir, "frames = 4", "frames = 4\nframes_format = \"tiff\"");
  const fs::path bad_out = m_dir / "bad";
  const auto b = thaw({"run", bad.string(), "--out", bad_out.string()});
  EXPECT_EQ(b.exit_code, 2) << b.output;
  EXPECT_NE(b.output.find("frames_format"), std::string::npos) << b.output;
  EXPECT_NE(b.output.find(bad.string()), std::string::npos) << b.output;
  EXPECT_EQ(std::count(b.output.begin(), b.output.end(), '\n'), 1) << b.output;
  EXPECT_FALSE(fs::exists(bad_out / "frames"));
}

}  // namespace
}  // namespace thaw::pipeline

namespace thaw::pipeline {
namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(ThawRun, FrameSubsetsTogetherEqualTheWholeRunAndTheLastOneMakesTheFilm) {
  const fs::path whole = m_dir / "whole", parts = m_dir / "parts";
  const auto reference = thaw({"run", kTiny.string(), "--out", whole.string()});
  ASSERT_EQ(reference.exit_code, 0) << reference.output;
  // thaw run prints the simulation's events as thaw simulate does.
  EXPECT_TRUE(contains(reference.output, "event break_through at t = ")) << reference.output;

  // As two Slurm array tasks would: frames 1 and 3, then 0 and 2. Each meshes only its frames'
  // steps (kept in sim/mesh.partial/); no sim/mesh until a whole run.
  const auto odd = thaw({"run", kTiny.string(), "--out", parts.string(), "--frames", "1:3:2"});
  ASSERT_EQ(odd.exit_code, 0) << odd.output;
  EXPECT_TRUE(
      contains(odd.output, "for the 2 selected frames' steps only (a whole run meshes all 4)"))
      << odd.output;
  EXPECT_TRUE(contains(odd.output, "render: 2/2 done")) << odd.output;
  EXPECT_TRUE(contains(odd.output, "waits for every frame (2 of 4 rendered)")) << odd.output;
  EXPECT_FALSE(fs::exists(parts / "melt.mp4"));
  EXPECT_FALSE(fs::exists(parts / "sim/mesh"));
  EXPECT_EQ(frames_of(parts).size(), 2u);
  const auto sim_time = fs::last_write_time(parts / "sim/interfaces.csv");

  const auto even = thaw({"run", kTiny.string(), "--out", parts.string(), "--frames", "0:2:2"});
  ASSERT_EQ(even.exit_code, 0) << even.output;
  EXPECT_TRUE(contains(even.output, "simulate: up to date")) << even.output;
  EXPECT_TRUE(contains(even.output, "for the 2 selected frames' steps only")) << even.output;
  EXPECT_EQ(fs::last_write_time(parts / "sim/interfaces.csv"), sim_time);
  EXPECT_EQ(frames_of(parts), frames_of(whole));  // byte-identical frames
  EXPECT_EQ(count_video_frames(parts / "melt.mp4"), 4);
  EXPECT_EQ(read_file(parts / "melt.mp4"), read_file(whole / "melt.mp4"));
  EXPECT_TRUE(contains(even.output, "inspect: waits for every step's meshes")) << even.output;
  EXPECT_FALSE(fs::exists(parts / "plot.png"));

  // The whole run meshes every step (the kept form reused), renders nothing, writes the rest.
  const auto rest = thaw({"run", kTiny.string(), "--out", parts.string()});
  ASSERT_EQ(rest.exit_code, 0) << rest.output;
  EXPECT_TRUE(contains(rest.output, "render: up to date")) << rest.output;
  EXPECT_TRUE(contains(rest.output, "film: up to date")) << rest.output;
  for (const auto& e : fs::directory_iterator(whole / "sim/mesh"))
    EXPECT_EQ(read_file(e.path()), read_file(parts / "sim/mesh" / e.path().filename()))
        << e.path().filename();
  EXPECT_FALSE(fs::exists(parts / "sim/mesh.partial"));
  EXPECT_EQ(read_file(parts / "plot.png"), read_file(whole / "plot.png"));

  // --fps re-encodes the film only.
  const auto faster = thaw({"run", kTiny.string(), "--out", parts.string(), "--fps", "8"});
  ASSERT_EQ(faster.exit_code, 0) << faster.output;
  EXPECT_TRUE(contains(faster.output, "render: up to date")) << faster.output;
  EXPECT_TRUE(contains(faster.output, "film: encoding 4 frames")) << faster.output;
  EXPECT_NE(read_file(parts / "melt.mp4"), read_file(whole / "melt.mp4"));
  EXPECT_EQ(count_video_frames(parts / "melt.mp4"), 4);
}

TEST_F(ThawRun, StageRunsOneStageOnceTheStagesItReadsAreUpToDate) {
  const fs::path out = m_dir / "out";
  const auto one_line_error = [&](const std::vector<std::string>& extra, const std::string& part) {
    std::vector<std::string> args{"run", kTiny.string(), "--out", out.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = thaw(args);
    EXPECT_EQ(r.exit_code, 2) << extra.back() << ": " << r.output;
    EXPECT_TRUE(contains(r.output, part)) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  };
  one_line_error({"--stage", "render"}, "the simulate stage is not up to date");
  EXPECT_FALSE(fs::exists(out));  // nothing written
  for (const auto& [flag, value, part] :
       std::vector<std::array<std::string, 3>>{{"--frames", "4-9", "the film has frames 0-3"},
                                               {"--frames", "3-1", "last frame comes before"},
                                               {"--frames", "1:3:0", "step must be at least 1"},
                                               {"--frames", "one", "expected frames N"},
                                               {"--stage", "bake", "must be simulate, mesh"},
                                               {"--fps", "0", "--fps: must be between 0.01 and"},
                                               {"--fps", "1e-300", "between 0.01 and 240"},
                                               {"--fps", "1000", "and 240 frames per second"}})
    one_line_error({flag, value}, part);
  EXPECT_FALSE(fs::exists(out));

  ASSERT_EQ(thaw({"run", kTiny.string(), "--out", out.string(), "--stage", "simulate"}).exit_code,
            0);
  EXPECT_TRUE(fs::exists(out / "sim/interfaces.csv"));
  EXPECT_FALSE(fs::exists(out / "sim/mesh"));
  ASSERT_EQ(thaw({"run", kTiny.string(), "--out", out.string(), "--stage", "mesh"}).exit_code, 0);
  EXPECT_TRUE(fs::exists(out / "sim/mesh/manifest.json"));
  EXPECT_FALSE(fs::exists(out / "frames"));
  ASSERT_EQ(
      thaw({"run", kTiny.string(), "--out", out.string(), "--stage", "render", "--frames", "0"})
          .exit_code,
      0);
  EXPECT_EQ(frames_of(out).size(), 1u);
  one_line_error({"--stage", "film"}, "the render stage is not up to date");
  ASSERT_EQ(thaw({"run", kTiny.string(), "--out", out.string(), "--stage", "render"}).exit_code, 0);
  EXPECT_FALSE(fs::exists(out / "melt.mp4"));
  ASSERT_EQ(thaw({"run", kTiny.string(), "--out", out.string(), "--stage", "film"}).exit_code, 0);
  EXPECT_EQ(count_video_frames(out / "melt.mp4"), 4);
  EXPECT_FALSE(fs::exists(out / "plot.png"));
  ASSERT_EQ(thaw({"run", kTiny.string(), "--out", out.string(), "--stage", "inspect"}).exit_code,
            0);
  EXPECT_TRUE(fs::exists(out / "plot.png"));
  one_line_error({"--stage", "mesh", "--force"}, "--force");
}

TEST_F(ThawRun, ASimulationThatRunsOutOfIceSaysWhyItStoppedShort) {
  const fs::path scenario = variant(m_dir, "duration_s = 600.0", "duration_s = 20000.0");
  const auto r = thaw({"run", scenario.string(), "--out", (m_dir / "out").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "[1/5] simulate: 2/4 frame times: the ice is gone at t = "))
      << r.output;
  EXPECT_TRUE(contains(r.output, "render: 2/2 done")) << r.output;
}

}  // namespace
}  // namespace thaw::pipeline

namespace thaw::pipeline {
namespace {

/// The `v` lines of an OBJ file.
std::vector<std::array<double, 3>> obj_vertices(const fs::path& p) {
  std::vector<std::array<double, 3>> v;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("v ", 0) == 0) {
      std::array<double, 3> x{};
      std::istringstream(line.substr(2)) >> x[0] >> x[1] >> x[2];
      v.push_back(x);
    }
  return v;
}

TEST_F(ThawRun, HandOffMeshesSitWhereTheFilmShowsThem) {
  const fs::path out = m_dir / "out";
  // An older run's world-space copies (handoff/obj/) go: the hand-off keeps one copy of each mesh.
  fs::create_directories(out / "handoff/obj");
  std::ofstream(out / "handoff/obj/shell_outer_000000.obj") << "# an older run's copy\n";
  const auto r = thaw({"run", kTiny.string(), "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, (out / "handoff/blender_scene.py").string())) << r.output;
  EXPECT_FALSE(fs::exists(out / "handoff/obj"));
  // handoff/surfaces.json names the mesh stage's own OBJs with the renderer's placement.
  const auto listing = nlohmann::json::parse(read_file(out / "handoff/surfaces.json"));
  EXPECT_EQ(listing["format"], "thaw-surfaces/1");
  const nlohmann::json* outer = nullptr;
  for (const auto& s : listing["surfaces"])
    if (s["label"] == "shell outer surface") outer = &s;
  ASSERT_NE(outer, nullptr) << listing.dump(1);
  int placed = 0;
  for (long step = 0; step < 4; ++step) {
    char name[64];
    std::snprintf(name, sizeof name, "step_%06ld_outer.obj", step);
    const auto& entry = (*outer)["frames"][static_cast<std::size_t>(step)];
    if (!fs::exists(out / "sim/mesh" / name)) {  // vanished: no surface in that frame
      EXPECT_TRUE(entry.is_null()) << step;
      continue;
    }
    ASSERT_FALSE(entry.is_null()) << step;
    EXPECT_EQ(entry["file"], std::string("sim/mesh/") + name);
    EXPECT_EQ(entry["scale"], 1.0);
    const auto local = obj_vertices(out / "sim/mesh" / name);
    ASSERT_FALSE(local.empty());
    ++placed;
    // tiny.toml rests the shell on the floor y = 0 at x = z = 0: x and z unchanged, every point
    // moved up by the same amount, the lowest one onto the floor. The renderer places the mesh
    // from its float positions, so "on the floor" holds to float rounding: 2^-24 of |y|.
    const auto t = entry["translate_m"].get<std::array<double, 3>>();
    EXPECT_EQ(t[0], 0.0);
    EXPECT_EQ(t[2], 0.0);
    double lowest = local[0][1] + t[1], largest = 0;
    for (const auto& v : local) {
      lowest = std::min(lowest, v[1] + t[1]);
      largest = std::max(largest, std::abs(v[1]));
    }
    EXPECT_NEAR(lowest, 0.0, largest * std::ldexp(1.0, -24)) << step;
  }
  EXPECT_GE(placed, 3);
  // The ParaView series has the same placement and the vertex normals as point data.
  const std::string vtp = read_file(out / "meshes_vtp/step_000001_outer.vtp");
  EXPECT_TRUE(contains(vtp, "Normals=\"Normals\"")) << vtp.substr(0, 600);
}

TEST_F(ThawRun, BlenderHandOffCarriesTheIcesScattering) {
  // Cloudy ice (issue 26) reaches Blender as the inside medium's scattering coefficient and
  // Henyey-Greenstein asymmetry of each interface, as given in the scene.
  const fs::path scenario = tiny_variant(
      m_dir, {{"[render.media.ice]\nior = 1.31",
               "[render.media.ice]\nior = 1.31\nscattering_per_m = 30.0\nasymmetry = 0.86"}});
  const fs::path out = m_dir / "out";
  const auto r = thaw({"run", scenario.string(), "--out", out.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string script = read_file(out / "handoff/blender_scene.py");
  const std::string open = "THAW = json.loads(r\'\'\'";
  const auto from = script.find(open), to = script.find("\'\'\')", from);
  ASSERT_NE(from, std::string::npos);
  const auto data =
      nlohmann::json::parse(script.substr(from + open.size(), to - from - open.size()));
  int cloudy = 0, clear = 0;
  for (const auto& face : data["interfaces"]) {
    if (face["inside"] == "ice") {
      EXPECT_DOUBLE_EQ(face["scattering_per_m"].get<double>(), 30.0) << face.dump();
      EXPECT_DOUBLE_EQ(face["scattering_g"].get<double>(), 0.86) << face.dump();
      ++cloudy;
    } else {
      EXPECT_EQ(face["scattering_per_m"].get<double>(), 0.0) << face.dump();
      ++clear;
    }
  }
  EXPECT_GE(cloudy, 1) << data["interfaces"].dump(1);
  EXPECT_GE(clear, 1) << data["interfaces"].dump(1);
}

}  // namespace
}  // namespace thaw::pipeline
