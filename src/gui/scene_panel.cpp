#include "src/gui/scene_panel.h"

#include <QComboBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QInputDialog>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>

#include "base/check.h"
#include "render/scene/camera_keys.h"
#include "render/scene/light_keys.h"
#include "src/gui/key_row_field.h"
#include "src/gui/main_window.h"
#include "src/gui/shell_step.h"
#include "src/pipeline/frame_camera.h"

namespace thaw::gui {
namespace {

using pipeline::RunScenario;
using V3 = std::array<double, 3>;

std::string indexed(const char* array, int k) {
  return std::string(array) + "[" + std::to_string(k) + "]";
}

/// The camera the frames use: the scenario's, or the built-in one framing the initial shell.
render::CameraDescription effective_camera(const RunScenario& sc) {
  if (sc.camera_set) return sc.scene.camera;
  const sim::InterfaceRecord row = initial_row(sc.simulation);
  return pipeline::framing_camera(
      pipeline::shell_extent({row}, shell_geometry(sc.simulation), sc.shell.center,
                             sc.shell.rest_on_floor, sc.shell.floor_y),
      static_cast<double>(sc.scene.image.width) / sc.scene.image.height);
}

/// A name not yet used among `taken`: base, base2, base3 ...
std::string fresh_name(const std::string& base, const std::vector<std::string>& taken) {
  for (int i = 1;; ++i) {
    const std::string name = i == 1 ? base : base + std::to_string(i);
    if (std::find(taken.begin(), taken.end(), name) == taken.end()) return name;
  }
}

}  // namespace

ValueGetter ScenePanel::doc(const std::string& key, TomlValue fallback) const {
  return [this, key, fallback](const RunScenario&) {
    return m_window.document().value(key).value_or(fallback);
  };
}

ScenePanel::ScenePanel(MainWindow& window, QWidget* parent) : QWidget(parent), m_window(window) {
  auto* v = new QVBoxLayout(this);
  m_view_form = new KeyForm;
  m_view_form->add_section("Background and camera");
  m_view_form->add_vector(
      "Background (linear RGB)", "render.image.background",
      [](const RunScenario& s) { return TomlValue{s.scene.image.background}; }, true);
  // The camera's rows (render/scene/camera_keys.h) name and label the fields; the values are the
  // frame's effective camera (the film's, when the file gives none).
  const auto camera_label = [](std::string_view name) {
    const render::CameraKey* row = find_key(render::camera_keys(), name);
    THAW_CHECK(row != nullptr, "the camera form names a [camera] key of the table");
    return key_row_label(*row);
  };
  m_view_form->add_vector(
      camera_label("position"), "render.camera.position",
      [](const RunScenario& s) { return TomlValue{effective_camera(s).position}; });
  m_view_form->add_vector(
      camera_label("look_at"), "render.camera.look_at",
      [](const RunScenario& s) { return TomlValue{effective_camera(s).look_at}; });
  m_view_form->add_number(
      camera_label("vertical_fov_deg"), "render.camera.vertical_fov_deg",
      [](const RunScenario& s) { return TomlValue{effective_camera(s).vertical_fov_deg}; });
  m_window.register_form(m_view_form, false);
  connect(m_view_form, &KeyForm::edited, this,
          [this](const std::string& key, const TomlValue& value) {
            if (key.rfind("render.camera.", 0) == 0) return camera_edit(key, value);
            m_window.apply_edit(key, value);
          });
  v->addWidget(m_view_form);

  auto* add_light = new QPushButton("Add light");
  connect(add_light, &QPushButton::clicked, this, [this] {
    m_window.modify([](ScenarioDocument& d) {
      const std::string key =
          indexed("render.lights", static_cast<int>(d.append_table("render.lights")));
      d.set(key + ".kind", std::string("point"));
      d.set(key + ".position", V3{0.3, 0.5, 0.3});
      d.set(key + ".intensity", 0.3);
      d.set(key + ".falloff", std::string("inverse_square"));
    });
  });
  v->addWidget(make_list("Lights", m_lights, add_light, [this] {
    const int k = m_lights.list->currentRow();
    if (k >= 0)
      m_window.modify([k](ScenarioDocument& d) {
        d.erase_table("render.lights", static_cast<std::size_t>(k));
      });
  }));

  auto* add_object = new QWidget;
  auto* h = new QHBoxLayout(add_object);
  h->setContentsMargins(0, 0, 0, 0);
  m_new_shape = new QComboBox;
  m_new_shape->addItems({"sphere", "box", "plane", "mesh"});
  auto* add = new QPushButton("Add object");
  add->setObjectName("add_object");
  h->addWidget(m_new_shape);
  h->addWidget(add);
  connect(add, &QPushButton::clicked, this, [this] {
    const std::string shape = m_new_shape->currentText().toStdString();
    std::string file;
    if (shape == "mesh") {
      file = QFileDialog::getOpenFileName(this, "Mesh (OBJ)", {}, "OBJ (*.obj)").toStdString();
      if (file.empty()) return;
    }
    m_window.add_object(shape, file);
    m_objects.list->setCurrentRow(m_objects.list->count() - 1);
  });
  v->addWidget(make_list("Objects", m_objects, add_object, [this] {
    const int k = m_objects.list->currentRow();
    if (k >= 0) m_window.remove_object(static_cast<std::size_t>(k));
  }));

  auto* add_material = new QPushButton("Add material");
  connect(add_material, &QPushButton::clicked, this, [this] {
    const std::string name =
        fresh_name("material", m_window.document().table_keys("render.materials"));
    m_window.modify([name](ScenarioDocument& d) {
      d.set("render.materials." + name + ".kind", std::string("matte"));
      d.set("render.materials." + name + ".color", V3{0.7, 0.7, 0.7});
    });
  });
  v->addWidget(make_list("Materials", m_materials, add_material, [this] {
    if (auto* item = m_materials.list->currentItem())
      m_window.modify([name = item->text().toStdString()](ScenarioDocument& d) {
        d.remove("render.materials." + name);
      });
  }));

  auto* add_medium = new QPushButton("Add medium");
  connect(add_medium, &QPushButton::clicked, this, [this] {
    const std::string name = fresh_name("glass", m_window.document().table_keys("render.media"));
    m_window.modify([name](ScenarioDocument& d) {
      d.set("render.media." + name + ".preset", std::string("n-bk7"));
    });
  });
  v->addWidget(
      make_list("Media (dielectrics: an object's inside and outside)", m_media, add_medium, [this] {
        if (auto* item = m_media.list->currentItem())
          m_window.modify([name = item->text().toStdString()](ScenarioDocument& d) {
            d.remove("render.media." + name);
          });
      }));
  v->addStretch(1);
}

QWidget* ScenePanel::make_list(const QString& title, List& list, QWidget* add_row,
                               const std::function<void()>& remove) {
  auto* box = new QWidget;
  auto* v = new QVBoxLayout(box);
  v->setContentsMargins(0, 6, 0, 0);
  v->addWidget(new QLabel("<b>" + title + "</b>"));
  list.list = new QListWidget;
  list.list->setObjectName(title.section(' ', 0, 0).toLower() + "_list");
  list.list->setMaximumHeight(90);
  v->addWidget(list.list);
  auto* row = new QHBoxLayout;
  row->addWidget(add_row);
  auto* rm = new QPushButton("Remove");
  connect(rm, &QPushButton::clicked, this, remove);
  row->addWidget(rm);
  v->addLayout(row);
  list.detail = new QVBoxLayout;
  v->addLayout(list.detail);
  connect(list.list, &QListWidget::currentRowChanged, this, [this, &list] {
    list.signature.clear();  // forces the form of the new selection
    refresh();
  });
  return box;
}

void ScenePanel::select_object(int index) {
  m_objects.list->setCurrentRow(index);
}

void ScenePanel::rebuild_detail(List& list, const std::function<KeyForm*(int)>& make_form) {
  const int k = list.list->currentRow();
  if (list.form) {
    m_window.unregister_form(list.form);
    list.form->hide();
    list.form->deleteLater();  // it may be the sender of the edit being handled
    list.form = nullptr;
  }
  if (k < 0) return;
  list.form = make_form(k);
  m_window.register_form(list.form, true);
  list.detail->addWidget(list.form);
  if (m_window.check().ok()) list.form->refresh(*m_window.check().scenario);
}

void ScenePanel::refresh() {
  const ScenarioDocument& d = m_window.document();
  auto fill = [this](List& list, const QStringList& items,
                     const std::function<KeyForm*(int)>& make_form) {
    const int row = list.list->currentRow();
    const QString signature = items.join('\n') + "#" + QString::number(row);
    if (signature == list.signature) return;
    {
      const QSignalBlocker block(list.list);
      list.list->clear();
      list.list->addItems(items);
      if (!items.isEmpty())
        list.list->setCurrentRow(std::clamp(row, 0, static_cast<int>(items.size()) - 1));
    }
    list.signature = items.join('\n') + "#" + QString::number(list.list->currentRow());
    rebuild_detail(list, make_form);
  };
  QStringList lights, objects, materials, media;
  for (std::size_t k = 0; k < d.array_size("render.lights"); ++k)
    lights << QString("%1: %2").arg(k).arg(QString::fromStdString(
        d.string_or(indexed("render.lights", static_cast<int>(k)) + ".kind", "point")));
  for (std::size_t k = 0; k < d.array_size("render.objects"); ++k) {
    const std::string key = indexed("render.objects", static_cast<int>(k));
    objects << QString("%1: %2 (%3)")
                   .arg(k)
                   .arg(QString::fromStdString(d.string_or(key + ".shape", "?")))
                   .arg(QString::fromStdString(
                       d.string_or(key + ".material", d.string_or(key + ".inside", ""))));
  }
  for (const std::string& name : d.table_keys("render.materials"))
    materials << QString::fromStdString(name);
  for (const std::string& name : d.table_keys("render.media"))
    media << QString::fromStdString(name);
  fill(m_lights, lights, [this](int k) { return light_form(k); });
  fill(m_objects, objects, [this](int k) { return object_form(k); });
  fill(m_materials, materials, [this](int k) { return material_form(k); });
  fill(m_media, media, [this](int k) { return medium_form(k); });
}

KeyForm* ScenePanel::light_form(int k) {
  auto* f = new KeyForm;
  const std::string key = indexed("render.lights", k);
  // Labels and choices from the light's rows (render/scene/light_keys.h); the values as the
  // document has them, with a new light's seed values.
  const auto row = [](std::string_view name) {
    const render::LightKey* r = find_key(render::light_keys(), name);
    THAW_CHECK(r != nullptr, "the light form names a [[lights]] key of the table");
    return r;
  };
  const auto names = [&](std::string_view name) {
    QStringList out;
    for (std::string_view n : std::get<ChoiceKey<render::LightDescription>>(row(name)->value).names)
      out << QString::fromUtf8(n.data(), static_cast<int>(n.size()));
    return out;
  };
  f->add_choice(key_row_label(*row("kind")), key + ".kind", names("kind"),
                doc(key + ".kind", std::string("point")));
  f->add_vector(key_row_label(*row("position")), key + ".position",
                doc(key + ".position", V3{0, 1, 0}));
  f->add_vector(key_row_label(*row("color")), key + ".color", doc(key + ".color", V3{1, 1, 1}),
                true);
  f->add_number(key_row_label(*row("intensity")), key + ".intensity", doc(key + ".intensity", 1.0));
  f->add_choice(key_row_label(*row("falloff")), key + ".falloff", names("falloff"),
                doc(key + ".falloff", std::string("none")));
  f->add_number(key_row_label(*row("radius")), key + ".radius", doc(key + ".radius", 0.0));
  return f;
}

KeyForm* ScenePanel::object_form(int k) {
  auto* f = new KeyForm;
  const std::string key = indexed("render.objects", k);
  const std::string shape = m_window.document().string_or(key + ".shape", "sphere");
  f->add_section(QString::fromStdString(shape));
  if (shape == "sphere") {
    f->add_vector("Centre [m]", key + ".center", doc(key + ".center", V3{0, 0, 0}));
    f->add_number("Radius [m]", key + ".radius", doc(key + ".radius", 0.01));
  } else if (shape == "box") {
    f->add_vector("Near corner (min) [m]", key + ".min", doc(key + ".min", V3{0, 0, 0}));
    f->add_vector("Far corner (max) [m]", key + ".max", doc(key + ".max", V3{0.01, 0.01, 0.01}));
  } else if (shape == "plane") {
    f->add_vector("Point [m]", key + ".point", doc(key + ".point", V3{0, 0, 0}));
    f->add_vector("Normal", key + ".normal", doc(key + ".normal", V3{0, 1, 0}));
  } else if (shape == "mesh") {
    f->add_number("Scale", key + ".scale", doc(key + ".scale", 1.0));
    f->add_vector("Translate [m]", key + ".translate", doc(key + ".translate", V3{0, 0, 0}));
  }
  const ScenarioDocument& d = m_window.document();
  // Opaque (a material) or a dielectric (transparent: the media inside and outside, e.g. a
  // Sellmeier glass of the Media list; spheres, boxes and closed meshes only, as the parser says).
  auto* surface = new QComboBox;
  surface->setObjectName(QString::fromStdString(key + ".surface"));
  surface->addItems({"opaque (material)", "dielectric (media)"});
  surface->setCurrentIndex(d.has(key + ".material") ? 0 : 1);
  connect(surface, QOverload<int>::of(&QComboBox::currentIndexChanged), this,
          [this, key](int index) { set_object_surface(key, index == 1); });
  f->layout()->addWidget(surface);
  if (d.has(key + ".material")) {
    QStringList names;
    for (const std::string& n : d.table_keys("render.materials"))
      names << QString::fromStdString(n);
    f->add_choice("Material", key + ".material", names, doc(key + ".material", std::string()));
  } else {
    QStringList names{"vacuum"};
    for (const std::string& n : d.table_keys("render.media")) names << QString::fromStdString(n);
    f->add_choice("Inside medium", key + ".inside", names,
                  doc(key + ".inside", std::string("vacuum")));
    f->add_choice("Outside medium", key + ".outside", names,
                  doc(key + ".outside", std::string("vacuum")));
  }
  return f;
}

KeyForm* ScenePanel::material_form(int k) {
  auto* f = new KeyForm;
  const std::vector<std::string> names = m_window.document().table_keys("render.materials");
  const std::string key = "render.materials." + names.at(static_cast<std::size_t>(k));
  const ScenarioDocument& d = m_window.document();
  f->add_choice("Kind", key + ".kind", {"matte", "metal", "phong", "emissive"},
                doc(key + ".kind", std::string("matte")));
  if (d.string_or(key + ".kind", "matte") == "emissive") {
    f->add_vector("Emitted colour", key + ".color", doc(key + ".color", V3{1, 1, 1}), true);
    f->add_number("Intensity", key + ".intensity", doc(key + ".intensity", 1.0));
  } else if (d.has(key + ".checker")) {
    f->add_vector("Checker colour 1", key + ".checker.colors[0]",
                  doc(key + ".checker.colors[0]", V3{0.9, 0.9, 0.9}), true);
    f->add_vector("Checker colour 2", key + ".checker.colors[1]",
                  doc(key + ".checker.colors[1]", V3{0.1, 0.1, 0.1}), true);
    f->add_number("Checker size [m]", key + ".checker.size", doc(key + ".checker.size", 0.02));
  } else {
    f->add_vector("Colour", key + ".color", doc(key + ".color", V3{0.8, 0.8, 0.8}), true);
  }
  if (d.string_or(key + ".kind", "matte") == "phong") {  // docs/render.md's defaults
    f->add_number("ka", key + ".ka", doc(key + ".ka", 0.1));
    f->add_number("kd", key + ".kd", doc(key + ".kd", 0.9));
    f->add_number("ks", key + ".ks", doc(key + ".ks", 0.0));
    f->add_number("Shininess", key + ".shininess", doc(key + ".shininess", 32.0));
    f->add_number("Reflectance", key + ".reflectance", doc(key + ".reflectance", 0.0));
  }
  auto* texture = new QPushButton(d.has(key + ".checker") ? "Make solid" : "Make checker");
  connect(texture, &QPushButton::clicked, this, [this, key] {
    m_window.modify([key](ScenarioDocument& doc) {
      if (doc.has(key + ".checker")) {
        doc.remove(key + ".checker");
        doc.set(key + ".color", V3{0.8, 0.8, 0.8});
      } else {
        doc.remove(key + ".color");
        doc.set(key + ".checker.size", 0.02);
        doc.set(key + ".checker.colors[0]", V3{0.9, 0.9, 0.9});
        doc.set(key + ".checker.colors[1]", V3{0.1, 0.1, 0.1});
      }
    });
    m_materials.signature.clear();
    refresh();
  });
  f->layout()->addWidget(texture);
  connect(f, &KeyForm::edited, this, [this](const std::string& key, const TomlValue&) {
    if (key.size() > 5 && key.compare(key.size() - 5, 5, ".kind") == 0)
      QTimer::singleShot(0, this, [this] {  // after the edit applies: the fields depend on the kind
        m_materials.signature.clear();
        refresh();
      });
  });
  return f;
}

KeyForm* ScenePanel::medium_form(int k) {
  auto* f = new KeyForm;
  const std::vector<std::string> names = m_window.document().table_keys("render.media");
  const std::string key = "render.media." + names.at(static_cast<std::size_t>(k));
  const ScenarioDocument& d = m_window.document();
  const std::string model = d.has(key + ".preset")      ? "preset"
                            : d.has(key + ".sellmeier") ? "sellmeier"
                            : d.has(key + ".cauchy")    ? "cauchy"
                                                        : "ior";
  auto* choose = new QComboBox;
  choose->addItems({"ior", "preset", "sellmeier", "cauchy"});
  choose->setCurrentText(QString::fromStdString(model));
  connect(choose, &QComboBox::currentTextChanged, this, [this, key](const QString& m) {
    m_window.modify([key, m](ScenarioDocument& doc) {
      for (const char* k : {".ior", ".preset", ".sellmeier", ".cauchy", ".table", ".iapws97"})
        doc.remove(key + k);
      if (m == "ior") doc.set(key + ".ior", 1.5);
      if (m == "preset") doc.set(key + ".preset", std::string("n-bk7"));
      if (m == "sellmeier") {  // N-BK7's coefficients (Schott) as a starting point
        doc.set(key + ".sellmeier.B", V3{1.03961212, 0.231792344, 1.01046945});
        doc.set(key + ".sellmeier.C", V3{0.00600069867, 0.0200179144, 103.560653});
      }
      if (m == "cauchy") {
        doc.set(key + ".cauchy.A", 1.5046);
        doc.set(key + ".cauchy.B", 0.0042);
        doc.set(key + ".cauchy.C", 0.0);
      }
    });
    m_media.signature.clear();
    refresh();
  });
  f->layout()->addWidget(choose);
  if (model == "ior") f->add_number("Index of refraction", key + ".ior", doc(key + ".ior", 1.5));
  if (model == "preset")
    f->add_choice(
        "Preset", key + ".preset",
        {"air", "diamond", "fused-silica", "ice-ih", "n-bk7", "n-sf10", "water-0c", "water-20c"},
        doc(key + ".preset", std::string("n-bk7")));
  if (model == "sellmeier") {
    f->add_vector("Sellmeier B1, B2, B3", key + ".sellmeier.B",
                  doc(key + ".sellmeier.B", V3{0, 0, 0}));
    f->add_vector("Sellmeier C1, C2, C3 [um^2]", key + ".sellmeier.C",
                  doc(key + ".sellmeier.C", V3{0, 0, 0}));
  }
  if (model == "cauchy") {
    f->add_number("Cauchy A", key + ".cauchy.A", doc(key + ".cauchy.A", 1.5));
    f->add_number("Cauchy B [um^2]", key + ".cauchy.B", doc(key + ".cauchy.B", 0.0));
    f->add_number("Cauchy C [um^4]", key + ".cauchy.C", doc(key + ".cauchy.C", 0.0));
  }
  f->add_number("Absorption [1/m]", key + ".absorption_per_m", doc(key + ".absorption_per_m", 0.0));
  return f;
}

void ScenePanel::set_object_surface(const std::string& key, bool dielectric) {
  const ScenarioCheck& c = m_window.check();
  const std::string outside = c.ok() ? c.scenario->shell.outside_medium : std::string("vacuum");
  m_window.modify([key, dielectric, outside](ScenarioDocument& d) {
    if (dielectric) {
      std::vector<std::string> media = d.table_keys("render.media");
      if (media.empty()) {  // a glass to start from (Schott N-BK7, the library's preset)
        d.set("render.media.glass.preset", std::string("n-bk7"));
        media.push_back("glass");
      }
      d.remove(key + ".material");
      d.set(key + ".inside", media.front());
      d.set(key + ".outside", outside);
    } else {
      std::vector<std::string> materials = d.table_keys("render.materials");
      if (materials.empty()) {
        d.set("render.materials.grey.kind", std::string("matte"));
        d.set("render.materials.grey.color", V3{0.7, 0.7, 0.7});
        materials.push_back("grey");
      }
      d.remove(key + ".inside");
      d.remove(key + ".outside");
      d.set(key + ".material", materials.front());
    }
  });
  m_objects.signature.clear();  // the form's fields depend on the surface
  QTimer::singleShot(0, this, [this] { refresh(); });
}

void ScenePanel::camera_edit(const std::string& key, const TomlValue& value) {
  const ScenarioCheck& c = m_window.check();
  if (c.ok() && !c.scenario->camera_set) {
    // The built-in camera becomes the scenario's own, then the edit applies to it.
    const render::CameraDescription cam = effective_camera(*c.scenario);
    m_window.modify([cam](ScenarioDocument& d) {
      d.set("render.camera.position", cam.position);
      d.set("render.camera.look_at", cam.look_at);
      d.set("render.camera.up", cam.up);
      d.set("render.camera.vertical_fov_deg", cam.vertical_fov_deg);
    });
  }
  m_window.apply_edit(key, value);
}

}  // namespace thaw::gui
