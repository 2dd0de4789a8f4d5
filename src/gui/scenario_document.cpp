#include "src/gui/scenario_document.h"

#include <toml++/toml.h>
#include <fstream>
#include <regex>
#include <sstream>

#include "base/atomic_file.h"
#include "base/check.h"
#include "base/error.h"
#include "base/format/toml_table.h"
#include "src/gui/toml_text.h"

namespace thaw::gui {
namespace {

using toml_text::KeyPart;
using toml_text::split_key;

/// The table holding the last part of `parts`, created on the way when `create`; nullptr if absent.
toml::table* parent_table(toml::table& root, const std::vector<KeyPart>& parts, bool create) {
  toml::table* t = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const KeyPart& p = parts[i];
    if (p.index) {
      toml::array* a = t->get_as<toml::array>(p.name);
      if (!a || *p.index >= a->size()) return nullptr;
      t = a->get_as<toml::table>(*p.index);
    } else {
      toml::table* next = t->get_as<toml::table>(p.name);
      if (!next) {
        if (!create) return nullptr;
        next = t->insert_or_assign(p.name, toml::table{}).first->second.as_table();
      }
      t = next;
    }
    if (!t) return nullptr;
  }
  return t;
}

toml::table parse_toml(const std::string& text, const std::string& source_name) {
  return toml::parse(std::string_view(text), std::string_view(source_name));
}

toml::array* table_array(toml::table& root, const std::string& dotted, bool create) {
  const auto parts = split_key(dotted);
  toml::table* parent = parent_table(root, parts, create);
  if (!parent) return nullptr;
  toml::array* a = parent->get_as<toml::array>(parts.back().name);
  if (!a && create)
    a = parent->insert_or_assign(parts.back().name, toml::array{}).first->second.as_array();
  return a;
}

}  // namespace

ScenarioDocument::ScenarioDocument()
    : ScenarioDocument(from_text(pipeline::default_run_scenario_text(), "<built-in default>")) {}

ScenarioDocument::ScenarioDocument(std::nullptr_t) {}

// A copy parses the text again rather than copying the table: toml++'s copy of a table loses
// the source positions of what inline tables hold (a [shape] body's size_m), which the in-place
// edits need (the copy's first edit of one re-serialised the whole file, without its comments).
// m_root is always the parse of m_text (edit()), so the copy is the same document.
ScenarioDocument::ScenarioDocument(const ScenarioDocument& o)
    : m_root(std::make_unique<toml::table>(parse_toml(o.m_text, o.m_source_name))),
      m_text(o.m_text),
      m_source_name(o.m_source_name),
      m_layout_kept(o.m_layout_kept) {}

ScenarioDocument& ScenarioDocument::operator=(const ScenarioDocument& o) {
  if (this != &o) {
    m_root = std::make_unique<toml::table>(parse_toml(o.m_text, o.m_source_name));
    m_text = o.m_text;
    m_source_name = o.m_source_name;
    m_layout_kept = o.m_layout_kept;
  }
  return *this;
}

ScenarioDocument::~ScenarioDocument() = default;

ScenarioDocument ScenarioDocument::from_text(const std::string& text,
                                             const std::string& source_name) {
  // TomlTable::parse_string reports malformed TOML as thaw's one-line UserError.
  (void)TomlTable::parse_string(text, source_name);
  ScenarioDocument d(std::nullptr_t{});
  d.m_root = std::make_unique<toml::table>(parse_toml(text, source_name));
  d.m_text = text;
  d.m_source_name = source_name;
  return d;
}

ScenarioDocument ScenarioDocument::load(const std::filesystem::path& path) {
  const TomlTable checked = TomlTable::parse_file(path);  // missing or malformed: UserError
  (void)checked;
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw UserError(path.string(), "", "cannot be read");
  return from_text(text.str(), path.string());
}

void ScenarioDocument::edit(const std::function<void(toml::table&)>& change,
                            const TextEdit& in_text) {
  toml::table expected = *m_root;
  change(expected);
  if (const std::optional<std::string> text = in_text(expected)) {
    try {
      toml::table back = parse_toml(*text, m_source_name);
      if (back == expected) {  // the in-place edit made exactly the intended document
        m_text = *text;
        *m_root = std::move(back);
        return;
      }
    } catch (const toml::parse_error&) {
    }
  }
  // A layout the in-place edits do not handle: toml++ writes the document anew.
  std::ostringstream out;
  out << expected << "\n";
  m_text = out.str();
  *m_root = parse_toml(m_text, m_source_name);
  m_layout_kept = false;
}

namespace {

void set_in(toml::table& root, const std::vector<KeyPart>& parts, const TomlValue& value) {
  toml::table* parent = parent_table(root, parts, true);
  THAW_CHECK(parent != nullptr, "no table holds the key");
  const std::string& name = parts.back().name;
  toml::array* array = nullptr;
  if (parts.back().index) {  // an element of an array ("checker.colors[1]"), grown as needed
    array = parent->get_as<toml::array>(name);
    if (!array) array = parent->insert_or_assign(name, toml::array{}).first->second.as_array();
    while (array->size() <= *parts.back().index) array->push_back(toml::array{});
  }
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        auto put = [&](auto&& node) {
          if (array)
            array->replace(array->begin() + static_cast<std::ptrdiff_t>(*parts.back().index),
                           std::forward<decltype(node)>(node));
          else
            parent->insert_or_assign(name, std::forward<decltype(node)>(node));
        };
        if constexpr (std::is_same_v<T, std::array<double, 3>>)
          put(toml::array{v[0], v[1], v[2]});
        else if constexpr (std::is_same_v<T, long long>)
          put(static_cast<std::int64_t>(v));
        else
          put(v);
      },
      value);
}

}  // namespace

