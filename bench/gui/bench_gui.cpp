// bench_gui: the responsiveness targets of `thaw gui` (issue 14) on the default scenario.
//   1. preview latency: seconds from an edit (the key light's intensity, alternating) to the
//      320x240 image (the first pass of the progressive preview: quick settings), wall time and
//      the CPU time the whole process spent meanwhile (all threads: the GUI thread's parse, the
//      worker's scene build and render; robust under load, where wall time depends on what else
//      the 2 cores serve);
//   2. slider scrub: milliseconds from setting the time slider to the step's frame shown (the 3D
//      view's render thread draws it, src/gui/view_render_thread.h, and the view paints the image
//      it sends), and the GUI thread's own time in setting it, over every step of a run;
//   3. per phase (start-up from just before the window's show(), new objects, edits, orbits,
//      simulation, scrubbing): the longest the GUI thread went without serving its event loop,
//      measured by a 5 ms timer (the gap between two ticks minus the 5 ms period), with the CPU
//      time the GUI thread itself used in that gap, and the most GUI-thread CPU in any gap (a
//      long gap with little CPU is the scheduler serving other processes of a loaded machine,
//      not work on the GUI thread).
// A machine's first run (Mesa's shader cache empty): run it with MESA_SHADER_CACHE_DIR set to a
// new folder (bench/gui/compare_blocks.sh does, alternating two builds).
// Run it under Xvfb (the default without $DISPLAY): Qt's offscreen platform has no OpenGL for
// VTK, so the 3D view is not drawn there and the scrub figures would mean nothing.
// Usage: bench_gui [EDITS=10] [objects|nopreload]. Prints one line per figure; `objects` stops
// after start-up and the new objects; `nopreload`: without the OpenGL driver's preload.
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <QApplication>
#include <QElapsedTimer>
#include <QProgressBar>
#include <QSlider>
#include <QTimer>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "src/gui/main_window.h"
#include "src/gui/opengl_preload.h"
#include "src/gui/shell_view.h"
#include "src/inspect/virtual_display.h"

using thaw::gui::MainWindow;

namespace {

/// Runs the event loop until `done()` or `timeout_ms`; false on timeout. It sleeps between
/// events (the 5 ms watchdog ticker wakes it): a loop of processEvents() without waiting would
/// keep one of the 2 cores busy and slow the preview's render threads down by itself.
template <class Done>
bool wait_until(Done done, int timeout_ms) {
  QElapsedTimer t;
  t.start();
  while (!done()) {
    if (t.elapsed() > timeout_ms) return false;
    QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents);
  }
  return true;
}

double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

/// The calling thread's time spent runnable but waiting for a core so far (Linux's schedstat,
/// its second field) [ms]; 0 where the kernel does not keep it.
double thread_runqueue_wait_ms() {
  std::FILE* f = std::fopen("/proc/thread-self/schedstat", "r");
  if (!f) return 0;
  unsigned long long run_ns = 0, wait_ns = 0;
  const int n = std::fscanf(f, "%llu %llu", &run_ns, &wait_ns);
  std::fclose(f);
  return n == 2 ? 1e-6 * static_cast<double>(wait_ns) : 0;
}

/// The GUI thread's blocks of one phase: the longest (wall) with the GUI thread's CPU in it and
/// its time waiting for a core (runnable, not scheduled: the machine's load), and the most
/// GUI-thread CPU in any block, and the longest block less its waits for a core (what the
/// program itself kept the GUI thread from its event loop: its work and its waits for others).
struct Blocks {
  qint64 longest_ms = 0;
  double longest_cpu_ms = 0, longest_wait_ms = 0, most_cpu_ms = 0, longest_own_ms = 0;
  void add(qint64 gap_ms, double cpu_ms, double wait_ms) {
    if (gap_ms > longest_ms)
      longest_ms = gap_ms, longest_cpu_ms = cpu_ms, longest_wait_ms = wait_ms;
    most_cpu_ms = std::max(most_cpu_ms, cpu_ms);
    longest_own_ms = std::max(longest_own_ms, static_cast<double>(gap_ms) - wait_ms);
  }
  /// e.g. "172 ms (49 ms CPU, 80 ms waiting for a core)"
  std::string text() const {
    char t[96];
    std::snprintf(t, sizeof t, "%lld ms (%.0f ms CPU, %.0f ms waiting for a core)",
                  static_cast<long long>(longest_ms), longest_cpu_ms, longest_wait_ms);
    return t;
  }
};

