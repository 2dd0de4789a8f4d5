#include "src/gui/toml_text.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/check.h"
#include "base/number_text.h"

namespace thaw::gui::toml_text {
namespace {

/// The byte offsets of the text's lines (toml++ positions are 1-based lines and columns counted
/// in code points).
class Lines {
 public:
  explicit Lines(const std::string& text) : m_text(text) {
    m_starts.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') m_starts.push_back(i + 1);
  }
  /// Lines of the text (a final line without '\n' counts; an empty text has one).
  std::size_t count() const {
    return m_starts.size() - (!m_text.empty() && m_text.back() == '\n' ? 1 : 0);
  }
  /// Offset of the start of `line` (1-based); one past the last line is the text's end.
  std::size_t start(std::size_t line) const {
    return line - 1 < m_starts.size() ? m_starts[line - 1] : m_text.size();
  }
  std::size_t offset(const toml::source_position& p) const {
    std::size_t at = start(p.line);
    for (toml::source_index c = 1; c < p.column && at < m_text.size(); ++c) {
      ++at;  // one code point: its lead byte, then its continuation bytes 10xxxxxx
      while (at < m_text.size() && (static_cast<unsigned char>(m_text[at]) & 0xC0) == 0x80) ++at;
    }
    return at;
  }
  char at(const toml::source_position& p) const {
    const std::size_t o = offset(p);
    return o < m_text.size() ? m_text[o] : '\0';
  }
  bool blank(std::size_t line) const {
    if (line < 1 || line > count()) return false;
    for (std::size_t i = start(line); i < start(line + 1); ++i)
      if (m_text[i] != ' ' && m_text[i] != '\t' && m_text[i] != '\r' && m_text[i] != '\n')
        return false;
    return true;
  }

