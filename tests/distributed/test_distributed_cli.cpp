// lucent-cli render --distributed under mpirun on the real CT (Philips, 28 and
// 140 slices): the composited image equals the single-process render, a rank
// reads only its slab, and failures end the job with a message naming the rank.
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTest>

#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "tests/support/CliRunner.h"

using namespace lucent;
using namespace lucent::test;

namespace {

const QString kSmallCt = LUCENT_TEST_DATA_DIR "/dcm_qa_ct/Philips_S21570/S2010";
const QString kLargerCt = LUCENT_TEST_DATA_DIR "/dcm_qa_ct/Philips_S21570/S2020";

// mpirun -n N lucent-cli ARGS, oversubscribed (more ranks than cores), as root too.
CliRun runMpi(int ranks, const QStringList& args, int timeoutMs = 120000) {
    const QStringList all =
        QStringList{"-n", QString::number(ranks), "--oversubscribe", "--allow-run-as-root",
                    QString(LUCENT_BIN_DIR) + "/lucent-cli"} +
        args;
    return runProgram(LUCENT_MPIEXEC, all, timeoutMs);
}

} // namespace

class TestDistributedCli : public QObject {
    Q_OBJECT

    QTemporaryDir tmp_;

    QString path(const QString& name) const { return tmp_.filePath(name); }

    // The single-process image and the one of N ranks for the same flags, compared.
    // The distributed run's --stats line.
    QString compare(int ranks, const QStringList& flags, double minDb) {
        const QString tag = QString::number(qHash(flags.join(' '))) + "_" + QString::number(ranks);
        const CliRun local = runCli(
            QStringList{"render", kSmallCt, "-o", path("l" + tag + ".png"), "--size", "96x96"} +
            flags);
        if (local.exitCode != 0) {
            QTest::qFail(qPrintable(local.err), __FILE__, __LINE__);
            return {};
        }
        const CliRun dist =
            runMpi(ranks, QStringList{"render", kSmallCt, "-o", path("d" + tag + ".png"), "--size",
                                      "96x96", "--distributed", "--stats"} +
                              flags);
        if (dist.exitCode != 0 || statOf(dist.out, "ranks") != double(ranks)) {
            QTest::qFail(qPrintable(dist.err + dist.out), __FILE__, __LINE__);
            return {};
        }
        const double db = psnr(readPng(path("l" + tag + ".png").toStdString()),
                               readPng(path("d" + tag + ".png").toStdString()));
        if (!(db >= minDb)) {
            QTest::qFail(
                qPrintable(QString("%1 ranks, %2: %3 dB").arg(ranks).arg(flags.join(' ')).arg(db)),
                __FILE__, __LINE__);
        }
        return dist.out;
    }

private slots:
    void initTestCase() {
        if (QString(LUCENT_MPIEXEC).isEmpty()) {
            QFAIL("mpiexec was not found when this test was configured: install openmpi-bin "
                  "(packaging/install-deps.sh)");
        }
        if (!QFileInfo::exists(kSmallCt)) {
            QSKIP("the Philips CT is not in ../shared/data");
        }
        QVERIFY(tmp_.isValid());
    }

