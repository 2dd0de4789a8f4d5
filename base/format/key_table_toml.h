#pragma once
// One key of a TOML table read by its row (base/key_table.h): a key the table leaves out keeps
// the value the section holds (or takes the row's `absent` value); a present one is read, checked
// by the row's rule and set, and a value the row rejects is the file's error at that key (exit 2);
// a required key the table leaves out is the file's error too.
#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "base/format/toml_table.h"
#include "base/key_table.h"

namespace thaw {

/// "a", "b" or "c": the names of a choice key, for its message.
inline std::string choice_names_text(std::span<const std::string_view> names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += '"';
    out.append(names[i]);
    out += '"';
  }
  return out;
}

/// A unit vector: |v| must be 1 to within 1e-6 relative (a float's worth of rounding in the file).
inline std::array<double, 3> unit_vector(const TomlTable& t, const std::string& key) {
  const std::array<double, 3> v = t.get_vec3(key);
  const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (len == 0.0) t.fail(key, "must not be the zero vector");
  if (std::abs(len - 1.0) > 1e-6)
    t.fail(key, "must be a unit vector (its length is " + std::to_string(len) + ")");
  return v;
}

template <class Section, class Extra>
void read_key(const TomlTable& t, const KeyRow<Section, Extra>& row, Section& s) {
  if (row.applies && !row.applies(s)) return;
  const std::string key(row.name);
  const auto fail_if = [&](const KeyProblem& problem) {
    if (problem) t.fail(key, *problem);
  };
  if (const auto* k = std::get_if<IntegerKey<Section>>(&row.value)) {
    const long long v = t.get_int(key, s.*(k->field));
    if (k->rule) fail_if(k->rule(v));
    s.*(k->field) = static_cast<int>(v);
  } else if (const auto* k = std::get_if<NumberKey<Section>>(&row.value)) {
    const double v = k->required ? t.get_double(key)
                                 : t.get_double(key, k->absent ? k->absent(s) : s.*(k->field));
    if (k->rule) fail_if(k->rule(v));
    s.*(k->field) = v;
  } else if (const auto* k = std::get_if<OptionalIntegerKey<Section>>(&row.value)) {
    if (!t.has(key)) return;
    const long long v = t.get_int(key);
    if (k->rule) fail_if(k->rule(v));
    s.*(k->field) = v;
  } else if (const auto* k = std::get_if<OptionalNumberKey<Section>>(&row.value)) {
    if (!t.has(key)) return;
    const double v = t.get_double(key);
    if (k->rule) fail_if(k->rule(v));
    s.*(k->field) = v;
  } else if (const auto* k = std::get_if<VectorKey<Section>>(&row.value)) {
    if (!k->required && !t.has(key)) return;
    s.*(k->field) = k->unit ? unit_vector(t, key) : t.get_vec3(key);
  } else if (const auto* k = std::get_if<TextKey<Section>>(&row.value)) {
    s.*(k->field) = k->required ? t.get_string(key) : t.get_string(key, s.*(k->field));
  } else if (const auto* k = std::get_if<FlagKey<Section>>(&row.value)) {
    s.*(k->field) = t.get_bool(key, s.*(k->field));
  } else if (const auto* k = std::get_if<ColourKey<Section>>(&row.value)) {
    const std::array<double, 3> c = t.get_vec3(key, s.*(k->field));
    for (double v : c)
      if (v < 0.0) t.fail(key, "colour components must not be negative");
    s.*(k->field) = c;
  } else if (const auto* k = std::get_if<ChoiceKey<Section>>(&row.value)) {
    const std::string name = t.get_string(key, std::string(k->get(s)));
    if (!k->set(s, name)) {
      std::string problem;
      if (k->what.empty()) {
        problem.append("must be ").append(choice_names_text(k->names));
        problem.append(" (got \"").append(name).append("\")");
      } else {
        problem.append("unknown ").append(k->what).append(" '").append(name).append("' (expected ");
        for (std::size_t i = 0; i < k->names.size(); ++i)
          problem.append(i == 0                     ? ""
                         : i + 1 == k->names.size() ? " or "
                                                    : ", ")
              .append(k->names[i]);
        problem.append(")");
      }
      t.fail(key, problem);
    }
  } else if (const auto* k = std::get_if<AutoFlagKey<Section>>(&row.value)) {
    if (!t.has(key)) return;
    if (t.is<bool>(key))
      k->set(s, t.get_bool(key, false));
    else if (t.is<std::string>(key) && t.get_string(key) == "auto")
      k->set(s, std::nullopt);
    else
      t.fail(key, "must be \"auto\", true or false");
  }
}

/// Every row of `rows`, in table order.
template <class Row, class Section>
void read_keys(const TomlTable& t, std::span<const Row> rows, Section& s) {
  for (const Row& row : rows) read_key(t, row, s);
}

}  // namespace thaw
