#pragma once
// Checked access to a TOML document: every value read is typed and validated (finite numbers,
// ranges), every key read is remembered, and check_no_unknown_keys() turns any key that nobody
// read into an error naming it (pbrt-v4 ParameterDictionary::ReportUnused). A typo never falls
// back silently to a default. Errors are thaw::UserError("file", "line N, key 'a.b'", problem).
// Knows nothing about what the keys mean.
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace toml {
inline namespace v3 {
class table;
class node;
}  // namespace v3
}  // namespace toml

namespace thaw {

class TomlTable {
 public:
  /// Parses a file; malformed TOML or a missing file throws UserError naming it.
  static TomlTable parse_file(const std::filesystem::path& path);
  /// Parses text; `source_name` stands for the file name in messages.
  static TomlTable parse_string(const std::string& text, const std::string& source_name);

  const std::string& source_name() const { return m_shared->source; }
  /// Dotted path of this table ("" for the root, "media.ice", "objects[2]").
  const std::string& path() const { return m_prefix; }

  bool has(const std::string& key) const;
  /// True when the key is present and holds a T: bool, std::string, double (any number),
  /// std::int64_t (an integer), or TomlTable (a table). Does not mark the key as read, so a
  /// parser can ask before it picks the reading of a key that accepts several types.
  template <typename T>
  bool is(const std::string& key) const;
  /// Keys present in this table, in document order of insertion (not marked as read).
  std::vector<std::string> keys() const;

  double get_double(const std::string& key) const;
  double get_double(const std::string& key, double fallback) const;
  std::int64_t get_int(const std::string& key) const;
  std::int64_t get_int(const std::string& key, std::int64_t fallback) const;
  bool get_bool(const std::string& key, bool fallback) const;
  std::string get_string(const std::string& key) const;
  std::string get_string(const std::string& key, const std::string& fallback) const;
  std::array<double, 3> get_vec3(const std::string& key) const;
  std::array<double, 3> get_vec3(const std::string& key,
                                 const std::array<double, 3>& fallback) const;
  /// An array of finite numbers of any length (integers accepted).
  std::vector<double> get_doubles(const std::string& key) const;
  /// An array of 3-vectors, e.g. checker colours [[r,g,b],[r,g,b]].
  std::vector<std::array<double, 3>> get_vec3s(const std::string& key) const;

  /// A sub-table; required version throws if missing.
  TomlTable table(const std::string& key) const;
  std::optional<TomlTable> optional_table(const std::string& key) const;
  /// An array of tables ([[objects]]); empty if absent.
  std::vector<TomlTable> array_of_tables(const std::string& key) const;

  /// This table re-serialised by toml++ (keys sorted, comments and layout dropped): a canonical
  /// text for fingerprinting a section, so only real edits change it. Marks nothing as read.
  std::string canonical_text() const;

  /// Throws UserError for the first key anywhere in the document that was never read.
  void check_no_unknown_keys() const;

  /// Throws UserError naming this table's `key` (with its line) and `problem`.
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

  // Validation helpers for numbers already read; they call fail() with the value in the message.
  double require_positive(const std::string& key, double value) const;
  double require_non_negative(const std::string& key, double value) const;

 private:
  struct Shared {
    std::string source;
    std::shared_ptr<toml::table> root;
    std::set<std::string> used;
    /// every key looked up, present or not: the known keys an unknown one is compared with
    std::set<std::string> asked;
  };
  TomlTable(std::shared_ptr<Shared> shared, const toml::table* table, std::string prefix);
  const toml::node* find(const std::string& key) const;
  std::string full_key(const std::string& key) const;
  std::string where(const std::string& key) const;
  void mark(const std::string& key) const;
  double as_finite_double(const std::string& key, const toml::node& node) const;

  std::shared_ptr<Shared> m_shared;
  const toml::table* m_table;
  std::string m_prefix;
};

}  // namespace thaw
