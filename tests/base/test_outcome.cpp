// base/outcome.h: an outcome keeps its kind, file and key through its text form and rethrow.
#include "base/outcome.h"

#include <gtest/gtest.h>

#include <new>
#include <stdexcept>

#include "base/error.h"
#include "base/interrupt.h"

namespace thaw {
namespace {

TEST(Outcome, CatchesEachKindOfFailureAsItWas) {
  EXPECT_TRUE(Outcome::of([] {}).ok());
  const Outcome user =
      Outcome::of([] { throw UserError("run.toml", "[film] fps", "must be > 0 (got -1)"); });
  EXPECT_EQ(user.kind(), Outcome::Kind::user);
  EXPECT_EQ(user.file(), "run.toml");
  EXPECT_EQ(user.where(), "[film] fps");
  EXPECT_EQ(user.problem(), "must be > 0 (got -1)");
  EXPECT_EQ(user.message(), "run.toml: [film] fps: must be > 0 (got -1)");
  EXPECT_EQ(user.exit_code(), 2);
  const Outcome internal = Outcome::of([] { throw std::logic_error("index out of range"); });
  EXPECT_EQ(internal.kind(), Outcome::Kind::internal);
  EXPECT_EQ(internal.message(), "index out of range");
  EXPECT_EQ(internal.exit_code(), 3);
  EXPECT_EQ(Outcome::of([] { throw std::bad_alloc(); }).message(), "out of memory");
  EXPECT_EQ(Outcome::of([] { throw 7; }).kind(), Outcome::Kind::internal);
  const Outcome stopped = Outcome::of([] { throw Interrupted(); });
  EXPECT_EQ(stopped.kind(), Outcome::Kind::interrupted);
  EXPECT_EQ(stopped.exit_code(), kInterruptedExitCode);
}

TEST(Outcome, TextFormReadsBackExactlyWhateverTheFieldsHold) {
  const Outcome outcomes[] = {Outcome(),
                              Outcome::user("a:b\nc.toml", "", "12:x"),
                              Outcome::user("", "--stage", ""),
                              Outcome::internal("3:broken\0here"),
                              Outcome::internal(""),
                              Outcome::interrupted()};
  for (const Outcome& o : outcomes) EXPECT_EQ(Outcome::from_text(o.to_text()), o) << o.to_text();
  EXPECT_EQ(Outcome().to_text(), "");  // ok is the empty text: the first failure is the first
                                       // non-empty text
}

TEST(Outcome, TextThatIsNoOutcomeIsAnInternalError) {
  for (const char* text :
       {"U3:ab", "X", "X5:abc", "U1:a1:b", "Z", "X1:ab", "U99999999999999999999:"}) {
    const Outcome o = Outcome::from_text(text);
    EXPECT_EQ(o.kind(), Outcome::Kind::internal) << text;
    EXPECT_NE(o.message().find("not an outcome"), std::string::npos) << text;
  }
}

TEST(Outcome, RethrowsWhatItStandsFor) {
  EXPECT_NO_THROW(Outcome().rethrow());
  try {
    Outcome::user("scene.toml", "[image] width", "must be >= 1").rethrow();
    FAIL();
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), "scene.toml");
    EXPECT_EQ(e.where(), "[image] width");
    EXPECT_EQ(e.problem(), "must be >= 1");
  }
  EXPECT_THROW(Outcome::interrupted().rethrow(), Interrupted);
  try {
    Outcome::internal("broken").rethrow();
    FAIL();
  } catch (const UserError&) {
    FAIL() << "an internal error must not become a user error";
  } catch (const std::exception& e) {
    EXPECT_STREQ(e.what(), "broken");
  }
}

}  // namespace
}  // namespace thaw
