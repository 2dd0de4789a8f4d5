#pragma once
// In-place edits of a TOML file's text, so that what `thaw gui` saves keeps the file's comments,
// blank lines and key order: an edit rewrites only the span of the value it changes, inserts one
// line after the last key of the table it adds a key to, or deletes the lines of what it removes.
// Each function takes the text, the table parsed from it (toml++ keeps every node's source
// position) and the table the edit should produce, and returns the edited text, or nullopt when
// the text's layout is one it does not edit in place (a key defined by a dotted key, an inline
// array of tables). The caller (ScenarioDocument) parses the result and keeps it only if it is
// equal to the expected table, so a layout these functions misjudge is never saved: the document
// is re-serialised instead. Qt-free.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace toml {
inline namespace v3 {
class table;
class node;
}  // namespace v3
}  // namespace toml

namespace thaw::gui::toml_text {

/// One step of a dotted key: a table key, optionally indexing an array ("objects[2]").
struct KeyPart {
  std::string name;
  std::optional<std::size_t> index;
};

/// "render.objects[2].radius" -> render, objects[2], radius.
std::vector<KeyPart> split_key(const std::string& dotted);

/// A value as TOML text: numbers in their shortest form that reads back exactly (0.1, not
/// 0.10000000000000001; floats keep a '.' or an exponent), arrays and inline tables on one line.
std::string format_value(const toml::node& value);

/// The text with `key` holding what `expected` holds there (a new or changed value; `key` may
/// address an element of an array, "colors[1]").
std::optional<std::string> with_value(const std::string& text, const toml::table& parsed,
                                      const std::vector<KeyPart>& key, const toml::table& expected);

/// The text without `key` (a value, a table with its sub-tables, or an array of tables).
std::optional<std::string> without(const std::string& text, const toml::table& parsed,
                                   const std::vector<KeyPart>& key, const toml::table& expected);

/// The text with an empty table appended to the array of tables `key` ("[[key]]" at the end).
std::optional<std::string> with_table_appended(const std::string& text, const toml::table& parsed,
                                               const std::vector<KeyPart>& key);

/// The text without entry `index` of the array of tables `key` (its header, keys and sub-tables).
std::optional<std::string> without_table(const std::string& text, const toml::table& parsed,
                                         const std::vector<KeyPart>& key, std::size_t index);

}  // namespace thaw::gui::toml_text
