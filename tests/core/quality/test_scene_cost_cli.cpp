// Only what the scene needs, on the real Philips CT through lucent-cli render
// --backend gl --stats: faint transfer functions that show everything, hide
// air, and hide air and soft tissue keep fewer bricks resident on the GPU and
// take fewer samples as they hide more, and never more samples than a
// brute-force march. Faint (opacity 0.002 a voxel), so that no ray stops early
// and only the hidden values decide.
#include <QDir>
#include <QFile>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTest>

#include "tests/support/CliRunner.h"

using namespace lucent;
using lucent::test::statOf;

namespace {

const QString kSeries = QStringLiteral(LUCENT_TEST_DATA_DIR "/dcm_qa_ct/Philips_S21570/S2020");

// Opacity 0.002 from `hiddenBelow` HU up, nothing below.
QString writeTf(const QTemporaryDir& dir, const QString& name, double hiddenBelow) {
    const QString path = dir.filePath(name + ".json");
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly)) {
        return {};
    }
    const QString below = QString::number(hiddenBelow - 1.0);
    const QString at = QString::number(hiddenBelow);
    f.write(QString("{\"name\": \"%1\", \"opacity\": [[-3024, 0], [%2, 0], [%3, 0.002], "
                    "[3071, 0.002]], \"colour\": [[-3024, 1, 1, 1], [3071, 1, 1, 1]], "
                    "\"shading\": {\"enabled\": false}}")
                .arg(name, below, at)
                .toUtf8());
    return path;
}

} // namespace

class TestSceneCostCli : public QObject {
    Q_OBJECT
private slots:
    void hidingMoreKeepsLessResidentAndSamplesLess() {
        if (!QDir(kSeries).exists()) {
            QSKIP("real CT data absent (../shared/data/dcm_qa_ct)");
        }
        QTemporaryDir dir;
        // Everything (from -2000 HU, below the data), no air, no air and no soft tissue.
        const std::vector<std::pair<QString, double>> tfs = {
            {"everything", -2000.0}, {"no-air", -500.0}, {"bone-and-contrast", 150.0}};
        double lastResident = 1e300, lastSamples = 1e300;
        for (const auto& [name, hiddenBelow] : tfs) {
            const QString tf = writeTf(dir, name, hiddenBelow);
            QVERIFY(!tf.isEmpty());
            const test::CliRun r =
                test::runCli({"render", kSeries, "-o", dir.filePath(name + ".png"), "--backend",
                              "gl", "--size", "128x128", "--brick", "32", "--tf", tf, "--stats"},
                             240000);
            QVERIFY2(r.exitCode == 0, qPrintable(r.err));
            if (r.err.contains("GL backend is not available")) {
                QSKIP(qPrintable("no GL here: " + r.err));
            }
            const double resident = statOf(r.out, "resident_mib");
            const double volume = statOf(r.out, "volume_mib");
            const double samples = statOf(r.out, "samples");
            const double brute = statOf(r.out, "brute_samples");
            qInfo("%s: resident %.1f MiB of a %.1f MiB volume, %.0f samples of %.0f brute force",
                  qPrintable(name), resident, volume, samples, brute);
            QVERIFY2(resident > 0.0 && volume > 0.0 && samples > 0.0 && brute > 0.0,
                     qPrintable(r.out));
            QVERIFY2(samples <= brute, qPrintable(r.out));
            QVERIFY2(resident < lastResident, qPrintable(name + ": " + r.out));
            QVERIFY2(samples < lastSamples, qPrintable(name + ": " + r.out));
            lastResident = resident;
            lastSamples = samples;
        }
    }
};

QTEST_GUILESS_MAIN(TestSceneCostCli)
#include "test_scene_cost_cli.moc"