void print_stats(const char* what, std::vector<double> v, const char* unit) {
  if (v.empty()) return;
  std::sort(v.begin(), v.end());
  const double median = v[v.size() / 2];
  std::printf("%-44s n=%zu  median %.3f %s  max %.3f %s\n", what, v.size(), median, unit, v.back(),
              unit);
}

/// What the GUI thread is doing while its event loop is late: a thread that every 5 ms, when the
/// 5 ms ticker has not run for 30 ms, samples the GUI thread's state from /proc (its scheduler
/// state, the kernel function it sleeps in and its system call with the first argument's count
/// of poll descriptors: a poll on one descriptor is Qt's xcb waiting for the X server's reply, a
/// futex a lock another thread holds). Counts per kind, printed at the end (diagnosis of blocks
/// that are neither the GUI thread's CPU nor its waits for a core).
class LateLoopSampler {
 public:
  LateLoopSampler() : m_tid(static_cast<long>(::syscall(SYS_gettid))) {
    tick();
    m_thread = std::thread([this] { run(); });
  }
  ~LateLoopSampler() {
    m_stop = true;
    m_thread.join();
  }
  /// The ticker ran (GUI thread).
  void tick() { m_last_tick_ns = now_ns(); }
  std::map<std::string, int> samples() {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_samples;
  }

 private:
  static long long now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
  std::string read(const char* what) const {
    std::ifstream in("/proc/self/task/" + std::to_string(m_tid) + "/" + what);
    std::string text;
    std::getline(in, text);
    return text;
  }
  /// The file (or [heap], [stack:...], "anonymous") of the mapping holding `address`.
  static std::string mapping_of(unsigned long long address) {
    std::ifstream maps("/proc/self/maps");
    std::string line;
    while (std::getline(maps, line)) {
      unsigned long long from = 0, to = 0;
      if (std::sscanf(line.c_str(), "%llx-%llx", &from, &to) != 2) continue;
      if (address < from || address >= to) continue;
      const std::size_t slash = line.find_first_of("/[");
      return slash == std::string::npos ? "anonymous" : line.substr(slash);
    }
    return "unmapped";
  }
  void run() {
    while (!m_stop) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      if (now_ns() - m_last_tick_ns < 30'000'000) continue;
      const std::string stat = read("stat");
      const std::size_t paren = stat.rfind(')');
      const std::string state = paren + 2 < stat.size() ? stat.substr(paren + 2, 1) : "?";
      std::string syscall = read("syscall");
      // "number arg1 arg2 ...": keep the number and, for poll (7) and ppoll (271), the count
      if (const std::size_t sp = syscall.find(' '); sp != std::string::npos) {
        const std::string number = syscall.substr(0, sp);
        std::string count;
        if (number == "7" || number == "271") {
          const std::size_t a = syscall.find(' ', sp + 1), b = syscall.find(' ', a + 1);
          if (a != std::string::npos) count = " nfds " + syscall.substr(a + 1, b - a - 1);
        }
        // for a futex (202), the mapping its word lies in (a library's data: glibc's malloc
        // arena or the dynamic loader's lock; [heap] or an anonymous mapping: a lock of an
        // object, or another thread's malloc arena)
        if (number == "202") {
          const std::size_t a = syscall.find(' ', sp + 1);
          count = " in " + mapping_of(std::stoull(syscall.substr(sp + 1, a - sp - 1), nullptr, 16));
        }
        syscall = "syscall " + number + count;
      }
      std::lock_guard<std::mutex> lock(m_mutex);
      ++m_samples[state + " " + read("wchan") + " " + syscall];
    }
  }
  long m_tid;
  std::atomic<long long> m_last_tick_ns{0};
  std::atomic<bool> m_stop{false};
  std::mutex m_mutex;
  std::map<std::string, int> m_samples;
  std::thread m_thread;
};

}  // namespace

