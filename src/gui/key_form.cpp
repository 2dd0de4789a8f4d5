#include "src/gui/key_form.h"

#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QStringList>

namespace thaw::gui {
namespace {

QString number_text(double v) {
  return QString::number(v, 'g', 10);
}

QString vector_text(const std::array<double, 3>& v) {
  return number_text(v[0]) + ", " + number_text(v[1]) + ", " + number_text(v[2]);
}

std::optional<std::array<double, 3>> parse_vector(const QString& text) {
  const QStringList parts = text.split(',', Qt::SkipEmptyParts);
  if (parts.size() != 3) return std::nullopt;
  std::array<double, 3> v{};
  for (int i = 0; i < 3; ++i) {
    bool ok = false;
    v[i] = parts[i].trimmed().toDouble(&ok);
    if (!ok) return std::nullopt;
  }
  return v;
}

}  // namespace

KeyForm::KeyForm(QWidget* parent) : QWidget(parent), m_layout(new QFormLayout(this)) {
  m_layout->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
}

void KeyForm::add_section(const QString& title) {
  auto* label = new QLabel("<b>" + title + "</b>", this);
  m_layout->addRow(label);
}

void KeyForm::add_row(const QString& label, const std::string& key, QWidget* editor,
                      ValueGetter get, std::function<void(const TomlValue&)> show) {
  auto* box = new QWidget(this);
  auto* v = new QVBoxLayout(box);
  v->setContentsMargins(0, 0, 0, 0);
  v->setSpacing(1);
  v->addWidget(editor);
  auto* message = new QLabel(box);
  message->setStyleSheet("color: #c0392b;");
  message->setWordWrap(true);
  message->hide();
  v->addWidget(message);
  editor->setObjectName(QString::fromStdString(key));
  editor->setToolTip(QString::fromStdString(key));
  m_layout->addRow(label, box);
  m_fields[key] = Field{editor, message, std::move(get), std::move(show)};
}

void KeyForm::report_text_problem(const std::string& key, const QString& message) {
  auto it = m_fields.find(key);
  if (it == m_fields.end()) return;
  it->second.message->setText(message);
  it->second.message->setVisible(!message.isEmpty());
}

void KeyForm::add_number(const QString& label, const std::string& key, ValueGetter get) {
  auto* edit = new QLineEdit(this);
  add_row(label, key, edit, std::move(get), [edit](const TomlValue& v) {
    if (const double* d = std::get_if<double>(&v)) edit->setText(number_text(*d));
    if (const long long* i = std::get_if<long long>(&v)) edit->setText(QString::number(*i));
  });
  connect(edit, &QLineEdit::editingFinished, this, [this, edit, key] {
    if (m_refreshing) return;
    bool ok = false;
    const double value = edit->text().trimmed().toDouble(&ok);
    if (!ok) return report_text_problem(key, "not a number: '" + edit->text() + "'");
    emit edited(key, TomlValue{value});
  });
}

void KeyForm::add_integer(const QString& label, const std::string& key, ValueGetter get) {
  auto* edit = new QLineEdit(this);
  add_row(label, key, edit, std::move(get), [edit](const TomlValue& v) {
    if (const long long* i = std::get_if<long long>(&v)) edit->setText(QString::number(*i));
  });
  connect(edit, &QLineEdit::editingFinished, this, [this, edit, key] {
    if (m_refreshing) return;
    bool ok = false;
    const long long value = edit->text().trimmed().toLongLong(&ok);
    if (!ok) return report_text_problem(key, "not an integer: '" + edit->text() + "'");
    emit edited(key, TomlValue{value});
  });
}

void KeyForm::add_choice(const QString& label, const std::string& key, const QStringList& choices,
                         ValueGetter get) {
  auto* combo = new QComboBox(this);
  combo->addItems(choices);
  add_row(label, key, combo, std::move(get), [combo](const TomlValue& v) {
    if (const std::string* s = std::get_if<std::string>(&v))
      combo->setCurrentText(QString::fromStdString(*s));
  });
  connect(combo, &QComboBox::currentTextChanged, this, [this, key](const QString& text) {
    if (!m_refreshing) emit edited(key, TomlValue{text.toStdString()});
  });
}

void KeyForm::add_flag(const QString& label, const std::string& key, ValueGetter get) {
  auto* check = new QCheckBox(this);
  add_row(label, key, check, std::move(get), [check](const TomlValue& v) {
    if (const bool* b = std::get_if<bool>(&v)) check->setChecked(*b);
  });
  connect(check, &QCheckBox::toggled, this, [this, key](bool on) {
    if (!m_refreshing) emit edited(key, TomlValue{on});
  });
}

void KeyForm::add_vector(const QString& label, const std::string& key, ValueGetter get,
                         bool colour) {
  auto* row = new QWidget(this);
  auto* h = new QHBoxLayout(row);
  h->setContentsMargins(0, 0, 0, 0);
  auto* edit = new QLineEdit(row);
  edit->setObjectName(QString::fromStdString(key) + ".text");
  h->addWidget(edit);
  if (colour) {
    auto* pick = new QPushButton("...", row);
    pick->setMaximumWidth(32);
    h->addWidget(pick);
    connect(pick, &QPushButton::clicked, this, [this, edit, key] {
      const auto v = parse_vector(edit->text()).value_or(std::array<double, 3>{1, 1, 1});
      const QColor start = QColor::fromRgbF(std::clamp(v[0], 0.0, 1.0), std::clamp(v[1], 0.0, 1.0),
                                            std::clamp(v[2], 0.0, 1.0));
      const QColor c = QColorDialog::getColor(start, this, "Colour (linear RGB)");
      if (!c.isValid()) return;
      const std::array<double, 3> picked{c.redF(), c.greenF(), c.blueF()};
      edit->setText(vector_text(picked));
      emit edited(key, TomlValue{picked});
    });
  }
  add_row(label, key, row, std::move(get), [edit](const TomlValue& v) {
    if (const auto* a = std::get_if<std::array<double, 3>>(&v)) edit->setText(vector_text(*a));
  });
  connect(edit, &QLineEdit::editingFinished, this, [this, edit, key] {
    if (m_refreshing) return;
    const auto v = parse_vector(edit->text());
    if (!v) return report_text_problem(key, "three numbers separated by commas, e.g. 0, 0.1, 0");
    emit edited(key, TomlValue{*v});
  });
}

void KeyForm::refresh(const pipeline::RunScenario& scenario) {
  m_refreshing = true;
  for (auto& [key, f] : m_fields)
    if (f.get) f.show(f.get(scenario));
  m_refreshing = false;
}

bool KeyForm::show_problem(const std::string& key, const QString& message) {
  bool mine = false;
  for (auto& [k, f] : m_fields) {
    const bool here = !key.empty() && k == key;
    f.message->setText(here ? message : QString());
    f.message->setVisible(here);
    mine |= here;
  }
  return mine;
}

QWidget* KeyForm::field(const std::string& key) const {
  auto it = m_fields.find(key);
  return it == m_fields.end() ? nullptr : it->second.editor;
}

QString KeyForm::problem(const std::string& key) const {
  auto it = m_fields.find(key);
  return it == m_fields.end() ? QString() : it->second.message->text();
}

}  // namespace thaw::gui
