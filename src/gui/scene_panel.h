#pragma once
// The Scene tab (the second report's tabs): background, camera, lights, objects, materials and
// media of the scenario's [render] scene. Each list (lights, objects, materials, media) has Add
// and Remove and shows the selected entry's keys in a KeyForm; every edit is a key of the TOML
// document, checked by the scene parser like any other. Textures: a material is solid (`color`)
// or checker (`checker = { colors, size }`); dielectrics are media (a preset of the medium
// library, a constant index, or Sellmeier / Cauchy coefficients) named by an object's inside and
// outside.
#include <QWidget>
#include <functional>

#include "src/gui/key_form.h"

class QListWidget;
class QVBoxLayout;
class QComboBox;

namespace thaw::gui {

class MainWindow;

class ScenePanel : public QWidget {
  Q_OBJECT
 public:
  explicit ScenePanel(MainWindow& window, QWidget* parent = nullptr);
  /// Rebuilds the lists from the document (after any valid edit); the selected entries' forms
  /// are rebuilt only when the lists changed.
  void refresh();
  /// Selects entry `index` of the objects list (tests).
  void select_object(int index);

 private:
  struct List {
    QListWidget* list = nullptr;
    QVBoxLayout* detail = nullptr;
    KeyForm* form = nullptr;
    QString signature;
  };
  QWidget* make_list(const QString& title, List& list, QWidget* add_row,
                     const std::function<void()>& remove);
  void rebuild_detail(List& list, const std::function<KeyForm*(int)>& make_form);
  KeyForm* light_form(int k);
  KeyForm* object_form(int k);
  KeyForm* material_form(int k);
  KeyForm* medium_form(int k);
  ValueGetter doc(const std::string& key, TomlValue fallback) const;
  void camera_edit(const std::string& key, const TomlValue& value);
  /// Makes object `key` ("render.objects[k]") a dielectric (inside: the first medium, a glass
  /// added if there is none; outside: the shell's outside medium) or opaque (the first material).
  void set_object_surface(const std::string& key, bool dielectric);

  MainWindow& m_window;
  KeyForm* m_view_form = nullptr;
  List m_lights, m_objects, m_materials, m_media;
  QComboBox* m_new_shape = nullptr;
};

}  // namespace thaw::gui
