#pragma once
// A KeyForm field built from a key table's row (base/key_table.h): its label and unit, its kind
// (number, integer, flag, choice, colour) and the value the parsed scenario holds, so that a form
// spells no key, label or unit of its own. Knows no particular section.
#include <QString>
#include <QStringList>
#include <string>
#include <variant>

#include "base/check.h"
#include "base/key_table.h"
#include "src/gui/key_form.h"

namespace thaw::gui {

/// The section a row's value lives in, within a parsed scenario.
template <class Section>
using SectionOf = const Section& (*)(const pipeline::RunScenario&);

/// The row's label and unit as a form shows them: "Width [px]".
template <class Row>
QString key_row_label(const Row& row) {
  QString label = QString::fromUtf8(row.label.data(), static_cast<int>(row.label.size()));
  if (!row.unit.empty())
    label += " [" + QString::fromUtf8(row.unit.data(), static_cast<int>(row.unit.size())) + "]";
  return label;
}

/// Adds `row` to `form`, bound to the document's dotted key `prefix + row.name`.
template <class Section, class Extra>
void add_key_row(KeyForm* form, const KeyRow<Section, Extra>& row, const std::string& prefix,
                 SectionOf<Section> section) {
  const QString label = key_row_label(row);
  const std::string key = prefix + std::string(row.name);
  if (const auto* k = std::get_if<IntegerKey<Section>>(&row.value)) {
    const auto field = k->field;
    form->add_integer(label, key, [field, section](const pipeline::RunScenario& s) {
      return TomlValue{static_cast<long long>(section(s).*field)};
    });
  } else if (const auto* k = std::get_if<NumberKey<Section>>(&row.value)) {
    const auto field = k->field;
    form->add_number(label, key, [field, section](const pipeline::RunScenario& s) {
      return TomlValue{section(s).*field};
    });
  } else if (const auto* k = std::get_if<FlagKey<Section>>(&row.value)) {
    const auto field = k->field;
    form->add_flag(label, key, [field, section](const pipeline::RunScenario& s) {
      return TomlValue{section(s).*field};
    });
  } else if (const auto* k = std::get_if<ChoiceKey<Section>>(&row.value)) {
    QStringList names;
    for (std::string_view n : k->names)
      names << QString::fromUtf8(n.data(), static_cast<int>(n.size()));
    const auto get = k->get;
    form->add_choice(label, key, names, [get, section](const pipeline::RunScenario& s) {
      return TomlValue{std::string(get(section(s)))};
    });
  } else if (const auto* k = std::get_if<ColourKey<Section>>(&row.value)) {
    const auto field = k->field;
    form->add_vector(
        label, key,
        [field, section](const pipeline::RunScenario& s) { return TomlValue{section(s).*field}; },
        true);
  } else {
    THAW_CHECK(false, "a form has a field for every kind of key it shows");
  }
}

}  // namespace thaw::gui
