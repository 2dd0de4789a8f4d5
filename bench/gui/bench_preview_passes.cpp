// bench_preview_passes: what one pass of `thaw gui`'s progressive preview costs on the default
// scenario's initial shell (the scene build and the render, wall and CPU time of the process),
// for candidate pass settings, interleaved over several rounds so that every variant sees the
// same machine load. Chooses the quick passes (docs/benchmarks.md, "thaw gui"). Qt-free.
// Usage: bench_preview_passes [ROUNDS=5]
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "render/integrator/whitted.h"
#include "render/scene/scene.h"
#include "src/gui/preview_scene.h"
#include "src/gui/shell_step.h"

namespace {

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Variant {
  std::string name;
  thaw::gui::PreviewPass pass;
  std::vector<double> build_wall, render_wall, cpu, build_cpu;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  using namespace thaw;
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 5;
  const pipeline::RunScenario sc = pipeline::default_run_scenario();
  const gui::ShellStep step = gui::initial_shell(sc);
  const int spp = sc.scene.image.samples_per_pixel;
  std::vector<Variant> variants = {
      {"80x60 1 spp", {80, 60, 1, false, false, 0, false}, {}, {}, {}, {}},
      {"160x120 1 spp", {160, 120, 1, false, false, 0, false}, {}, {}, {}, {}},
      {"160x120 quick (the former pass 0)", {160, 120, 1, false, false, 6, true}, {}, {}, {}, {}},
      {"320x240 1 spp, own depth, shadow rays",
       {320, 240, 1, false, false, 0, false},
       {},
       {},
       {},
       {}},
      {"320x240 quick (pass 0)", {320, 240, 1, false, false, 6, true}, {}, {}, {}, {}},
      {"320x240 adaptive + caustics (pass 1)",
       {320, 240, spp, true, true, 0, false},
       {},
       {},
       {},
       {}},
  };
  for (int r = 0; r < rounds; ++r)
    for (Variant& v : variants) {
      const double c0 = cpu_seconds();
      const auto t0 = std::chrono::steady_clock::now();
      const render::Scene scene = render::build_scene(gui::preview_scene(sc, step, {}, v.pass));
      const auto t1 = std::chrono::steady_clock::now();
      v.build_cpu.push_back(cpu_seconds() - c0);
      const render::RenderResult result = render::render(scene, {});
      const auto t2 = std::chrono::steady_clock::now();
      v.cpu.push_back(cpu_seconds() - c0);
      v.build_wall.push_back(std::chrono::duration<double>(t1 - t0).count());
      v.render_wall.push_back(std::chrono::duration<double>(t2 - t1).count());
      (void)result;
    }
  std::printf("preview pass costs, default scenario, initial shell, %d rounds (median)\n", rounds);
  std::printf("%-42s %10s %10s %10s %10s\n", "pass", "build [s]", "(CPU)", "render [s]", "CPU [s]");
  for (const Variant& v : variants)
    std::printf("%-42s %10.3f %10.3f %10.3f %10.3f\n", v.name.c_str(), median(v.build_wall),
                median(v.build_cpu), median(v.render_wall), median(v.cpu));
  return 0;
}
