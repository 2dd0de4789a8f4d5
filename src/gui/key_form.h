#pragma once
// A form of fields each bound to one dotted key of the scenario document: numbers, integers,
// choices, flags and 3-vectors (points, colours with a colour picker). A field shows the parsed
// scenario's effective value (refresh), reports what the user typed as (key, value) through
// `edited`, and shows the parser's message for its key inline (show_problem). It checks nothing
// itself beyond "is this a number": every rule stays in the parsers.
#include <QFormLayout>
#include <QLabel>
#include <QWidget>
#include <functional>
#include <map>

#include "src/gui/scenario_document.h"

class QLineEdit;

namespace thaw::gui {

/// Reads a field's effective value from a parsed scenario.
using ValueGetter = std::function<TomlValue(const pipeline::RunScenario&)>;

class KeyForm : public QWidget {
  Q_OBJECT
 public:
  explicit KeyForm(QWidget* parent = nullptr);

  void add_section(const QString& title);
  void add_number(const QString& label, const std::string& key, ValueGetter get);
  void add_integer(const QString& label, const std::string& key, ValueGetter get);
  void add_choice(const QString& label, const std::string& key, const QStringList& choices,
                  ValueGetter get);
  void add_flag(const QString& label, const std::string& key, ValueGetter get);
  /// Three numbers "x, y, z"; with `colour` a button opens a colour picker (linear RGB 0..1).
  void add_vector(const QString& label, const std::string& key, ValueGetter get,
                  bool colour = false);

  /// Shows the scenario's values in every field (not emitting `edited`).
  void refresh(const pipeline::RunScenario& scenario);
  /// Shows `message` under the field of `key` and clears the others; returns whether a field of
  /// this form has that key.
  bool show_problem(const std::string& key, const QString& message);
  /// The field widget editing `key` (tests type into it), or nullptr.
  QWidget* field(const std::string& key) const;
  /// The message shown for `key` ("" when none).
  QString problem(const std::string& key) const;

 signals:
  void edited(const std::string& key, const thaw::gui::TomlValue& value);

 private:
  struct Field {
    QWidget* editor = nullptr;
    QLabel* message = nullptr;
    ValueGetter get;
    std::function<void(const TomlValue&)> show;
  };
  void add_row(const QString& label, const std::string& key, QWidget* editor, ValueGetter get,
               std::function<void(const TomlValue&)> show);
  void report_text_problem(const std::string& key, const QString& message);

  QFormLayout* m_layout;
  std::map<std::string, Field> m_fields;
  bool m_refreshing = false;
};

}  // namespace thaw::gui
Q_DECLARE_METATYPE(thaw::gui::TomlValue)
