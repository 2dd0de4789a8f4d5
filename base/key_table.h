#pragma once
// A section's keys written once (pbrt-v4's ParameterDictionary, Mitsuba 3's props.get beside the
// plugin's documentation, MFEM's OptionsParser::AddOption): one row per key with its name, kind,
// the form's label and unit, the documented default and meaning, the field of the plain struct
// `Section` it sets and the rule that checks it. The parser (base/format/key_table_toml.h), the
// rules, the summaries, the GUI's forms and the docs' key tables all read the rows, so a new key
// is one row plus its use. A section may attach its own columns (`Extra`: the scenario's typical
// ranges, say). Knows nothing of TOML, JSON, Qt or any particular section.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace thaw {

/// What a rule finds wrong with a value ("must be > 0 (got -1)"), or nothing.
using KeyProblem = std::optional<std::string>;

/// An integer, checked by `rule` on its full 64-bit value before it is narrowed to int.
template <class Section>
struct IntegerKey {
  int Section::*field;
  KeyProblem (*rule)(long long) = nullptr;
};
/// A real number and its rule; `absent` (when set) gives the value of a key the file leaves out
/// from the settings read so far ([image] filter_radius follows the filter); `required`: the file
/// must give it.
template <class Section>
struct NumberKey {
  double Section::*field;
  KeyProblem (*rule)(double) = nullptr;
  double (*absent)(const Section&) = nullptr;
  bool required = false;
};
/// An integer or a real number that may be left to the program ("automatic": nullopt).
template <class Section>
struct OptionalIntegerKey {
  std::optional<long long> Section::*field;
  KeyProblem (*rule)(long long) = nullptr;
};
template <class Section>
struct OptionalNumberKey {
  std::optional<double> Section::*field;
  KeyProblem (*rule)(double) = nullptr;
};
/// Three numbers: a point, or with `unit` a direction of length 1 (to within 1e-6); `required`:
/// the file must give it.
template <class Section>
struct VectorKey {
  std::array<double, 3> Section::*field;
  bool unit = false;
  bool required = false;
};
/// A name (a medium's, a file's), checked where it is used; `required`: the file must give it.
template <class Section>
struct TextKey {
  std::string Section::*field;
  bool required = false;
};
template <class Section>
struct FlagKey {
  bool Section::*field;
};
/// A linear RGB colour, each component non-negative.
template <class Section>
struct ColourKey {
  std::array<double, 3> Section::*field;
};
/// One of a list of names; `set` returns false for a name not in the list. `what` (when set)
/// names the list in the message for another name: "unknown light kind 'x' (expected point or
/// sphere)"; else "must be \"point\" or \"sphere\" (got \"x\")".
template <class Section>
struct ChoiceKey {
  std::span<const std::string_view> names;
  std::string_view (*get)(const Section&);
  bool (*set)(Section&, std::string_view name);
  std::string_view what = {};
};
/// true, false or "auto" (nullopt).
template <class Section>
struct AutoFlagKey {
  std::optional<bool> (*get)(const Section&);
  void (*set)(Section&, std::optional<bool> value);
};

template <class Section, class Extra = std::monostate>
struct KeyRow {
  std::string_view name;          ///< the key within its section
  std::string_view label;         ///< the form's label
  std::string_view unit;          ///< unit of the value ("px", "W/(m K)"), "" for none
  std::string_view default_text;  ///< the default as the docs write it
  std::string_view doc;           ///< its meaning (and accepted range), as the docs write it
  std::variant<IntegerKey<Section>, NumberKey<Section>, FlagKey<Section>, ColourKey<Section>,
               ChoiceKey<Section>, AutoFlagKey<Section>, OptionalIntegerKey<Section>,
               OptionalNumberKey<Section>, VectorKey<Section>, TextKey<Section>>
      value;
  Extra extra{};  ///< the section's own columns
  /// Whether the key belongs to the section as read so far (a sphere light's radius); a key that
  /// does not is left unread, so the file's unused-key check names it. Null: always.
  bool (*applies)(const Section&) = nullptr;
};

/// Sets `value` to the enumerator at `name`'s place in `names` (a choice key's names, in the
/// order of the enumerators); false, and `value` unchanged, if `name` is not one of them.
template <class Enum>
bool set_enum_by_name(Enum& value, std::span<const std::string_view> names, std::string_view name) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) {
      value = static_cast<Enum>(i);
      return true;
    }
  return false;
}

/// The row named `name`, or nullptr.
template <class Row>
const Row* find_key(std::span<const Row> rows, std::string_view name) {
  for (const Row& r : rows)
    if (r.name == name) return &r;
  return nullptr;
}

/// The rows' names, in table order.
template <class Row>
std::vector<std::string> key_names(std::span<const Row> rows) {
  std::vector<std::string> out;
  for (const Row& r : rows) out.emplace_back(r.name);
  return out;
}

/// The row's rule applied to its value in `section` (integer and real keys, an automatic one
/// passing; the other kinds are checked as they are read or where they are used), or nothing.
template <class Section, class Extra>
KeyProblem key_problem(const KeyRow<Section, Extra>& row, const Section& section) {
  if (const auto* k = std::get_if<IntegerKey<Section>>(&row.value))
    return k->rule ? k->rule(section.*(k->field)) : std::nullopt;
  if (const auto* k = std::get_if<NumberKey<Section>>(&row.value))
    return k->rule ? k->rule(section.*(k->field)) : std::nullopt;
  if (const auto* k = std::get_if<OptionalIntegerKey<Section>>(&row.value))
    return k->rule && section.*(k->field) ? k->rule(*(section.*(k->field))) : std::nullopt;
  if (const auto* k = std::get_if<OptionalNumberKey<Section>>(&row.value))
    return k->rule && section.*(k->field) ? k->rule(*(section.*(k->field))) : std::nullopt;
  return std::nullopt;
}

/// The docs' rows of a key table, "| `key` | default | doc |" each, the first key written after
/// `first_prefix` (e.g. "[image] "), the others bare: what a test holds the docs' page to.
template <class Row>
std::string key_docs_rows(std::span<const Row> rows, std::string_view first_prefix) {
  std::string out;
  bool first = true;
  for (const Row& r : rows) {
    out.append("| `").append(first ? first_prefix : std::string_view()).append(r.name);
    out.append("` | ").append(r.default_text).append(" | ").append(r.doc).append(" |\n");
    first = false;
  }
  return out;
}

}  // namespace thaw