 private:
  const std::string& m_text;
  std::vector<std::size_t> m_starts;
};

bool bare_key(const std::string& k) {
  return !k.empty() && std::all_of(k.begin(), k.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
          char u[8];
          std::snprintf(u, sizeof u, "\\u%04X", static_cast<unsigned>(c));
          out += u;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string format_key(const std::string& k) {
  return bare_key(k) ? k : quoted(k);
}

std::string format_double(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::string s = shortest_text(v);                           // shortest exact round trip
  if (s.find_first_of(".e") == std::string::npos) s += ".0";  // stays a float
  return s;
}

/// Whether `n` is an array of tables written as [[headers]] (not a value on one key's line).
bool table_array(const toml::node& n) {
  const toml::array* a = n.as_array();
  if (!a || a->empty()) return false;
  return std::all_of(a->begin(), a->end(), [](const toml::node& e) {
    return e.is_table() && !e.as_table()->is_inline();
  });
}

/// A value as it is written after "key = " (a non-inline table is not one).
bool is_value(const toml::node& n) {
  if (const toml::table* t = n.as_table()) return t->is_inline();
  return !table_array(n);
}

struct Found {
  const toml::node* node = nullptr;
  /// nodes from the root's child down to the node's parent (tables and arrays)
  std::vector<const toml::node*> ancestors;
  /// for each ancestor, the number of key parts that lead to it
  std::vector<std::size_t> depth;
};

/// Follows `key[0..parts)` from `root`; node null when absent (ancestors: those found).
Found find(const toml::table& root, const std::vector<KeyPart>& key, std::size_t parts) {
  Found f;
  const toml::node* at = &root;
  for (std::size_t i = 0; i < parts; ++i) {
    const toml::table* t = at->as_table();
    const toml::node* next = t ? t->get(key[i].name) : nullptr;
    if (next && key[i].index) {
      f.ancestors.push_back(next);
      f.depth.push_back(i + 1);
      const toml::array* a = next->as_array();
      next = a && *key[i].index < a->size() ? a->get(*key[i].index) : nullptr;
    }
    if (!next) return f;
    if (i + 1 < parts) {
      f.ancestors.push_back(next);
      f.depth.push_back(i + 1);
    }
    at = next;
  }
  f.node = at;
  return f;
}

Found find(const toml::table& root, const std::vector<KeyPart>& key) {
  return find(root, key, key.size());
}

/// The outermost inline table or array among `f`'s ancestors (a value written on one key's
/// line): its index in f.ancestors, or nullopt.
std::optional<std::size_t> outermost_inline(const Found& f) {
  for (std::size_t i = 0; i < f.ancestors.size(); ++i) {
    const toml::node* a = f.ancestors[i];
    if (const toml::table* t = a->as_table(); t && t->is_inline()) return i;
    if (a->is_array() && !table_array(*a)) return i;
  }
  return std::nullopt;
}

std::string replace_span(const std::string& text, const Lines& lines, const toml::node& node,
                         const std::string& with) {
  const toml::source_region& s = node.source();
  const std::size_t b = lines.offset(s.begin), e = lines.offset(s.end);
  return text.substr(0, b) + with + text.substr(e);
}

/// Replaces the outermost inline ancestor of `f` (the key prefix `depth` in both tables) by what
/// `expected` holds there.
std::optional<std::string> rewrite_inline(const std::string& text, const Lines& lines,
                                          const Found& f, std::size_t i,
                                          const std::vector<KeyPart>& key,
                                          const toml::table& expected) {
  std::vector<KeyPart> prefix(key.begin(), key.begin() + static_cast<long>(f.depth[i]));
  // The ancestor found after `name` of an indexed part is the array itself.
  const bool is_array_of_part = f.ancestors[i]->is_array() && prefix.back().index;
  if (is_array_of_part) prefix.back().index.reset();
  const Found e = find(expected, prefix);
  if (!e.node) return std::nullopt;
  return replace_span(text, lines, *f.ancestors[i], format_value(*e.node));
}

enum class TableKind { root, headed, implicit, dotted };

TableKind kind_of(const toml::table& t, const toml::table& root, const Lines& lines) {
  if (&t == &root) return TableKind::root;
  const toml::source_region& s = t.source();
  if (lines.at(s.begin) != '[') return TableKind::dotted;
  // A table made implicitly by a sub-table's header ([a.b] makes a) shares that header's source.
  for (const auto& [k, child] : t)
    if ((child.is_table() || child.is_array()) && child.source().begin == s.begin)
      return TableKind::implicit;
  return TableKind::headed;
}

/// The last line of `t`'s own keys (values, inline tables, arrays, dotted sub-keys); 0 if none.
std::size_t content_end_line(const toml::table& t, const toml::table& root, const Lines& lines) {
  std::size_t last = 0;
  for (const auto& [k, child] : t) {
    if (const toml::table* sub = child.as_table(); sub && !sub->is_inline()) {
      if (kind_of(*sub, root, lines) == TableKind::dotted)
        last = std::max(last, content_end_line(*sub, root, lines));
    } else if (!table_array(child)) {
      last = std::max<std::size_t>(last, child.source().end.line);
    }
  }
  return last;
}

/// Inserts `line` (without its '\n') after line `after` (0: at the top).
std::string insert_line(const std::string& text, const Lines& lines, std::size_t after,
                        const std::string& line) {
  std::string out = text;
  const std::size_t at = lines.start(after + 1);
  if (at == out.size() && !out.empty() && out.back() != '\n') out += '\n';
  return out.insert(std::min(at, out.size()), line + "\n");
}

std::string append_section(std::string text, const std::string& section) {
  if (!text.empty() && text.back() != '\n') text += '\n';
  if (!text.empty()) text += '\n';
  return text + section;
}

std::optional<std::string> header_path(const std::vector<KeyPart>& key, std::size_t parts) {
  std::string path;
  for (std::size_t i = 0; i < parts; ++i) {
    if (key[i].index) return std::nullopt;
    if (i) path += '.';
    path += format_key(key[i].name);
  }
  return path;
}

/// The lines `n` occupies in the text, as closed ranges; headers of tables included.
void collect_lines(const toml::node& n, const toml::table& root, const Lines& lines,
                   std::vector<std::pair<std::size_t, std::size_t>>& ranges) {
  if (table_array(n)) {
    for (const toml::node& e : *n.as_array()) collect_lines(e, root, lines, ranges);
    return;
  }
  const toml::table* t = n.as_table();
  if (!t || t->is_inline()) {
    ranges.emplace_back(n.source().begin.line, n.source().end.line);
    return;
  }
  const TableKind kind = kind_of(*t, root, lines);
  if (kind == TableKind::headed) {
    const std::size_t header = t->source().begin.line;
    ranges.emplace_back(header, std::max(header, content_end_line(*t, root, lines)));
  }
  for (const auto& [k, child] : *t) {
    const toml::table* sub = child.as_table();
    const bool own_section =
        table_array(child) ||
        (sub && !sub->is_inline() && kind_of(*sub, root, lines) != TableKind::dotted);
    if (kind != TableKind::headed || own_section) collect_lines(child, root, lines, ranges);
  }
}

/// The text without the lines in `ranges`. A blank line that separated the deleted lines from
/// the text before them goes too when another follows them or they ended the text.
std::string delete_lines(const std::string& text, const Lines& lines,
                         const std::vector<std::pair<std::size_t, std::size_t>>& ranges) {
  const std::size_t n = lines.count();
  std::vector<bool> gone(n + 2, false);
  for (const auto& [b, e] : ranges)
    for (std::size_t l = b; l <= e && l <= n; ++l) gone[l] = true;
  for (const auto& [b, e] : ranges) {
    if (b < 2 || !lines.blank(b - 1) || gone[b - 1]) continue;
    std::size_t after = e + 1;
    while (after <= n && gone[after]) ++after;
    if (after > n)
      gone[b - 1] = true;
    else if (lines.blank(after))
      gone[after] = true;
  }
  std::string out;
  for (std::size_t l = 1; l <= lines.count(); ++l)
    if (!gone[l]) out += text.substr(lines.start(l), lines.start(l + 1) - lines.start(l));
  return out;
}

}  // namespace

std::vector<KeyPart> split_key(const std::string& dotted) {
  std::vector<KeyPart> parts;
  std::stringstream in(dotted);
  std::string item;
  while (std::getline(in, item, '.')) {
    KeyPart p;
    const auto bracket = item.find('[');
    p.name = item.substr(0, bracket);
    if (bracket != std::string::npos) p.index = std::stoul(item.substr(bracket + 1));
    parts.push_back(std::move(p));
  }
  THAW_CHECK(!parts.empty(), "empty key");
  return parts;
}

std::string format_value(const toml::node& n) {
  if (const auto* v = n.as_floating_point()) return format_double(v->get());
  if (const auto* v = n.as_integer()) return std::to_string(v->get());
  if (const auto* v = n.as_boolean()) return v->get() ? "true" : "false";
  if (const auto* v = n.as_string()) return quoted(v->get());
  if (const auto* a = n.as_array()) {
    std::string out = "[";
    for (std::size_t i = 0; i < a->size(); ++i) {
      if (i) out += ", ";
      out += format_value(*a->get(i));
    }
    return out + "]";
  }
  if (const auto* t = n.as_table()) {
    if (t->empty()) return "{}";
    std::string out = "{ ";
    bool first = true;
    for (const auto& [k, v] : *t) {
      if (!first) out += ", ";
      out += format_key(std::string(k.str()));
      out += " = ";
      out += format_value(v);
      first = false;
    }
    return out + " }";
  }
  std::ostringstream other;  // dates and times: toml++'s own form
  n.visit([&](const auto& v) { other << v; });
  return other.str();
}

std::optional<std::string> with_value(const std::string& text, const toml::table& parsed,
                                      const std::vector<KeyPart>& key,
                                      const toml::table& expected) {
  const Lines lines(text);
  std::vector<KeyPart> whole = key;
  if (key.back().index) {
    // An element of an array: its own span when it exists, else the whole array.
    const Found element = find(parsed, key), want = find(expected, key);
    if (element.node && want.node) {
      if (!is_value(*element.node)) return std::nullopt;
      return replace_span(text, lines, *element.node, format_value(*want.node));
    }
    whole.back().index.reset();
  }
  const Found want = find(expected, whole);
  if (!want.node || !is_value(*want.node)) return std::nullopt;
  const Found have = find(parsed, whole);
  if (const auto i = outermost_inline(have))
    return rewrite_inline(text, lines, have, *i, whole, expected);
  if (have.node) {
    if (!is_value(*have.node)) return std::nullopt;
    return replace_span(text, lines, *have.node, format_value(*want.node));
  }
  const std::string line = format_key(whole.back().name) + " = " + format_value(*want.node);
  const Found parent = find(parsed, whole, whole.size() - 1);
  if (!parent.node) {
    // A new table: its header and the key at the end of the file.
    const auto path = header_path(whole, whole.size() - 1);
    if (!path) return std::nullopt;
    return append_section(text, "[" + *path + "]\n" + line + "\n");
  }
  const toml::table* t = parent.node->as_table();
  if (!t) return std::nullopt;
  switch (kind_of(*t, parsed, lines)) {
    case TableKind::root:
      return insert_line(text, lines, content_end_line(*t, parsed, lines), line);
    case TableKind::headed:
      return insert_line(
          text, lines,
          std::max<std::size_t>(t->source().begin.line, content_end_line(*t, parsed, lines)), line);
    case TableKind::implicit: {
      // Defined now, after the sub-table header that made it (TOML allows that order).
      const auto path = header_path(whole, whole.size() - 1);
      if (!path) return std::nullopt;
      return append_section(text, "[" + *path + "]\n" + line + "\n");
    }
    case TableKind::dotted:
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<std::string> without(const std::string& text, const toml::table& parsed,
                                   const std::vector<KeyPart>& key, const toml::table& expected) {
  const Lines lines(text);
  const Found have = find(parsed, key);
  if (!have.node) return text;
  if (const auto i = outermost_inline(have))
    return rewrite_inline(text, lines, have, *i, key, expected);
  if (key.back().index) return std::nullopt;  // an entry of an array of tables: without_table
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  collect_lines(*have.node, parsed, lines, ranges);
  return delete_lines(text, lines, ranges);
}

std::optional<std::string> with_table_appended(const std::string& text, const toml::table& parsed,
                                               const std::vector<KeyPart>& key) {
  const Found have = find(parsed, key);
  if (have.node && !table_array(*have.node)) return std::nullopt;
  if (outermost_inline(have)) return std::nullopt;
  const auto path = header_path(key, key.size());
  if (!path) return std::nullopt;
  return append_section(text, "[[" + *path + "]]\n");
}

std::optional<std::string> without_table(const std::string& text, const toml::table& parsed,
                                         const std::vector<KeyPart>& key, std::size_t index) {
  const Lines lines(text);
  const Found have = find(parsed, key);
  if (!have.node || !table_array(*have.node) || outermost_inline(have)) return std::nullopt;
  const toml::array& a = *have.node->as_array();
  if (index >= a.size()) return text;
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  collect_lines(*a.get(index), parsed, lines, ranges);
  return delete_lines(text, lines, ranges);
}

}  // namespace thaw::gui::toml_text