    void equalsTheSingleProcessRender_data() {
        QTest::addColumn<int>("ranks");
        QTest::addColumn<QStringList>("flags");
        for (int n : {2, 3, 4}) {
            QTest::newRow(qPrintable(QString("%1 front").arg(n))) << n << QStringList{};
            QTest::newRow(qPrintable(QString("%1 oblique").arg(n)))
                << n << QStringList{"--azimuth", "35", "--elevation", "25"};
        }
        QTest::newRow("3 top, small bricks")
            << 3 << QStringList{"--elevation", "90", "--brick", "16"};
        QTest::newRow("3 back, small bricks")
            << 3 << QStringList{"--azimuth", "180", "--brick", "16"};
        QTest::newRow("2 left cubic") << 2 << QStringList{"--azimuth", "90", "--interp", "cubic"};
        QTest::newRow("3 bottom preintegrated")
            << 3 << QStringList{"--elevation", "-90", "--preintegrate", "--brick", "32"};
        QTest::newRow("4 right unshaded")
            << 4 << QStringList{"--azimuth", "270", "--no-shading", "--brick", "32"};
        QTest::newRow("2 mip oblique")
            << 2 << QStringList{"--mode", "mip", "--azimuth", "30", "--brick", "32"};
        QTest::newRow("3 mip top")
            << 3 << QStringList{"--mode", "mip", "--elevation", "90", "--brick", "16"};
        QTest::newRow("4 minip left")
            << 4 << QStringList{"--mode", "minip", "--azimuth", "90", "--brick", "32"};
        QTest::newRow("3 average oblique")
            << 3 << QStringList{"--mode",      "avg", "--azimuth", "215",
                                "--elevation", "-40", "--brick",   "16"};
        // GL ranks (llvmpipe here), against the single-process GL image.
        QTest::newRow("2 gl oblique")
            << 2 << QStringList{"--backend", "gl", "--azimuth", "40", "--elevation", "20"};
        QTest::newRow("3 gl iso top") << 3 << QStringList{"--backend",   "gl", "--mode",  "iso",
                                                          "--elevation", "90", "--brick", "16"};
        QTest::newRow("2 gl cubic bottom")
            << 2 << QStringList{"--backend", "gl", "--interp", "cubic", "--elevation", "-90"};
        QTest::newRow("4 gl preintegrated left")
            << 4
            << QStringList{"--backend", "gl", "--preintegrate", "--azimuth", "90", "--brick", "32"};
        QTest::newRow("2 gl mip oblique")
            << 2 << QStringList{"--backend", "gl", "--mode", "mip", "--azimuth", "30"};
        QTest::newRow("3 gl minip left") << 3 << QStringList{"--backend", "gl", "--mode",  "minip",
                                                             "--azimuth", "90", "--brick", "32"};
        QTest::newRow("4 gl average back") << 4 << QStringList{"--backend", "gl",  "--mode",  "avg",
                                                               "--azimuth", "180", "--brick", "32"};
        QTest::newRow("3 iso oblique")
            << 3 << QStringList{"--mode", "iso",         "--iso", "300",     "--azimuth",
                                "215",    "--elevation", "-40",   "--brick", "16"};
    }
    void equalsTheSingleProcessRender() {
        QFETCH(int, ranks);
        QFETCH(QStringList, flags);
        (void)compare(ranks, flags, 50.0);
    }

    // A clip box that keeps the right two fifths of the head leaves a rank
    // nothing to draw (the split cuts across x): it still takes part in
    // compositing, and the image equals the whole's.
    void aClipBoxEmptiesRanks_data() {
        QTest::addColumn<QString>("backend");
        QTest::newRow("cpu") << "cpu";
        QTest::newRow("gl") << "gl";
    }
    void aClipBoxEmptiesRanks() {
        QFETCH(QString, backend);
        const QString stats = compare(3,
                                      {"--backend", backend, "--clip", "300,0,0,511,511,27",
                                       "--brick", "16", "--azimuth", "30", "--elevation", "20"},
                                      50.0);
        QVERIFY2(statOf(stats, "ranks_empty") >= 1.0, qPrintable(stats));
        QVERIFY2(statOf(stats, "samples") > 0.0, qPrintable(stats)); // not a blank image
    }

    // Each rank reads only the slices of its box plus halo: with 4 ranks over
    // the 140-slice CT and bricks of 16, no rank opens every file.
    // Each rank hands its composited part back to its caster: from the second
    // frame of a size on, every CPU rank draws into the buffers of its last frame.
    void partFramesAreHandedBack() {
        const CliRun once = runMpi(3, {"render", kSmallCt, "-o", path("once.png"), "--size",
                                       "96x96", "--distributed", "--stats"});
        QVERIFY2(once.exitCode == 0, qPrintable(once.err));
        QCOMPARE(statOf(once.out, "ranks_frame_buffers_recycled"), 0.0);
        const CliRun turned = runMpi(3, {"render", kSmallCt, "-o", path("turned.png"), "--size",
                                         "96x96", "--distributed", "--stats", "--repeat", "3"});
        QVERIFY2(turned.exitCode == 0, qPrintable(turned.err));
        QCOMPARE(statOf(turned.out, "ranks_frame_buffers_recycled"), 3.0); // the last frame's
    }

