#pragma once
// Long library calls from Python: the work runs on a worker thread while the calling thread
// waits with the GIL released, so other Python threads run meanwhile. Every 20 ms the waiting
// thread takes the GIL back to run Python's signal handlers (PyErr_CheckSignals: Ctrl-C raises
// KeyboardInterrupt there) and the caller's progress callback. On KeyboardInterrupt (or an
// exception from the callback) it sets thaw's interrupt flag (base/interrupt.h), which the
// solvers, the mesher and the renderer poll at their safe points; the work then ends by throwing
// thaw::Interrupted, the flag is cleared, and the Python exception is raised: the next call
// starts clean. The callback always runs on the calling thread, never on a worker.
// The interrupt flag is the process's: an interrupted call interrupts any other call that runs
// at the same moment in another Python thread.
#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <future>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "base/interrupt.h"
#include "base/progress.h"
#include "base/progress_observer.h"

namespace thaw::python {

/// Progress as the work reports it through base/progress.h's observer: the last (title, done,
/// total) seen, read by the waiting thread. Lock-free but for the title (a short string).
class ProgressMailbox {
 public:
  void post(const char* title, std::int64_t done, std::int64_t total) noexcept {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_title = title;
    m_done = done;
    m_total = total;
    ++m_version;
  }
  /// The latest post if it is newer than the last one taken.
  bool take(std::string& title, std::int64_t& done, std::int64_t& total) {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_version == m_taken) return false;
    m_taken = m_version;
    title = m_title;
    done = m_done;
    total = m_total;
    return true;
  }

 private:
  std::mutex m_mutex;
  std::string m_title;
  std::int64_t m_done = 0, m_total = 0;
  std::uint64_t m_version = 0, m_taken = 0;
};

/// Runs work() as described above and returns its value; its exceptions propagate (translated
/// by errors.cpp). `progress`, if not None, is called as progress(stage, done, total) with the
/// reports of every thaw progress bar inside the work (quiet or not).
template <typename Work>
auto call_blocking(Work&& work, const pybind11::object& progress = pybind11::none())
    -> decltype(work()) {
  namespace py = pybind11;
  using Value = decltype(work());
  ProgressMailbox mailbox;
  const bool observe = !progress.is_none();
  if (observe)
    set_progress_observer(
        [](void* box, const char* title, std::int64_t done, std::int64_t total) noexcept {
          static_cast<ProgressMailbox*>(box)->post(title, done, total);
        },
        &mailbox);
  std::packaged_task<Value()> task(std::forward<Work>(work));
  std::future<Value> result = task.get_future();
  std::optional<py::error_already_set> python_error;
  {
    std::thread worker(std::move(task));
    for (;;) {
      bool ready;
      {
        py::gil_scoped_release release;
        ready = result.wait_for(std::chrono::milliseconds(20)) == std::future_status::ready;
      }
      if (!python_error && observe) {
        std::string title;
        std::int64_t done = 0, total = 0;
        if (mailbox.take(title, done, total)) {
          try {
            progress(title, done, total);
          } catch (py::error_already_set& e) {
            python_error = std::move(e);
            request_interrupt();
          }
        }
      }
      if (ready) break;
      if (!python_error && PyErr_CheckSignals() != 0) {
        python_error.emplace();  // takes the KeyboardInterrupt that the handler raised
        request_interrupt();
      }
    }
    py::gil_scoped_release release;
    worker.join();
  }
  if (observe) set_progress_observer(nullptr, nullptr);
  if (python_error) {
    clear_interrupt_request();
    try {
      result.get();  // thaw::Interrupted, or the value if the work had just finished
    } catch (...) {
    }
    throw std::move(*python_error);
  }
  return result.get();
}

}  // namespace thaw::python
