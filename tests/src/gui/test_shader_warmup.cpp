// The shader warm-up's child process (src/gui/shader_warmup.h), without a window: its outcome is
// reported once, whether it exits 0, fails, cannot start or outlives its time limit (then it is
// killed), and the real child, `thaw gui --warm-shaders`, fills an empty Mesa shader cache.
#include <QCoreApplication>
#include <QElapsedTimer>
#include <QSignalSpy>
#include <QtTest>
#include <filesystem>

#include "src/gui/shader_warmup.h"

namespace fs = std::filesystem;
using thaw::gui::ShaderWarmup;

class TestShaderWarmup : public QObject {
  Q_OBJECT
 private slots:
  void reportsTheChildsExitCode() {
    ShaderWarmup ok("/bin/sh", {"-c", "exit 0"}, 30000);
    ShaderWarmup failed("/bin/sh", {"-c", "exit 3"}, 30000);
    QSignalSpy ok_spy(&ok, &ShaderWarmup::finished), failed_spy(&failed, &ShaderWarmup::finished);
    QTRY_VERIFY_WITH_TIMEOUT(ok_spy.count() == 1 && failed_spy.count() == 1, 30000);
    QCOMPARE(ok_spy.front().front().toBool(), true);
    QCOMPARE(failed_spy.front().front().toBool(), false);
    QVERIFY(!ok.running() && !failed.running());
  }

  void aProgramThatCannotStartIsAFailure() {
    ShaderWarmup missing("/nonexistent/thaw", {}, 30000);
    QSignalSpy spy(&missing, &ShaderWarmup::finished);
    QTRY_VERIFY_WITH_TIMEOUT(spy.count() == 1, 30000);
    QCOMPARE(spy.front().front().toBool(), false);
  }

  // A child that hangs is killed at its time limit and counts as failed, once.
  void aChildPastItsTimeLimitIsKilled() {
    QElapsedTimer clock;
    clock.start();
    ShaderWarmup hung("/bin/sleep", {"60"}, 300);
    QSignalSpy spy(&hung, &ShaderWarmup::finished);
    QTRY_VERIFY_WITH_TIMEOUT(spy.count() == 1, 30000);
    QCOMPARE(spy.front().front().toBool(), false);
    QVERIFY(clock.elapsed() < 30000);  // not the child's 60 s
    QTest::qWait(200);
    QCOMPARE(spy.count(), 1);
  }

  // The real child on an empty cache folder: exits 0 and leaves Mesa's compiled shaders there.
  void theWarmShadersChildFillsAnEmptyCache() {
    const fs::path dir =
        fs::temp_directory_path() /
        ("thaw_gui_shader_cache_" + std::to_string(QCoreApplication::applicationPid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    qputenv("MESA_SHADER_CACHE_DIR", QByteArray::fromStdString(dir.string()));
    ShaderWarmup child(THAW_EXE, {"gui", "--warm-shaders"}, 300000);
    QSignalSpy spy(&child, &ShaderWarmup::finished);
    QTRY_VERIFY_WITH_TIMEOUT(spy.count() == 1, 300000);
    QCOMPARE(spy.front().front().toBool(), true);
    std::size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir)) files += e.is_regular_file();
    QVERIFY2(files >= 5, qPrintable(QString::number(files)));  // one per look at least
    fs::remove_all(dir);
  }
};

QTEST_GUILESS_MAIN(TestShaderWarmup)
#include "test_shader_warmup.moc"
