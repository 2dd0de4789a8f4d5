#pragma once
// The scenario being edited in `thaw gui`: the file's text and the TOML document parsed from it
// (toml++), so that Save writes back every key, including those the GUI has no widget for, with
// the file's comments and layout, and what is saved loads back identically. Every edit sets one
// dotted key: the text is edited in place (toml_text.h: only that value's span or line changes)
// and kept if it parses to exactly the edited document, else the document is re-serialised.
// check() then runs the scenario parser of `thaw run` (src/pipeline/run_scenario.h, which calls
// sim/ and render/ parsers) on the text: the GUI's messages are the files' messages (their line
// numbers those of the saved file), no rule is written twice. Qt-free.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "base/outcome.h"
#include "src/pipeline/run_scenario.h"

namespace toml {
inline namespace v3 {
class table;
}
}  // namespace toml

namespace thaw::gui {

/// A value the GUI writes: a number, an integer, a flag, a name or a 3-vector (colour, point).
using TomlValue = std::variant<double, long long, bool, std::string, std::array<double, 3>>;

/// The result of checking the document: the parsed scenario, or the parser's one-line problem and
/// the dotted key it names ("" when the message names no key), and the failure as it was thrown
/// (file, where, problem), to be thrown again as itself.
struct ScenarioCheck {
  std::optional<pipeline::RunScenario> scenario;
  std::string key, message;
  Outcome failure;
  bool ok() const { return scenario.has_value(); }
};

class ScenarioDocument {
 public:
  /// The built-in default scenario (data/scenarios/default.toml).
  ScenarioDocument();
  ScenarioDocument(const ScenarioDocument&);
  ScenarioDocument& operator=(const ScenarioDocument&);
  ~ScenarioDocument();

  /// Parses `text`; malformed TOML throws thaw::UserError naming `source_name`. A document whose
  /// values break a rule is accepted (check() reports it), so a file can be opened and fixed.
  static ScenarioDocument from_text(const std::string& text, const std::string& source_name);
  static ScenarioDocument load(const std::filesystem::path& path);

  /// Sets `dotted_key` ("shell.outer_radius_m", "render.camera.position"), creating tables on
  /// the way. An array of tables is addressed as "render.objects[2].radius".
  void set(const std::string& dotted_key, const TomlValue& value);
  /// Removes a key (or a whole table); no-op if absent.
  void remove(const std::string& dotted_key);
  bool has(const std::string& dotted_key) const;
  /// Number of entries in an array of tables ("render.objects"), 0 if absent.
  std::size_t array_size(const std::string& dotted_key) const;
  /// Appends an empty table to the array of tables `dotted_key`; returns its index.
  std::size_t append_table(const std::string& dotted_key);
  /// Erases entry `index` of the array of tables `dotted_key`.
  void erase_table(const std::string& dotted_key, std::size_t index);
  /// The value at `dotted_key` as the GUI edits it (integers stay integers, arrays of three
  /// numbers are vectors), or nullopt when absent or of another type.
  std::optional<TomlValue> value(const std::string& dotted_key) const;
  /// The string at `dotted_key`, or `fallback`.
  std::string string_or(const std::string& dotted_key, const std::string& fallback) const;
  /// Names of the sub-tables of table `dotted_key` (e.g. the materials), in document order.
  std::vector<std::string> table_keys(const std::string& dotted_key) const;

  /// The document as TOML: the loaded text with the edits made in place (comments kept).
  std::string text() const;
  /// False once an edit could not be made in place (a layout toml_text.h does not edit): the
  /// text was then re-serialised by toml++, without the comments.
  bool layout_kept() const { return m_layout_kept; }
  /// Runs the scenario parser on text().
  ScenarioCheck check() const;
  /// Writes text() to `path` atomically after check(); throws thaw::UserError (the check's
  /// message) and writes nothing when the scenario is not valid.
  void save(const std::filesystem::path& path) const;

  /// The name the parser reports problems under (the file, or "<built-in default>").
  const std::string& source_name() const { return m_source_name; }
  void set_source_name(std::string name) { m_source_name = std::move(name); }

 private:
  explicit ScenarioDocument(std::nullptr_t);
  /// The text for the table `expected` made from the current one, or nullopt.
  using TextEdit = std::function<std::optional<std::string>(const toml::table& expected)>;
  /// Applies `change` to the document and `in_text` to the text, keeping the edited text only
  /// if it parses to the changed document.
  void edit(const std::function<void(toml::table&)>& change, const TextEdit& in_text);

  /// parsed from m_text (toml++ keeps each node's source position for the in-place edits)
  std::unique_ptr<toml::table> m_root;
  std::string m_text;
  std::string m_source_name;
  bool m_layout_kept = true;
};

/// The dotted key named in a parser message ("line 3, key 'shell.inner_radius_m'" -> the key),
/// or "" when it names none.
std::string key_of_problem(const std::string& where);

}  // namespace thaw::gui
