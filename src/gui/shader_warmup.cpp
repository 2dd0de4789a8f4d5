#include "src/gui/shader_warmup.h"

#include <QDateTime>
#include <QFile>
#include <QFileInfo>
#include <QProcess>
#include <QProcessEnvironment>
#include <QTimer>
#include <cstdlib>
#include <string>

#include "src/gui/shell_view.h"

namespace thaw::gui {
namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

/// Mesa's on-disk shader cache folder as Mesa 22 finds it (util/disk_cache_os.c): the
/// MESA_SHADER_CACHE_DIR (or older MESA_GLSL_CACHE_DIR), else XDG_CACHE_HOME, else ~/.cache, with
/// "mesa_shader_cache" appended; "" when the cache is disabled or no folder is known.
QString mesa_cache_dir() {
  for (const char* off : {"MESA_SHADER_CACHE_DISABLE", "MESA_GLSL_CACHE_DISABLE"}) {
    const std::string v = env(off);
    if (v == "1" || v == "true" || v == "TRUE" || v == "yes") return "";
  }
  std::string base = env("MESA_SHADER_CACHE_DIR");
  if (base.empty()) base = env("MESA_GLSL_CACHE_DIR");
  if (base.empty()) base = env("XDG_CACHE_HOME");
  if (base.empty() && !env("HOME").empty()) base = env("HOME") + "/.cache";
  if (base.empty()) return "";
  return QString::fromStdString(base) + "/mesa_shader_cache";
}

/// What the stamp records: this thaw build (another build may draw other looks).
QByteArray stamp_of(const QString& thaw_exe) {
  const QFileInfo exe(thaw_exe);
  return (exe.canonicalFilePath() + " " + QString::number(exe.size()) + " " +
          QString::number(exe.lastModified().toMSecsSinceEpoch()))
      .toUtf8();
}

QString stamp_path(const QString& cache_dir) {
  return cache_dir + "/thaw-gui-warm-shaders";
}

bool cache_warmed(const QString& cache_dir, const QString& thaw_exe) {
  QFile stamp(stamp_path(cache_dir));
  return stamp.open(QIODevice::ReadOnly) && stamp.readAll() == stamp_of(thaw_exe);
}

void mark_warmed(const QString& cache_dir, const QString& thaw_exe) {
  QFile stamp(stamp_path(cache_dir));
  if (stamp.open(QIODevice::WriteOnly | QIODevice::Truncate)) stamp.write(stamp_of(thaw_exe));
}

}  // namespace

ShaderWarmup::ShaderWarmup(const QString& program, const QStringList& arguments, int timeout_ms,
                           QObject* parent)
    : QObject(parent), m_process(new QProcess(this)), m_timeout(new QTimer(this)) {
  // The child draws on a private Xvfb (nothing shows on the user's screen) with the xcb platform
  // (Qt's offscreen platform composites without OpenGL: 15 of the parent's 40 shaders missed).
  QProcessEnvironment e = QProcessEnvironment::systemEnvironment();
  e.remove("DISPLAY");
  e.remove("QT_QPA_PLATFORM");
  m_process->setProcessEnvironment(e);
  m_process->setProcessChannelMode(QProcess::ForwardedErrorChannel);
  m_process->setStandardOutputFile(QProcess::nullDevice());
  connect(m_process, qOverload<int, QProcess::ExitStatus>(&QProcess::finished), this,
          [this](int code, QProcess::ExitStatus status) {
            finish(status == QProcess::NormalExit && code == 0);
          });
  connect(m_process, &QProcess::errorOccurred, this, [this](QProcess::ProcessError error) {
    if (error == QProcess::FailedToStart) finish(false);
  });
  m_timeout->setSingleShot(true);
  connect(m_timeout, &QTimer::timeout, this, [this] { finish(false); });
  m_timeout->start(timeout_ms);
  m_process->start(program, arguments);
}

ShaderWarmup::~ShaderWarmup() {
  m_done = true;
  m_process->disconnect(this);  // no slot of this half-destroyed object runs
  if (m_process->state() != QProcess::NotRunning) {
    m_process->kill();
    m_process->waitForFinished(1000);
  }
}

void ShaderWarmup::finish(bool ok) {
  if (m_done) return;
  m_done = true;
  m_timeout->stop();
  if (m_process->state() != QProcess::NotRunning) {
    m_process->kill();  // timed out: the view goes on without it
    m_process->waitForFinished(1000);
  }
  emit finished(ok);
}

ShaderWarmup* warm_shaders_first(ShellView& view, const QString& thaw_exe,
                                 const std::filesystem::path& scenario) {
  const QString cache = mesa_cache_dir();
  if (cache.isEmpty() || cache_warmed(cache, thaw_exe)) return nullptr;
  QStringList args{"gui", "--warm-shaders"};
  if (!scenario.empty()) args << QString::fromStdString(scenario.string());
  view.hold();
  auto* warmup = new ShaderWarmup(thaw_exe, args, kShaderWarmupTimeoutMs, &view);
  QObject::connect(warmup, &ShaderWarmup::finished, &view, [&view, cache, thaw_exe](bool ok) {
    if (ok) mark_warmed(cache, thaw_exe);
    view.release();
  });
  return warmup;
}

}  // namespace thaw::gui
