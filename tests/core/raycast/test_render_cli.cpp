// lucent-cli render as a user runs it: the contract's options, --stats, and
// clear errors with exit 2 (usage) or 3 (bad input).
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include "tests/support/CliRunner.h"

#include "core/formats/MetaImage.h"
#include "core/image/PngIO.h"

using namespace lucent;

namespace {

// A small CT-like volume: air around a water ball with a bone shell.
QString writeVolume(const QTemporaryDir& dir) {
    VolumeGeometry g;
    g.dims = {32, 32, 32};
    g.spacing = {0.8, 0.8, 1.2};
    Volume v(g, VoxelType::Int16);
    const auto out = v.voxels<std::int16_t>();
    for (int k = 0; k < 32; ++k) {
        for (int j = 0; j < 32; ++j) {
            for (int i = 0; i < 32; ++i) {
                const double r = glm::length(glm::dvec3(i - 15.5, j - 15.5, (k - 15.5) * 1.5));
                out[v.linearIndex(i, j, k)] = std::int16_t(r < 10 ? 40 : r < 13 ? 1200 : -1000);
            }
        }
    }
    v.modality = "CT";
    const QString path = dir.filePath("ball.mhd");
    writeMetaImage(v, path.toStdString());
    return path;
}

} // namespace

class TestRenderCli : public QObject {
    Q_OBJECT
private slots:
    void rendersWithStats() {
        QTemporaryDir dir;
        const QString vol = writeVolume(dir), png = dir.filePath("out.png");
        const test::CliRun r =
            test::runCli({"render", vol, "-o", png, "--size", "48x40", "--stats", "--repeat", "3"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        for (const char* key : {"load_ms=", "render_ms=", "first_ms=", "samples=", "bricks_total=",
                                "bricks_used=", "lod=0"}) {
            QVERIFY2(r.out.contains(key), qPrintable(r.out));
        }
        const ImageRGBA8 img = readPng(png.toStdString());
        QCOMPARE(img.width, 48);
        QCOMPARE(img.height, 40);
    }

    void modesAndOptions_data() {
        QTest::addColumn<QStringList>("options");
        QTest::newRow("mip") << QStringList{"--mode", "mip"};
        QTest::newRow("minip") << QStringList{"--mode", "minip", "--preset", "ct-mip"};
        QTest::newRow("avg") << QStringList{"--mode", "avg"};
        QTest::newRow("iso") << QStringList{"--mode", "iso", "--iso", "500"};
        QTest::newRow("cubic-double") << QStringList{"--interp", "cubic", "--precision", "double"};
        QTest::newRow("nearest-preclassified")
            << QStringList{"--interp", "nearest", "--preclassify"};
        QTest::newRow("preintegrated") << QStringList{"--preintegrate", "--no-shading"};
        QTest::newRow("camera") << QStringList{"--azimuth", "30",     "--elevation",
                                               "-20",       "--zoom", "1.5"};
        QTest::newRow("bricks") << QStringList{"--brick", "16", "--step", "0.25"};
    }
    void modesAndOptions() {
        QFETCH(QStringList, options);
        QTemporaryDir dir;
        const QString vol = writeVolume(dir), png = dir.filePath("o.png");
        const test::CliRun r =
            test::runCli(QStringList{"render", vol, "-o", png, "--size", "32x32"} + options);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const ImageRGBA8 img = readPng(png.toStdString());
        if (options.contains("minip")) {
            return; // the minimum along every ray here is the air around the ball: black
        }
        int lit = 0;
        for (std::size_t n = 0; n < img.pixels.size(); n += 4) {
            lit += (img.pixels[n] | img.pixels[n + 1] | img.pixels[n + 2]) != 0 ? 1 : 0;
        }
        QVERIFY2(lit > 32, qPrintable(QString("%1 lit pixels").arg(lit)));
    }

    void badInputIsRefused_data() {
        QTest::addColumn<QStringList>("options");
        QTest::addColumn<int>("exitCode");
        QTest::addColumn<QString>("message");
        QTest::newRow("size 0") << QStringList{"--size", "0x0"} << 2 << "image size";
        QTest::newRow("size 100000") << QStringList{"--size", "100000x100000"} << 2 << "image size";
        QTest::newRow("size junk") << QStringList{"--size", "big"} << 2 << "--size";
        QTest::newRow("step 0") << QStringList{"--step", "0"} << 2 << "step";
        QTest::newRow("step negative") << QStringList{"--step", "-1"} << 2 << "step";
        QTest::newRow("unknown preset")
            << QStringList{"--preset", "ct-nothing"} << 3 << "ct-nothing";
        QTest::newRow("unknown mode") << QStringList{"--mode", "xray"} << 2 << "--mode";
        QTest::newRow("unknown backend") << QStringList{"--backend", "vulkan"} << 2 << "backend";
        QTest::newRow("repeat 0") << QStringList{"--repeat", "0"} << 2 << "--repeat";
    }
    void badInputIsRefused() {
        QFETCH(QStringList, options);
        QFETCH(int, exitCode);
        QFETCH(QString, message);
        QTemporaryDir dir;
        const QString vol = writeVolume(dir);
        const test::CliRun r =
            test::runCli(QStringList{"render", vol, "-o", dir.filePath("x.png")} + options);
        QCOMPARE(r.exitCode, exitCode);
        QVERIFY2(r.err.contains(message), qPrintable(r.err));
        QVERIFY(!QFile::exists(dir.filePath("x.png")));
    }

    void malformedTransferFunctionNamesTheFile() {
        QTemporaryDir dir;
        const QString vol = writeVolume(dir), tf = dir.filePath("broken.json");
        QFile f(tf);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(R"({"opacity": [[0, 0.5], [100, 1.5]], "colour": [[0, 1, 1, 1]]})");
        f.close();
        const test::CliRun r =
            test::runCli({"render", vol, "-o", dir.filePath("x.png"), "--tf", tf});
        QCOMPARE(r.exitCode, 3);
        QVERIFY2(r.err.contains("broken.json") && r.err.contains("opacity"), qPrintable(r.err));
    }

    void compareOfTwoRendersOfTheSameSceneIsIdentical() {
        QTemporaryDir dir;
        const QString vol = writeVolume(dir);
        QCOMPARE(
            test::runCli({"render", vol, "-o", dir.filePath("a.png"), "--size", "40x40"}).exitCode,
            0);
        QCOMPARE(test::runCli({"render", vol, "-o", dir.filePath("b.png"), "--size", "40x40",
                               "--brick", "8"})
                     .exitCode,
                 0);
        const test::CliRun r =
            test::runCli({"compare", dir.filePath("a.png"), dir.filePath("b.png")});
        QCOMPARE(r.exitCode, 0);
        QCOMPARE(r.out.trimmed(), QString("psnr_db=inf ssim=1.0000"));
    }
};

QTEST_GUILESS_MAIN(TestRenderCli)
#include "test_render_cli.moc"
