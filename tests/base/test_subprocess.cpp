#include "base/subprocess.h"

#include <gtest/gtest.h>

#include "base/error.h"

namespace thaw {
namespace {

TEST(Subprocess, ExitCodesAndOutput) {
  EXPECT_EQ(run_process({"true"}).exit_code, 0);
  EXPECT_EQ(run_process({"false"}).exit_code, 1);
  const auto r = run_process({"sh", "-c", "echo out; echo err >&2; exit 7"});
  EXPECT_EQ(r.exit_code, 7);
  EXPECT_NE(r.output.find("out"), std::string::npos);
  EXPECT_NE(r.output.find("err"), std::string::npos);
}

TEST(Subprocess, ArgumentsAreNotShellParsed) {
  const auto r = run_process({"echo", "a b;c", "$HOME"});
  EXPECT_EQ(r.output, "a b;c $HOME\n");
}

TEST(Subprocess, MissingProgramIsAUserError) {
  EXPECT_FALSE(find_executable("thaw-no-such-program").has_value());
  EXPECT_THROW(run_process({"thaw-no-such-program"}), UserError);
}

}  // namespace
}  // namespace thaw
