// Benchmark (label perf): lucent-cli render --distributed on 1, 2 and 4 ranks,
// CPU backend, the Philips 140-slice CT, ct-bone, 1024x1024, 6 frames turning
// 5 degrees each (median): time per frame, compositing time and its share of
// the frame, IceT's bytes sent per rank, the ranks' render times (imbalance).
// Asserts that every rank count gives the single-process image (>= 50 dB);
// prints the figures, asserts nothing about time (docs/distributed.md).
#include <QFileInfo>
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTest>

#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "tests/support/CliRunner.h"

using namespace lucent;
using lucent::test::statOf;

namespace {

QString runMpi(int ranks, const QStringList& args) {
    QProcess p;
    p.start(LUCENT_MPIEXEC,
            QStringList{"-n", QString::number(ranks), "--oversubscribe", "--allow-run-as-root",
                        QString(LUCENT_BIN_DIR) + "/lucent-cli"} +
                args);
    if (!p.waitForFinished(600000) || p.exitCode() != 0) {
        return {};
    }
    return QString::fromUtf8(p.readAllStandardOutput());
}

} // namespace

class BenchDistributedRender : public QObject {
    Q_OBJECT
private slots:
    void philipsCt1024() {
        if (QString(LUCENT_MPIEXEC).isEmpty()) {
            QFAIL("mpiexec was not found when this benchmark was configured (openmpi-bin)");
        }
        const QString ct = LUCENT_TEST_DATA_DIR "/dcm_qa_ct/Philips_S21570/S2020";
        if (!QFileInfo::exists(ct)) {
            QSKIP("real test data not found: ../shared/data/dcm_qa_ct/Philips_S21570/S2020");
        }
        QTemporaryDir tmp;
        QString table = "ranks frame_ms render_ms_max render_ms_min composite_ms share_% "
                        "icet_bytes_sent_max rank_voxels_max rank_resident_mib_max\n";
        ImageRGBA8 single;
        for (int ranks : {1, 2, 4}) {
            const QString png = tmp.filePath(QString("r%1.png").arg(ranks));
            const QString out =
                runMpi(ranks, {"render", ct, "-o", png, "--size", "1024x1024", "--distributed",
                               "--stats", "--repeat", "7", "--brick", "32"});
            QVERIFY2(!out.isEmpty(), qPrintable(QString("%1 ranks failed").arg(ranks)));
            const double frame = statOf(out, "render_ms"), composite = statOf(out, "composite_ms");
            table += QString("%1 %2 %3 %4 %5 %6 %7 %8 %9\n")
                         .arg(ranks)
                         .arg(frame, 0, 'f', 1)
                         .arg(statOf(out, "render_ms_max"), 0, 'f', 1)
                         .arg(statOf(out, "render_ms_min"), 0, 'f', 1)
                         .arg(composite, 0, 'f', 1)
                         .arg(100.0 * composite / frame, 0, 'f', 1)
                         .arg(statOf(out, "icet_bytes_sent_max"), 0, 'f', 0)
                         .arg(statOf(out, "rank_voxels_max"), 0, 'f', 0)
                         .arg(statOf(out, "rank_resident_mib_max"), 0, 'f', 1);
            const ImageRGBA8 image = readPng(png.toStdString());
            if (ranks == 1) {
                single = image;
            } else {
                const double db = psnr(single, image);
                QVERIFY2(db >= 50.0, qPrintable(QString("%1 ranks: %2 dB").arg(ranks).arg(db)));
            }
        }
        qInfo().noquote() << "\n" << table;
    }
};

QTEST_GUILESS_MAIN(BenchDistributedRender)
#include "bench_distributed_render.moc"