int main(int argc, char** argv) {
  const int n_edits = argc > 1 ? std::atoi(argv[1]) : 10;
  std::unique_ptr<thaw::inspect::DisplayLease> display;
  if (!thaw::inspect::display_available())
    display = std::make_unique<thaw::inspect::DisplayLease>("bench_gui");
  // As `thaw gui` starts (src/gui/gui.cpp): the OpenGL driver loads on a thread of its own
  // while the window is built (src/gui/opengl_preload.h); `bench_gui N nopreload`: without it
  // (show() loads it).
  const std::string mode = argc > 2 ? argv[2] : "";
  const bool preload = mode != "nopreload";
  std::optional<thaw::gui::OpenGlPreload> opengl;
  if (preload) opengl.emplace();
  QApplication app(argc, argv);
  MainWindow w{thaw::gui::ScenarioDocument()};
  QElapsedTimer preload_wait;
  preload_wait.start();
  if (opengl) opengl->wait();
  // (before show(): the window is not on the screen yet; printed with start-up's figures)
  const qint64 preload_wait_ms = preload_wait.elapsed();

  // The GUI thread's blocks: gaps between ticks of a 5 ms timer (minus the period), each with
  // the CPU time the GUI thread itself used in it (CLOCK_THREAD_CPUTIME_ID: a long gap with
  // little of it was the scheduler serving other processes of a loaded machine, or the GUI
  // thread waiting for llvmpipe's rasterizer threads, not work done on the GUI thread). Per
  // phase: the longest block with its CPU, and the most CPU in any block. Blocks over 50 ms are
  // listed with their phase and, during the simulation, its stage (to find what blocks).
  // Measuring starts before show(): it lays the window out and may paint (a QOpenGLWidget paints
  // and makes its OpenGL context inside show()), which the first gap then includes.
  QElapsedTimer clock;
  clock.start();
  Blocks blocks;
  qint64 last_tick = clock.elapsed();
  double last_cpu_ms = thread_cpu_ms(), last_wait_ms = thread_runqueue_wait_ms();
  const char* phase = "start-up";
  auto* sim_progress = w.findChild<QProgressBar*>("simulation_progress");
  std::vector<std::string> long_gaps;
  QTimer ticker;
  ticker.setTimerType(Qt::PreciseTimer);
  LateLoopSampler late;
  QObject::connect(&ticker, &QTimer::timeout, [&] {
    const qint64 now = clock.elapsed();
    const double cpu = thread_cpu_ms(), wait = thread_runqueue_wait_ms();
    const qint64 gap = std::max<qint64>(0, now - last_tick - 5);
    blocks.add(gap, cpu - last_cpu_ms, wait - last_wait_ms);
    if (gap > 50)
      long_gaps.push_back(
          std::string(phase) + " at " + std::to_string(now) + " ms: " + std::to_string(gap) +
          " ms, GUI-thread CPU " + std::to_string(static_cast<int>(cpu - last_cpu_ms)) +
          " ms, waiting for a core " + std::to_string(static_cast<int>(wait - last_wait_ms)) +
          " ms (simulation: " + sim_progress->text().toStdString() + ")");
    last_tick = now;
    late.tick();
    last_cpu_ms = cpu;
    last_wait_ms = wait;
  });
  ticker.start(5);
  w.show();

  // Start-up (its own figure): the initial shell is meshed, the first preview rendered and the
  // scene drawn in the 3D view (on its render thread, which compiles llvmpipe's shaders there),
  // then half a second more.
  if (!wait_until(
          [&] {
            return w.preview_full_size() && w.shell_view().scene_objects() > 0 &&
                   w.shell_view().triangles() > 0 && !w.shell_view().drawing();
          },
          120000))
    return std::puts("no preview"), 1;
  // When the 3D view is complete.
  const qint64 view_complete_ms = clock.elapsed();
  // The last draw's paint and the window's compositing follow in the next turns: still start-up.
  wait_until([] { return false; }, 500);
  const Blocks startup = std::exchange(blocks, {});

  // New objects (issue 14): a box, a sphere and a plane added one by one as the Scene tab's "add"
  // does, each until the view has drawn it. A look no draw made before compiles its shaders (on
  // the view's render thread).
  phase = "new objects";
  const std::size_t objects_before = w.document().array_size("render.objects");
  const std::size_t view_objects_before = w.shell_view().scene_objects();
  for (const char* shape : {"box", "sphere", "plane"}) {
    const std::size_t n = w.shell_view().scene_objects();
    if (!w.add_object(shape)) return std::puts("add_object failed"), 1;
    if (!wait_until(
            [&] { return w.shell_view().scene_objects() == n + 1 && !w.shell_view().drawing(); },
            60000))
      return std::puts("no new object drawn"), 1;
    wait_until([] { return false; }, 300);  // its paint
  }
  std::printf("longest GUI-thread block: start-up %s, new objects %s\n", startup.text().c_str(),
              blocks.text().c_str());
  std::printf("  less its waits for a core [ms]: start-up %.0f, new objects %.0f\n",
              startup.longest_own_ms, blocks.longest_own_ms);
  std::printf("before show(): waited %lld ms for the OpenGL driver's preload%s\n",
              static_cast<long long>(preload_wait_ms), preload ? "" : " (none)");
  std::fflush(stdout);
  if (mode == "objects") {
    for (const std::string& g : long_gaps) std::printf("  GUI thread blocked: %s\n", g.c_str());
    return 0;
  }
  // The edits below are timed on the default scene (issue 14's preview target): the objects go.
  while (w.document().array_size("render.objects") > objects_before)
    w.remove_object(w.document().array_size("render.objects") - 1);
  if (!wait_until([&] { return w.shell_view().scene_objects() == view_objects_before; }, 60000))
    return std::puts("added objects not removed from the view"), 1;
  wait_until([] { return false; }, 300);
  blocks = {};

  phase = "edits";
  std::vector<double> full_s, full_cpu_s, worker_s;
  for (int k = 0; k < n_edits; ++k) {
    // The key light's intensity, as a user tuning the look would.
    QElapsedTimer t;
    t.start();
    const double c0 = process_cpu_s();
    w.apply_edit("render.lights[0].intensity", (k % 2) ? 0.7 : 0.6);
    if (!wait_until([&] { return w.preview_full_size(); }, 60000))
      return std::puts("no 320x240 image"), 1;
    full_s.push_back(t.nsecsElapsed() * 1e-9);
    full_cpu_s.push_back(process_cpu_s() - c0);
    worker_s.push_back(w.preview_seconds());
    // Let the refinement pass run a little, as a user pausing between edits would, then edit
    // again (which cancels it): the edit must not wait for the refinement.
    wait_until([] { return false; }, 150);
  }
  const Blocks edits = std::exchange(blocks, {});

  // Orbits: an interaction's start, 10 camera steps about the focus drawn quick (each until its
  // frame is shown), its end (the view drawn at rest, its camera written back as
  // [render.camera]: the preview restarts and the floor, drawn about the camera's focus, is made
  // anew), as a mouse drag does.
  phase = "orbits";
  std::vector<double> orbit_step_ms;
  thaw::gui::ShellView& view = w.shell_view();
  for (int k = 0; k < std::max(1, n_edits / 2); ++k) {
    const auto c0 = view.camera();
    view.begin_interaction();
    for (int step = 1; step <= 10; ++step) {
      auto c = c0;
      const double a = 0.02 * step * ((k % 2) ? -1 : 1);  // radians about the vertical
      const double x = c0.position[0] - c0.focal_point[0], z = c0.position[2] - c0.focal_point[2];
      c.position[0] = c0.focal_point[0] + std::cos(a) * x - std::sin(a) * z;
      c.position[2] = c0.focal_point[2] + std::sin(a) * x + std::cos(a) * z;
      QElapsedTimer t;
      t.start();
      view.set_camera(c);
      if (!wait_until([&] { return !view.drawing(); }, 5000))
        return std::puts("an orbit step's frame was not shown"), 1;
      orbit_step_ms.push_back(t.nsecsElapsed() * 1e-6);
    }
    view.end_interaction();
    if (!wait_until([&] { return w.preview_full_size(); }, 60000))
      return std::puts("no image after the orbit"), 1;
    wait_until([] { return false; }, 300);  // the floor made anew reaches the view
  }
  const Blocks orbits = std::exchange(blocks, {});

  // A simulated run to scrub.
  phase = "simulation";
  QElapsedTimer sim;
  sim.start();
  if (!w.start_simulation()) return std::puts("cannot simulate"), 1;
  if (!wait_until([&] { return w.simulation_run() != nullptr; }, 600000))
    return std::puts("no run"), 1;
  const double sim_s = sim.nsecsElapsed() * 1e-9;
  const Blocks simulation = std::exchange(blocks, {});
  phase = "scrubbing";
  auto* slider = w.findChild<QSlider*>("time_slider");
  std::vector<double> scrub_ms, scrub_cpu_ms, scrub_process_ms, scrub_shown_ms;
  for (int pass = 0; pass < 2; ++pass)
    for (int k = slider->minimum(); k <= slider->maximum(); ++k) {
      const int value = pass == 0 ? k : slider->maximum() - k;
      if (value == slider->value()) continue;  // no move (the second pass's first step): no draw
      QElapsedTimer t;
      t.start();
      const double c0 = thread_cpu_ms(), p0 = process_cpu_s();
      const long frames = w.shell_view().frames_shown();
      slider->setValue(value);
      scrub_ms.push_back(t.nsecsElapsed() * 1e-6);
      scrub_cpu_ms.push_back(thread_cpu_ms() - c0);
      scrub_process_ms.push_back(1e3 * (process_cpu_s() - p0));
      // ... and its frame on the screen (the view's paint of the render thread's image)
      if (!wait_until(
              [&] { return w.shell_view().frames_shown() > frames && !w.shell_view().drawing(); },
              5000))
        return std::puts("a step's frame was not shown"), 1;
      scrub_shown_ms.push_back(t.nsecsElapsed() * 1e-6);
    }
  const Blocks scrubbing = blocks;

  std::printf("thaw gui responsiveness, default scenario, preview 320x240\n");
  print_stats("edit -> 320x240 image shown [s] (wall)", full_s, "s");
  print_stats("  process CPU meanwhile [s]", full_cpu_s, "s");
  print_stats("request -> 320x240 image [s] (worker clock)", worker_s, "s");
  print_stats("orbit step -> frame shown (quick) [ms]", orbit_step_ms, "ms");
  print_stats("slider -> step requested (GUI thread) [ms]", scrub_ms, "ms");
  print_stats("  GUI-thread CPU meanwhile [ms]", scrub_cpu_ms, "ms");
  print_stats("  process CPU meanwhile [ms] (llvmpipe, preview)", scrub_process_ms, "ms");
  print_stats("slider -> step's frame shown (painted) [ms]", scrub_shown_ms, "ms");
  std::printf("simulate + mesh + load %d steps: %.2f s\n", slider->maximum() + 1, sim_s);
  std::printf("start-up: the 3D view complete after %lld ms\n",
              static_cast<long long>(view_complete_ms));
  std::printf(
      "longest GUI-thread block (its GUI-thread CPU): start-up %s, edits %s, orbits %s, "
      "simulation %s, scrubbing %s\n",
      startup.text().c_str(), edits.text().c_str(), orbits.text().c_str(),
      simulation.text().c_str(), scrubbing.text().c_str());
  std::printf(
      "most GUI-thread CPU in one block [ms]: start-up %.0f, edits %.0f, orbits %.0f, "
      "simulation %.0f, scrubbing %.0f\n",
      startup.most_cpu_ms, edits.most_cpu_ms, orbits.most_cpu_ms, simulation.most_cpu_ms,
      scrubbing.most_cpu_ms);
  std::printf(
      "longest GUI-thread block less its waits for a core [ms]: start-up %.0f, edits %.0f, "
      "orbits %.0f, simulation %.0f, scrubbing %.0f\n",
      startup.longest_own_ms, edits.longest_own_ms, orbits.longest_own_ms,
      simulation.longest_own_ms, scrubbing.longest_own_ms);
  for (const std::string& g : long_gaps) std::printf("  GUI thread blocked: %s\n", g.c_str());
  for (const auto& [what, n] : late.samples())
    std::printf("  GUI thread while its loop was 30+ ms late (5 ms samples): %d x %s\n", n,
                what.c_str());
  return 0;
}