void ScenarioDocument::set(const std::string& dotted_key, const TomlValue& value) {
  const auto parts = split_key(dotted_key);
  edit([&](toml::table& t) { set_in(t, parts, value); },
       [&](const toml::table& expected) {
         return toml_text::with_value(m_text, *m_root, parts, expected);
       });
}

void ScenarioDocument::remove(const std::string& dotted_key) {
  const auto parts = split_key(dotted_key);
  edit(
      [&](toml::table& t) {
        if (toml::table* parent = parent_table(t, parts, false)) parent->erase(parts.back().name);
      },
      [&](const toml::table& expected) {
        return toml_text::without(m_text, *m_root, parts, expected);
      });
}

bool ScenarioDocument::has(const std::string& dotted_key) const {
  const auto parts = split_key(dotted_key);
  const toml::table* parent = parent_table(*m_root, parts, false);
  return parent && parent->contains(parts.back().name);
}

std::size_t ScenarioDocument::array_size(const std::string& dotted_key) const {
  const toml::array* a = table_array(*m_root, dotted_key, false);
  return a ? a->size() : 0;
}

std::size_t ScenarioDocument::append_table(const std::string& dotted_key) {
  std::size_t index = 0;
  edit(
      [&](toml::table& t) {
        toml::array* a = table_array(t, dotted_key, true);
        THAW_CHECK(a != nullptr, "not an array of tables");
        a->push_back(toml::table{});
        index = a->size() - 1;
      },
      [&](const toml::table&) {
        return toml_text::with_table_appended(m_text, *m_root, split_key(dotted_key));
      });
  return index;
}

void ScenarioDocument::erase_table(const std::string& dotted_key, std::size_t index) {
  edit(
      [&](toml::table& t) {
        toml::array* a = table_array(t, dotted_key, false);
        if (a && index < a->size()) a->erase(a->begin() + static_cast<std::ptrdiff_t>(index));
        if (a && a->empty()) {
          const auto parts = split_key(dotted_key);
          if (toml::table* parent = parent_table(t, parts, false)) parent->erase(parts.back().name);
        }
      },
      [&](const toml::table&) {
        return toml_text::without_table(m_text, *m_root, split_key(dotted_key), index);
      });
}

std::optional<TomlValue> ScenarioDocument::value(const std::string& dotted_key) const {
  const auto parts = split_key(dotted_key);
  const toml::table* parent = parent_table(*m_root, parts, false);
  if (!parent) return std::nullopt;
  const toml::node* n = parent->get(parts.back().name);
  if (n && parts.back().index) {
    const toml::array* a = n->as_array();
    n = a && *parts.back().index < a->size() ? a->get(*parts.back().index) : nullptr;
  }
  if (!n) return std::nullopt;
  if (const auto* v = n->as_floating_point()) return TomlValue{v->get()};
  if (const auto* v = n->as_integer()) return TomlValue{static_cast<long long>(v->get())};
  if (const auto* v = n->as_boolean()) return TomlValue{v->get()};
  if (const auto* v = n->as_string()) return TomlValue{v->get()};
  if (const auto* a = n->as_array(); a && a->size() == 3) {
    std::array<double, 3> out{};
    for (std::size_t i = 0; i < 3; ++i) {
      const auto d = (*a)[i].value<double>();
      if (!d) return std::nullopt;
      out[i] = *d;
    }
    return TomlValue{out};
  }
  return std::nullopt;
}

std::string ScenarioDocument::string_or(const std::string& dotted_key,
                                        const std::string& fallback) const {
  const auto parts = split_key(dotted_key);
  const toml::table* parent = parent_table(*m_root, parts, false);
  if (!parent) return fallback;
  if (const auto* s = parent->get_as<std::string>(parts.back().name)) return s->get();
  return fallback;
}

std::vector<std::string> ScenarioDocument::table_keys(const std::string& dotted_key) const {
  std::vector<std::string> keys;
  const auto parts = split_key(dotted_key + ".x");
  const toml::table* t = parent_table(*m_root, parts, false);
  if (t)
    for (const auto& [k, v] : *t)
      if (v.is_table()) keys.emplace_back(k.str());
  return keys;
}

std::string ScenarioDocument::text() const {
  return m_text;
}

ScenarioCheck ScenarioDocument::check() const {
  ScenarioCheck c;
  try {
    c.scenario = pipeline::parse_run_scenario(TomlTable::parse_string(text(), m_source_name));
  } catch (const UserError& e) {
    c.key = key_of_problem(e.where());
    c.message = e.what();
    c.failure = Outcome::user(e.file(), e.where(), e.problem());
  }
  return c;
}

void ScenarioDocument::save(const std::filesystem::path& path) const {
  const ScenarioCheck c = check();
  if (!c.ok()) throw UserError(path.string(), "", "not saved: " + c.message);
  write_file_atomic(path, text());
}

std::string key_of_problem(const std::string& where) {
  static const std::regex key_re("key '([^']*)'");
  std::smatch m;
  if (std::regex_search(where, m, key_re)) return m[1].str();
  return "";
}

}  // namespace thaw::gui
