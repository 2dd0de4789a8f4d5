// Tests of src/inspect/virtual_display: with neither $DISPLAY nor Xvfb the lease is a clear
// UserError; with Xvfb installed and no display, a server is started and stopped.
#include "src/inspect/virtual_display.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "base/error.h"
#include "base/subprocess.h"

namespace thaw::inspect {
namespace {

/// Sets an environment variable for the scope of the object (nullptr: unset).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : m_name(name) {
    if (const char* old = std::getenv(name)) m_old = old;
    if (value)
      ::setenv(name, value, 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (m_old)
      ::setenv(m_name.c_str(), m_old->c_str(), 1);
    else
      ::unsetenv(m_name.c_str());
  }

 private:
  std::string m_name;
  std::optional<std::string> m_old;
};

TEST(VirtualDisplay, NeitherDisplayNorXvfbIsAClearUserError) {
  ScopedEnv display("DISPLAY", nullptr);
  ScopedEnv path("PATH", "/nonexistent");
  EXPECT_FALSE(rendering_possible());
  try {
    DisplayLease lease("--screenshot");
    FAIL() << "expected a UserError";
  } catch (const UserError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--screenshot needs an X display"), std::string::npos) << what;
    EXPECT_NE(what.find("xvfb"), std::string::npos) << what;
  }
}

TEST(VirtualDisplay, StartsAndStopsXvfbWhenNoDisplay) {
  if (!find_executable("Xvfb")) GTEST_SKIP() << "Xvfb not installed";
  ScopedEnv display("DISPLAY", nullptr);
  EXPECT_TRUE(rendering_possible());
  std::string used;
  {
    DisplayLease lease("test");
    EXPECT_TRUE(lease.virtual_server());
    used = lease.display();
    EXPECT_EQ(used.front(), ':');
    EXPECT_TRUE(display_available());
    DisplayLease second("test");  // shares the same server
    EXPECT_EQ(second.display(), used);
  }
  EXPECT_EQ(std::getenv("DISPLAY"), nullptr);  // restored
}

}  // namespace
}  // namespace thaw::inspect
