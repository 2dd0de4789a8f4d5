// thaw::UserError (base/error.h) and json_problem (base/format/json_error.h): every message
// is one line whatever the user's input holds, and JSON errors carry no library tags.
#include "base/error.h"

#include <gtest/gtest.h>

#include "base/format/json_error.h"

namespace thaw {
namespace {

TEST(UserError, FormatsFileWhereAndProblem) {
  EXPECT_STREQ(UserError("a.toml", "line 3, key 'x'", "must be positive").what(),
               "a.toml: line 3, key 'x': must be positive");
  EXPECT_STREQ(UserError("", "", "bare").what(), "bare");
}

TEST(UserError, ControlCharactersAreEscapedSoTheMessageIsOneLine) {
  // A TOML quoted key or string may hold any of these ("a\nb" = 1).
  const UserError e("dir\nname/a.toml", "key 'a\nb'", "unknown key \"x\ty\r\x1b[31m\x7f\"");
  EXPECT_STREQ(e.what(), "dir\\nname/a.toml: key 'a\\nb': unknown key \"x\\ty\\r\\x1b[31m\\x7f\"");
  // the parts themselves are kept as given (for callers that build other messages)
  EXPECT_EQ(e.where(), "key 'a\nb'");
}

TEST(UserError, TextWithoutControlCharactersIsUnchangedIncludingUtf8) {
  const std::string text = "caf\xc3\xa9 \xe2\x80\x94 100 %";
  EXPECT_EQ(escape_control_characters(text), text);
}

TEST(JsonProblem, DropsTheLibraryTag) {
  try {
    const nlohmann::json j = nlohmann::json::parse("{\"a\": }");
    FAIL() << j.dump();
  } catch (const nlohmann::json::exception& e) {
    const std::string p = json_problem(e);
    EXPECT_EQ(p.find("[json.exception"), std::string::npos) << p;
    EXPECT_NE(p.find("line 1, column 7"), std::string::npos) << p;
  }
  try {
    (void)nlohmann::json::object().at("steps");
    FAIL() << "no exception";
  } catch (const nlohmann::json::exception& e) {
    EXPECT_EQ(json_problem(e), "key 'steps' not found");
  }
}

}  // namespace
}  // namespace thaw
