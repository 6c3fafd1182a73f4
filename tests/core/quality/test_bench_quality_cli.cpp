// lucent-cli bench quality on a small volume: the CSV's columns and rows, a
// front that exists and is consistent, the plot, and bad options refused.
#include <QFile>
#include <QTemporaryDir>
#include <QTest>

#include "core/formats/MetaImage.h"
#include "core/image/PngIO.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/support/CliRunner.h"

using namespace lucent;

class TestBenchQualityCli : public QObject {
    Q_OBJECT
private slots:
    void sweepWritesCsvAndPlot() {
        QTemporaryDir dir;
        const Volume v = test::makeVolume(
            {24, 22, 20}, [](int i, int j, int k) { return 10.0 * test::blobs(i, j, k) - 300.0; },
            VoxelType::Int16);
        const QString vol = dir.filePath("blobs.mhd"), csv = dir.filePath("q.csv"),
                      plot = dir.filePath("q.png");
        writeMetaImage(v, vol.toStdString());
        const test::CliRun r = test::runCli({"bench", "quality", vol, "--size", "24x24", "--frames",
                                             "1", "--steps", "2,0.5", "--csv", csv, "--plot", plot},
                                            300000);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(r.out.contains("front ("), qPrintable(r.out));
        QFile f(csv);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QStringList lines = QString::fromUtf8(f.readAll()).trimmed().split('\n');
        QCOMPARE(
            lines.front(),
            QString("step,interp,classification,shading,brick,ms,samples,psnr_db,ssim,pareto"));
        QCOMPARE(lines.size(), 1 + 2 * 7 * 2); // 2 steps x 7 filter/classification x shading
        int front = 0;
        double bestStep2 = 0.0, bestStepHalf = 0.0;
        for (int n = 1; n < lines.size(); ++n) {
            const QStringList c = lines[n].split(',');
            QCOMPARE(c.size(), 10);
            front += c[9].toInt();
            QVERIFY(c[7] == "inf" || c[7].toDouble() > 5.0);
            if (c[1] == "cubic" && c[2] == "post" && c[3] == "1") {
                (c[0] == "2" ? bestStep2 : bestStepHalf) = c[7].toDouble();
            }
        }
        QVERIFY(front >= 2); // one front per shading state at least
        QVERIFY2(
            bestStepHalf > bestStep2,
            qPrintable(
                QString("cubic: %1 dB at step 2, %2 at 0.5").arg(bestStep2).arg(bestStepHalf)));
        const ImageRGBA8 img = readPng(plot.toStdString());
        QCOMPARE(img.width, 900);
    }

    void badOptionsAreRefused() {
        QCOMPARE(test::runCli({"bench", "speed", "x"}).exitCode, 2);
        QCOMPARE(test::runCli({"bench", "quality", "x", "--steps", "0"}).exitCode, 2);
        QCOMPARE(test::runCli({"bench", "quality", "/nonexistent/volume.mhd"}).exitCode, 3);
    }
};

QTEST_GUILESS_MAIN(TestBenchQualityCli)
#include "test_bench_quality_cli.moc"
