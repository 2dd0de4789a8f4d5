#include "base/format/toml_table.h"

#include <toml++/toml.h>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "base/error.h"
#include "base/text_file.h"

namespace thaw {

namespace {
std::string number_text(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}
}  // namespace

TomlTable::TomlTable(std::shared_ptr<Shared> shared, const toml::table* table, std::string prefix)
    : m_shared(std::move(shared)), m_table(table), m_prefix(std::move(prefix)) {}

TomlTable TomlTable::parse_string(const std::string& text, const std::string& source_name) {
  auto shared = std::make_shared<Shared>();
  shared->source = source_name;
  try {
    shared->root = std::make_shared<toml::table>(toml::parse(text, source_name));
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw UserError(source_name,
                    "line " + std::to_string(b.line) + ", column " + std::to_string(b.column),
                    "malformed TOML: " + std::string(e.description()));
  }
  return TomlTable(shared, shared->root.get(), "");
}

TomlTable TomlTable::parse_file(const std::filesystem::path& path) {
  return parse_string(read_text_file(path, "a TOML file", kMaxTomlFileBytes), path.string());
}

std::string TomlTable::full_key(const std::string& key) const {
  return m_prefix.empty() ? key : m_prefix + "." + key;
}

const toml::node* TomlTable::find(const std::string& key) const {
  if (!key.empty()) m_shared->asked.insert(full_key(key));
  return m_table->get(key);
}

namespace {

/// Levenshtein distance (insertions, deletions, substitutions of one character each) between a
/// and b, by the two-row dynamic programme (Wagner & Fischer 1974).
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1), next(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    next[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      next[j] = std::min({row[j] + 1, next[j - 1] + 1, row[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(row, next);
  }
  return row[b.size()];
}

/// The known key of the same table nearest to the unknown `key` (dotted path), if it is a likely
/// typo: at most a third of the longer name's characters differ (at least 1).
std::string nearest_known_key(const std::set<std::string>& known, const std::string& key) {
  const std::size_t dot = key.rfind('.');
  const std::string prefix = dot == std::string::npos ? "" : key.substr(0, dot + 1);
  const std::string name = key.substr(prefix.size());
  std::string best;
  std::size_t best_distance = 0;
  for (const std::string& k : known) {
    if (k.size() <= prefix.size() || k.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string candidate = k.substr(prefix.size());
    if (candidate.find_first_of(".[") != std::string::npos || candidate == name) continue;
    const std::size_t d = edit_distance(name, candidate);
    const std::size_t allowed =
        std::max<std::size_t>(1, std::max(name.size(), candidate.size()) / 3);
    if (d <= allowed && (best.empty() || d < best_distance)) best = candidate, best_distance = d;
  }
  return best;
}

}  // namespace

std::string TomlTable::where(const std::string& key) const {
  std::string w;
  const toml::node* n = key.empty() ? static_cast<const toml::node*>(m_table) : find(key);
  if (n && n->source().begin.line > 0) w = "line " + std::to_string(n->source().begin.line) + ", ";
  return w + "key '" + (key.empty() ? m_prefix : full_key(key)) + "'";
}

void TomlTable::fail(const std::string& key, const std::string& problem) const {
  throw UserError(m_shared->source, where(key), problem);
}

void TomlTable::mark(const std::string& key) const {
  m_shared->used.insert(full_key(key));
}

bool TomlTable::has(const std::string& key) const {
  return find(key) != nullptr;
}

template <>
bool TomlTable::is<bool>(const std::string& key) const {
  const toml::node* n = find(key);
  return n && n->is_boolean();
}
template <>
bool TomlTable::is<std::string>(const std::string& key) const {
  const toml::node* n = find(key);
  return n && n->is_string();
}
template <>
bool TomlTable::is<double>(const std::string& key) const {
  const toml::node* n = find(key);
  return n && n->is_number();
}
template <>
bool TomlTable::is<std::int64_t>(const std::string& key) const {
  const toml::node* n = find(key);
  return n && n->is_integer();
}
template <>
bool TomlTable::is<TomlTable>(const std::string& key) const {
  const toml::node* n = find(key);
  return n && n->is_table();
}

std::vector<std::string> TomlTable::keys() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : *m_table) out.emplace_back(k.str());
  return out;
}

double TomlTable::as_finite_double(const std::string& key, const toml::node& node) const {
  double v;
  if (auto d = node.as_floating_point()) {
    v = d->get();
  } else if (auto i = node.as_integer()) {
    v = static_cast<double>(i->get());
  } else {
    fail(key, "expected a number");
  }
  if (!std::isfinite(v)) fail(key, "must be a finite number (got " + number_text(v) + ")");
  return v;
}

double TomlTable::get_double(const std::string& key) const {
  const toml::node* n = find(key);
  if (!n) fail(key, "required key is missing");
  mark(key);
  return as_finite_double(key, *n);
}

double TomlTable::get_double(const std::string& key, double fallback) const {
  return has(key) ? get_double(key) : fallback;
}

std::int64_t TomlTable::get_int(const std::string& key) const {
  const toml::node* n = find(key);
  if (!n) fail(key, "required key is missing");
  mark(key);
  if (auto i = n->as_integer()) return i->get();
  if (auto d = n->as_floating_point()) {
    const double v = d->get();
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 9e15)
      return static_cast<std::int64_t>(v);
  }
  fail(key, "expected an integer");
}

std::int64_t TomlTable::get_int(const std::string& key, std::int64_t fallback) const {
  return has(key) ? get_int(key) : fallback;
}

bool TomlTable::get_bool(const std::string& key, bool fallback) const {
  const toml::node* n = find(key);
  if (!n) return fallback;
  mark(key);
  if (auto b = n->as_boolean()) return b->get();
  fail(key, "expected true or false");
}

std::string TomlTable::get_string(const std::string& key) const {
  const toml::node* n = find(key);
  if (!n) fail(key, "required key is missing");
  mark(key);
  if (auto s = n->as_string()) return s->get();
  fail(key, "expected a string");
}

std::string TomlTable::get_string(const std::string& key, const std::string& fallback) const {
  return has(key) ? get_string(key) : fallback;
}

std::vector<double> TomlTable::get_doubles(const std::string& key) const {
  const toml::node* n = find(key);
  if (!n) fail(key, "required key is missing");
  mark(key);
  const toml::array* arr = n->as_array();
  if (!arr) fail(key, "expected an array of numbers");
  std::vector<double> out;
  for (const auto& e : *arr) out.push_back(as_finite_double(key, e));
  return out;
}

std::array<double, 3> TomlTable::get_vec3(const std::string& key) const {
  const auto v = get_doubles(key);
  if (v.size() != 3) fail(key, "expected 3 numbers [x, y, z], got " + std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

std::array<double, 3> TomlTable::get_vec3(const std::string& key,
                                          const std::array<double, 3>& fallback) const {
  return has(key) ? get_vec3(key) : fallback;
}

std::vector<std::array<double, 3>> TomlTable::get_vec3s(const std::string& key) const {
  const toml::node* n = find(key);
  if (!n) fail(key, "required key is missing");
  mark(key);
  const toml::array* arr = n->as_array();
  if (!arr) fail(key, "expected an array of [x, y, z] arrays");
  std::vector<std::array<double, 3>> out;
  for (const auto& e : *arr) {
    const toml::array* inner = e.as_array();
    if (!inner || inner->size() != 3) fail(key, "expected an array of [x, y, z] arrays");
    std::array<double, 3> v{};
    for (int i = 0; i < 3; ++i) v[i] = as_finite_double(key, *inner->get(i));
    out.push_back(v);
  }
  return out;
}

TomlTable TomlTable::table(const std::string& key) const {
  auto t = optional_table(key);
  if (!t) fail(key, "required table is missing");
  return *t;
}

std::optional<TomlTable> TomlTable::optional_table(const std::string& key) const {
  const toml::node* n = find(key);
  if (!n) return std::nullopt;
  mark(key);
  const toml::table* t = n->as_table();
  if (!t) fail(key, "expected a table");
  return TomlTable(m_shared, t, full_key(key));
}

std::vector<TomlTable> TomlTable::array_of_tables(const std::string& key) const {
  std::vector<TomlTable> out;
  const toml::node* n = find(key);
  if (!n) return out;
  mark(key);
  const toml::array* arr = n->as_array();
  if (!arr) fail(key, "expected an array of tables ([[" + full_key(key) + "]])");
  std::size_t index = 0;
  for (const auto& e : *arr) {
    const toml::table* t = e.as_table();
    if (!t) fail(key, "expected an array of tables ([[" + full_key(key) + "]])");
    const std::string prefix = full_key(key) + "[" + std::to_string(index++) + "]";
    m_shared->used.insert(prefix);
    out.push_back(TomlTable(m_shared, t, prefix));
  }
  return out;
}

std::string TomlTable::canonical_text() const {
  std::ostringstream os;
  os << *m_table;
  return os.str();
}

double TomlTable::require_positive(const std::string& key, double value) const {
  if (!(value > 0)) fail(key, "must be positive (got " + number_text(value) + ")");
  return value;
}

double TomlTable::require_non_negative(const std::string& key, double value) const {
  if (!(value >= 0)) fail(key, "must not be negative (got " + number_text(value) + ")");
  return value;
}

void TomlTable::check_no_unknown_keys() const {
  // Walk the whole document; any key (or table) whose dotted path was never read is unknown.
  struct Walker {
    const Shared& shared;
    void walk(const toml::table& t, const std::string& prefix) const {
      for (const auto& [k, v] : t) {
        const std::string key =
            prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
        if (!shared.used.count(key)) {
          const auto line = v.source().begin.line;
          const std::string near = nearest_known_key(shared.asked, key);
          throw UserError(
              shared.source,
              (line > 0 ? "line " + std::to_string(line) + ", " : "") + "key '" + key + "'",
              near.empty() ? "unknown key" : "unknown key (did you mean '" + near + "'?)");
        }
        if (const toml::table* sub = v.as_table()) {
          walk(*sub, key);
        } else if (const toml::array* arr = v.as_array()) {
          std::size_t i = 0;
          for (const auto& e : *arr) {
            const std::string ik = key + "[" + std::to_string(i++) + "]";
            if (const toml::table* et = e.as_table())
              if (shared.used.count(ik)) walk(*et, ik);
          }
        }
      }
    }
  };
  Walker{*m_shared}.walk(*m_shared->root, "");
}

}  // namespace thaw
