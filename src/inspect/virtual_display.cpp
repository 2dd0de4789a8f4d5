#include "src/inspect/virtual_display.h"

#include <X11/Xlib.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <optional>

#include "base/error.h"
#include "base/subprocess.h"

extern char** environ;

namespace thaw::inspect {
namespace {

// One Xvfb per process, shared by all leases (a screenshot and a plot in one run reuse it).
struct VirtualServer {
  std::mutex mutex;
  int leases = 0;
  pid_t pid = -1;
  std::string display;
  std::optional<std::string> saved_display;  // $DISPLAY before we replaced it
};

VirtualServer& server() {
  static VirtualServer s;
  return s;
}

/// Starts `Xvfb -displayfd FD` and returns ":N" once the server has announced it is ready.
std::string start_xvfb(const std::string& exe, const std::string& purpose, pid_t& pid_out) {
  int fds[2];
  if (::pipe(fds) != 0) throw UserError("", "", purpose + ": pipe: " + std::strerror(errno));
  ::fcntl(fds[0], F_SETFD, FD_CLOEXEC);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  const std::string fd_arg = std::to_string(fds[1]);
  std::vector<std::string> argv = {
      exe, "-displayfd", fd_arg, "-screen", "0", "1920x1080x24", "-nolisten", "tcp", "-noreset"};
  std::vector<char*> args;
  for (auto& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = ::posix_spawn(&pid, exe.c_str(), &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (rc != 0) {
    ::close(fds[0]);
    throw UserError(exe, "",
                    purpose + " needs an X display; cannot start Xvfb: " + std::strerror(rc));
  }
  // Xvfb writes the display number and a newline once it accepts connections.
  std::string number;
  const auto deadline_ms = 20000;
  int waited_ms = 0;
  while (waited_ms < deadline_ms) {
    pollfd p{fds[0], POLLIN, 0};
    const int r = ::poll(&p, 1, 100);
    if (r < 0 && errno == EINTR) continue;
    if (r == 0) {
      waited_ms += 100;
      continue;
    }
    char c = 0;
    const ssize_t n = ::read(fds[0], &c, 1);
    if (n <= 0 || c == '\n') break;
    number += c;
  }
  ::close(fds[0]);
  if (number.empty()) {
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    throw UserError(exe, "", purpose + " needs an X display; Xvfb did not start");
  }
  pid_out = pid;
  return ":" + number;
}

}  // namespace

bool display_available() {
  const char* d = std::getenv("DISPLAY");
  if (d == nullptr || *d == '\0') return false;
  Display* x = XOpenDisplay(nullptr);
  if (x == nullptr) return false;
  XCloseDisplay(x);
  return true;
}

bool rendering_possible() {
  {
    std::lock_guard<std::mutex> lock(server().mutex);
    if (server().leases > 0) return true;
  }
  return display_available() || find_executable("Xvfb").has_value();
}

DisplayLease::DisplayLease(const std::string& purpose) {
  VirtualServer& s = server();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (s.leases > 0) {  // our own Xvfb is running and $DISPLAY points at it
    ++s.leases;
    m_display = s.display;
    m_virtual = true;
    return;
  }
  if (display_available()) {
    m_display = std::getenv("DISPLAY");
    return;
  }
  const auto xvfb = find_executable("Xvfb");
  if (!xvfb)
    throw UserError("", "",
                    purpose +
                        " needs an X display (Debian's VTK renders through X only): $DISPLAY "
                        "is not usable and Xvfb is not installed (apt-get install xvfb, or "
                        "run under xvfb-run -a, or set DISPLAY)");
  pid_t pid = -1;
  const std::string display = start_xvfb(xvfb->string(), purpose, pid);
  if (const char* old = std::getenv("DISPLAY"))
    s.saved_display = old;
  else
    s.saved_display.reset();
  ::setenv("DISPLAY", display.c_str(), 1);
  s.pid = pid;
  s.display = display;
  s.leases = 1;
  m_display = display;
  m_virtual = true;
}

DisplayLease::~DisplayLease() {
  if (!m_virtual) return;
  VirtualServer& s = server();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (--s.leases > 0) return;
  if (s.saved_display)
    ::setenv("DISPLAY", s.saved_display->c_str(), 1);
  else
    ::unsetenv("DISPLAY");
  ::kill(s.pid, SIGTERM);
  int status = 0;
  while (::waitpid(s.pid, &status, 0) < 0 && errno == EINTR) {
  }
  s.pid = -1;
}

}  // namespace thaw::inspect
