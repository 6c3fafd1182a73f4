// lucent-cli render --backend gl: the same image as the CPU backend, the
// statistics the contract names plus the GPU's, the budget option, and a
// clear refusal when the budget holds nothing.
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>

#include "core/formats/MetaImage.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/support/CliRunner.h"

using namespace lucent;

namespace {

// A CT-like ball with a bony shell, written as MetaImage.
QString writeVolume(const QTemporaryDir& dir) {
    const Volume v = test::makeVolume(
        {90, 80, 70},
        [](int i, int j, int k) {
            const double r = std::sqrt((i - 45.0) * (i - 45.0) + (j - 40.0) * (j - 40.0) +
                                       (k - 35.0) * (k - 35.0));
            return r < 25.0 ? 40.0 : r < 30.0 ? 900.0 : -1000.0;
        },
        VoxelType::Int16);
    const QString path = dir.filePath("ball.mhd");
    writeMetaImage(v, path.toStdString());
    return path;
}

} // namespace

class TestGlCli : public QObject {
    Q_OBJECT
private slots:
    void glMatchesCpu() {
        QTemporaryDir dir;
        const QString vol = writeVolume(dir);
        const QString gl = dir.filePath("gl.png"), cpu = dir.filePath("cpu.png");
        const test::CliRun g = test::runCli({"render", vol, "-o", gl, "--backend", "gl", "--size",
                                             "96x80", "--stats", "--repeat", "3"});
        QVERIFY2(g.exitCode == 0, qPrintable(g.err));
        for (const char* key :
             {"render_ms=", "first_ms=", "samples=", "bricks_total=", "bricks_used=", "lod=0",
              "backend=gl", "uploads=", "uploads_after_first=0",
              "budget_mib=", "resident_mib=", "volume_mib=", "brute_samples="}) {
            QVERIFY2(g.out.contains(key), qPrintable(g.out));
        }
        const test::CliRun c =
            test::runCli({"render", vol, "-o", cpu, "--size", "96x80", "--precision", "double"});
        QVERIFY2(c.exitCode == 0, qPrintable(c.err));
        const double p = psnr(readPng(gl.toStdString()), readPng(cpu.toStdString()));
        QVERIFY2(p >= 40.0, qPrintable(QString("gl vs cpu: %1 dB").arg(p)));
    }

    void smallBudgetSaysWhichLevel() {
        QTemporaryDir dir;
        const QString vol = writeVolume(dir);
        // Bricks of 16 take 22^3 int16 texels: half a MiB holds 24, the shell needs more.
        const test::CliRun r =
            test::runCli({"render", vol, "-o", dir.filePath("x.png"), "--backend", "gl", "--brick",
                          "16", "--gpu-budget", "0.5", "--stats"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(!r.out.contains("lod=0"), qPrintable(r.out));
        QVERIFY2(r.err.contains("rendered from level"), qPrintable(r.err));
    }

    // No GL at all (glvnd finds no EGL vendor): the CPU renders, and says so.
    void withoutGlTheCpuRendersAndSaysSo() {
        QTemporaryDir dir;
        const QString vol = writeVolume(dir), png = dir.filePath("x.png");
        QProcess p;
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.insert("__EGL_VENDOR_LIBRARY_FILENAMES", dir.filePath("no-vendor.json"));
        p.setProcessEnvironment(env);
        p.start(QString(LUCENT_BIN_DIR) + "/lucent-cli",
                {"render", vol, "-o", png, "--backend", "gl", "--size", "32x32", "--stats"});
        QVERIFY(p.waitForFinished(120000));
        const QString out = QString::fromUtf8(p.readAllStandardOutput());
        const QString err = QString::fromUtf8(p.readAllStandardError());
        QCOMPARE(p.exitCode(), 0);
        QVERIFY2(err.contains("GL backend is not available") && err.contains("CPU"),
                 qPrintable(err));
        QVERIFY2(out.contains("backend=cpu"), qPrintable(out));
        QVERIFY(QFile::exists(png));
    }

    void budgetThatHoldsNothingIsRefused() {
        QTemporaryDir dir;
        const QString vol = writeVolume(dir);
        const test::CliRun r = test::runCli({"render", vol, "-o", dir.filePath("x.png"),
                                             "--backend", "gl", "--gpu-budget", "0.0001"});
        QCOMPARE(r.exitCode, 3);
        QVERIFY2(r.err.contains("budget"), qPrintable(r.err));
        QVERIFY(!QFile::exists(dir.filePath("x.png")));
        const test::CliRun bad = test::runCli(
            {"render", vol, "-o", dir.filePath("x.png"), "--backend", "gl", "--gpu-budget", "-4"});
        QCOMPARE(bad.exitCode, 2);
        QVERIFY2(bad.err.contains("--gpu-budget"), qPrintable(bad.err));
    }
};

QTEST_GUILESS_MAIN(TestGlCli)
#include "test_gl_cli.moc"
