#pragma once
// A full disk for this test process: while a FileSizeLimit lives, writing a file beyond `bytes`
// fails (EFBIG, as ENOSPC would) instead of raising SIGXFSZ (RLIMIT_FSIZE, setrlimit(2)). CTest
// runs every test in its own process, so no other test sees the limit.
#include <signal.h>
#include <sys/resource.h>

namespace thaw::testing {

class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &m_old);
    m_old_handler = signal(SIGXFSZ, SIG_IGN);
    rlimit limit = m_old;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &m_old);
    signal(SIGXFSZ, m_old_handler);
  }

 private:
  rlimit m_old{};
  sighandler_t m_old_handler = SIG_DFL;
};

}  // namespace thaw::testing
