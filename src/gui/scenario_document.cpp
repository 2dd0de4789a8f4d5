#include "src/gui/scenario_document.h"

#include <toml++/toml.h>
#include <regex>
#include <sstream>

#include "src/common/atomic_file.h"
#include "src/common/check.h"
#include "src/common/error.h"
#include "src/common/toml_table.h"

namespace thaw::gui {
namespace {

/// One step of a dotted key: a table key, optionally indexing an array of tables ("objects[2]").
struct KeyPart {
  std::string name;
  std::optional<std::size_t> index;
};

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

ScenarioDocument::ScenarioDocument(const ScenarioDocument& o)
    : m_root(std::make_unique<toml::table>(*o.m_root)), m_source_name(o.m_source_name) {}

ScenarioDocument& ScenarioDocument::operator=(const ScenarioDocument& o) {
  if (this != &o) {
    m_root = std::make_unique<toml::table>(*o.m_root);
    m_source_name = o.m_source_name;
  }
  return *this;
}

ScenarioDocument::~ScenarioDocument() = default;

ScenarioDocument ScenarioDocument::from_text(const std::string& text,
                                             const std::string& source_name) {
  // TomlTable::parse_string reports malformed TOML as thaw's one-line UserError.
  (void)TomlTable::parse_string(text, source_name);
  ScenarioDocument d(std::nullptr_t{});
  d.m_root = std::make_unique<toml::table>(toml::parse(text, source_name));
  d.m_source_name = source_name;
  return d;
}

ScenarioDocument ScenarioDocument::load(const std::filesystem::path& path) {
  const TomlTable checked = TomlTable::parse_file(path);  // missing or malformed: UserError
  (void)checked;
  ScenarioDocument d(std::nullptr_t{});
  d.m_root = std::make_unique<toml::table>(toml::parse_file(path.string()));
  d.m_source_name = path.string();
  return d;
}

void ScenarioDocument::set(const std::string& dotted_key, const TomlValue& value) {
  const auto parts = split_key(dotted_key);
  toml::table* parent = parent_table(*m_root, parts, true);
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

void ScenarioDocument::remove(const std::string& dotted_key) {
  const auto parts = split_key(dotted_key);
  if (toml::table* parent = parent_table(*m_root, parts, false)) parent->erase(parts.back().name);
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
  toml::array* a = table_array(*m_root, dotted_key, true);
  THAW_CHECK(a != nullptr, "not an array of tables");
  a->push_back(toml::table{});
  return a->size() - 1;
}

void ScenarioDocument::erase_table(const std::string& dotted_key, std::size_t index) {
  toml::array* a = table_array(*m_root, dotted_key, false);
  if (a && index < a->size()) a->erase(a->begin() + static_cast<std::ptrdiff_t>(index));
  if (a && a->empty()) remove(dotted_key);
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
  std::ostringstream out;
  out << *m_root << "\n";
  return out.str();
}

ScenarioCheck ScenarioDocument::check() const {
  ScenarioCheck c;
  try {
    c.scenario = pipeline::parse_run_scenario(TomlTable::parse_string(text(), m_source_name));
  } catch (const UserError& e) {
    c.key = key_of_problem(e.where());
    c.message = e.what();
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