    void aRankReadsOnlyItsSlab() {
        if (!QFileInfo::exists(kLargerCt)) {
            QSKIP("the 140-slice Philips CT is not in ../shared/data");
        }
        const CliRun r =
            runMpi(4, {"render", kLargerCt, "-o", path("slab.png"), "--size", "64x64",
                       "--distributed", "--stats", "--brick", "16", "--elevation", "90"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(statOf(r.out, "rank_slab_reading_min"), 1.0);
        const double most = statOf(r.out, "rank_files_read_max");
        QVERIFY2(most > 0.0 && most < 140.0,
                 qPrintable(QString("a rank read %1 of 140 files").arg(most)));
        // A rank holds at most its share of the voxels plus its halo.
        const double voxels = statOf(r.out, "rank_voxels_max");
        QVERIFY2(voxels > 0.0 && voxels <= statOf(r.out, "rank_voxels_bound_max"),
                 qPrintable(r.out));
    }

    // A MetaImage (the 140-slice CT converted): each rank reads the byte
    // range of its slab's slices, not the whole file.
    void aRankReadsOnlyItsByteRange() {
        if (!QFileInfo::exists(kLargerCt)) {
            QSKIP("the 140-slice Philips CT is not in ../shared/data");
        }
        const CliRun convert = runCli({"convert", kLargerCt, path("ct.mhd")});
        QVERIFY2(convert.exitCode == 0, qPrintable(convert.err));
        const QStringList flags = {"--size", "64x64", "--elevation", "90", "--brick", "16"};
        const CliRun local =
            runCli(QStringList{"render", path("ct.mhd"), "-o", path("mhd_local.png")} + flags);
        QVERIFY2(local.exitCode == 0, qPrintable(local.err));
        const CliRun r = runMpi(3, QStringList{"render", path("ct.mhd"), "-o", path("mhd.png"),
                                               "--distributed", "--stats"} +
                                       flags);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(statOf(r.out, "rank_slab_reading_min"), 1.0);
        const double whole = statOf(r.out, "volume_voxels") * 2.0; // int16
        const double part = statOf(r.out, "rank_part_bytes_read_max");
        QVERIFY2(
            part > 0.0 && part < 0.6 * whole,
            qPrintable(QString("a rank read %1 of %2 bytes for its part").arg(part).arg(whole)));
        const double db = psnr(readPng(path("mhd_local.png").toStdString()),
                               readPng(path("mhd.png").toStdString()));
        QVERIFY2(db >= 50.0, qPrintable(QString("%1 dB").arg(db)));
    }

    void moreRanksThanBricksIsAClearError() {
        QElapsedTimer timer;
        timer.start();
        // Bricks of 512 voxels: the 512 x 512 x 28 CT is one brick.
        const CliRun r = runMpi(2, {"render", kSmallCt, "-o", path("none.png"), "--size", "32x32",
                                    "--distributed", "--brick", "512"});
        QCOMPARE(r.exitCode, 3);
        QVERIFY2(r.err.contains("2 parts (ranks)") && r.err.contains("1 bricks"),
                 qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(path("none.png")));
        QVERIFY(timer.elapsed() < 30000);
    }

    // One slice whose pixel data cannot be decoded (JPEG-LS with a damaged
    // stream: its header scans, its pixels do not decode): the rank whose part
    // holds it fails, and the job ends within seconds naming that rank and the
    // file, with no image written.
    void anUnreadablePartEndsTheJob() {
        const QString copy = path("broken");
        QVERIFY(QDir().mkpath(copy));
        const QStringList files = QDir(kSmallCt).entryList(QDir::Files, QDir::Name);
        QCOMPARE(files.size(), 28);
        for (const QString& f : files) {
            QVERIFY(QFile::copy(QDir(kSmallCt).filePath(f), QDir(copy).filePath(f)));
            QFile(QDir(copy).filePath(f)).setPermissions(QFile::ReadOwner | QFile::WriteOwner);
        }
        const QString victim = files.last();
        const QString compressed = path("victim.dcm");
        QProcess gdcmconv;
        gdcmconv.start("gdcmconv", {"--jpegls", QDir(kSmallCt).filePath(victim), compressed});
        if (!gdcmconv.waitForFinished(30000) || gdcmconv.exitCode() != 0) {
            QFAIL("gdcmconv (package libgdcm-tools) could not write a JPEG-LS slice");
        }
        QFile in(compressed);
        QVERIFY(in.open(QIODevice::ReadOnly));
        QByteArray bytes = in.readAll();
        for (qsizetype i = bytes.size() / 2; i < bytes.size() / 2 + 2000; ++i) {
            bytes[i] = char(i % 2 == 0 ? 0xFF : 0x00);
        }
        QFile out(QDir(copy).filePath(victim));
        QVERIFY(out.open(QIODevice::WriteOnly | QIODevice::Truncate));
        QCOMPARE(out.write(bytes), bytes.size());
        out.close();
        QElapsedTimer timer;
        timer.start();
        const CliRun r = runMpi(2,
                                {"render", copy, "-o", path("broken.png"), "--size", "32x32",
                                 "--distributed", "--brick", "16"},
                                60000);
        QVERIFY2(r.exitCode == 3, qPrintable(r.out + r.err));
        QVERIFY2(r.err.contains(QRegularExpression("rank [01]: reading")), qPrintable(r.err));
        QVERIFY2(r.err.contains(victim), qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(path("broken.png")));
        QVERIFY2(timer.elapsed() < 20000, qPrintable(QString::number(timer.elapsed())));
    }

    void withoutMpirunItIsOneRank() {
        compare(1, {}, 90.0); // one rank: the same image as today
        const CliRun r = runCli({"render", kSmallCt, "-o", path("one.png"), "--size", "32x32",
                                 "--distributed", "--stats"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(statOf(r.out, "ranks"), 1.0);
    }
};

QTEST_GUILESS_MAIN(TestDistributedCli)
#include "test_distributed_cli.moc"
