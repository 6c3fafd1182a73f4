// lucent-cli movie on a real CT: MP4, WebM and GIF decode (ffprobe) with the
// asked codec, frame count and size; a turntable's frame k is the still render
// at azimuth k * DEG / N and a cine's frame k is the slice it shows, windowed,
// within 35 dB (lossy codecs); an unknown format and an unwritable output fail
// with a message and leave no file.
#include <QDir>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>

#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/mpr/PlaneSampler.h"
#include "tests/support/MovieProbe.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

const char* kCt = "dcm_qa_ct/Philips_S21570/S2010"; // 28 slices 512x512, 5 mm
constexpr double kMinPsnr = 35.0;

QString ctPath() {
    return QString::fromStdString((test::kRealData / kCt).string());
}

} // namespace

class TestMovieCli : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        QVERIFY2(!test::ffmpegTool("ffprobe").isEmpty() && !test::ffmpegTool("ffmpeg").isEmpty(),
                 "ffprobe and ffmpeg are needed (apt-get install ffmpeg)");
    }

    void turntableFramesAreStillRenders_data() {
        QTest::addColumn<QString>("extension");
        QTest::addColumn<QString>("codec");
        QTest::newRow("mp4") << "mp4"
                             << "h264";
        QTest::newRow("webm") << "webm"
                              << "vp9";
        QTest::newRow("gif") << "gif"
                             << "gif";
    }

    void turntableFramesAreStillRenders() {
        QFETCH(QString, extension);
        QFETCH(QString, codec);
        constexpr int kFrames = 12;
        constexpr double kDegrees = 360.0;
        const QString movie = dir_.filePath("turn." + extension);
        const test::CliRun run = test::runCli({"movie", ctPath(), "-o", movie, "--size", "128x128",
                                               "--frames", QString::number(kFrames), "--turntable",
                                               QString::number(kDegrees), "--elevation", "20"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const test::ProbedMovie probed = test::probeMovie(movie);
        QVERIFY2(probed.error.isEmpty(), qPrintable(probed.error));
        QCOMPARE(probed.codec, codec);
        QCOMPARE(probed.frames, kFrames);
        QCOMPARE(probed.width, 128);
        QCOMPARE(probed.height, 128);

        const QString frames = dir_.filePath("frames-" + extension);
        const QString decodeError = test::decodeFrames(movie, frames);
        QVERIFY2(decodeError.isEmpty(), qPrintable(decodeError));
        for (const int k : {0, 5, 11}) {
            const QString still = dir_.filePath(QString("still-%1-%2.png").arg(extension).arg(k));
            const test::CliRun render =
                test::runCli({"render", ctPath(), "-o", still, "--size", "128x128", "--elevation",
                              "20", "--azimuth", QString::number(k * kDegrees / kFrames)});
            QVERIFY2(render.exitCode == 0, qPrintable(render.err));
            const double db = psnr(readPng(still.toStdString()),
                                   readPng(test::framePng(frames, k).toStdString()));
            qInfo("%s frame %d against the still render: %.2f dB", qPrintable(extension), k, db);
            QVERIFY2(db >= kMinPsnr, qPrintable(QString("frame %1: %2 dB").arg(k).arg(db)));
        }
        // Frame 5 is not frame 0 turned by another angle: the frames are in order.
        const double other =
            psnr(readPng(dir_.filePath("still-" + extension + "-0.png").toStdString()),
                 readPng(test::framePng(frames, 5).toStdString()));
        QVERIFY2(other < kMinPsnr,
                 qPrintable(QString("frame 5 matches azimuth 0: %1 dB").arg(other)));
    }

    // Axis k of this axial CT at its own 512x512 grid: frame n shows slice
    // round(n * 27 / 11) voxel for voxel, in the soft-tissue window.
    void cineFramesAreTheWindowedSlices() {
        const QString movie = dir_.filePath("cine.mp4");
        const test::CliRun run = test::runCli({"movie", ctPath(), "-o", movie, "--cine-axis", "k",
                                               "--size", "512x512", "--frames", "12"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const test::ProbedMovie probed = test::probeMovie(movie);
        QVERIFY2(probed.error.isEmpty(), qPrintable(probed.error));
        QCOMPARE(probed.frames, 12);
        QCOMPARE(probed.width, 512);
        const QString frames = dir_.filePath("frames-cine");
        const QString decodeError = test::decodeFrames(movie, frames);
        QVERIFY2(decodeError.isEmpty(), qPrintable(decodeError));

        const Volume volume = loadPath(test::kRealData / kCt);
        const VolumeGeometry& g = volume.geometry();
        QCOMPARE(g.dims, glm::ivec3(512, 512, 28));
        QVERIFY2(g.direction[0].x > 0.999 && g.direction[1].y > 0.999,
                 "the reference reads rows as the image: i must run left, j posterior");
        for (const int n : {0, 4, 11}) {
            const int slice = int(std::lround(n * 27.0 / 11.0));
            ImageRGBA8 expected = ImageRGBA8::filled(512, 512, 255);
            visitVoxels(volume, [&](auto voxels) {
                for (int y = 0; y < 512; ++y) {
                    for (int x = 0; x < 512; ++x) {
                        const double hu = double(voxels[(std::size_t(slice) * 512 + y) * 512 + x]);
                        const std::uint8_t grey = windowToGrey(hu, 40.0, 400.0);
                        std::fill_n(expected.at(x, y), 3, grey);
                    }
                }
            });
            const double db = psnr(expected, readPng(test::framePng(frames, n).toStdString()));
            qInfo("cine frame %d (slice %d) against the slice: %.2f dB", n, slice, db);
            QVERIFY2(db >= kMinPsnr, qPrintable(QString("cine frame %1: %2 dB").arg(n).arg(db)));
        }
    }

    void cineAlongAnotherAxis() {
        const QString movie = dir_.filePath("cine-j.gif");
        const test::CliRun run =
            test::runCli({"movie", ctPath(), "-o", movie, "--cine-axis", "j", "--size", "96x64",
                          "--frames", "5", "--window", "bone"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const test::ProbedMovie probed = test::probeMovie(movie);
        QVERIFY2(probed.error.isEmpty(), qPrintable(probed.error));
        QCOMPARE(probed.frames, 5);
        QCOMPARE(probed.width, 96);
        QCOMPARE(probed.height, 64);
    }

    void refusalsLeaveNoFile_data() {
        QTest::addColumn<QString>("output");
        QTest::addColumn<int>("exitCode");
        QTest::addColumn<QString>("message");
        QTest::newRow("unknown format") << "out/movie.avi" << 2 << "unknown movie format '.avi'";
        // A regular file as the folder: not writable even for root.
        QTest::newRow("unwritable") << "out/blocker/movie.mp4" << 3 << "cannot write a file in";
        QTest::newRow("odd size for 4:2:0") << "out/odd.mp4" << 3 << "even width and height";
    }

    void refusalsLeaveNoFile() {
        QFETCH(QString, output);
        QFETCH(int, exitCode);
        QFETCH(QString, message);
        const QString out = dir_.filePath("out");
        QDir().mkpath(out);
        QFile blocker(out + "/blocker");
        QVERIFY(blocker.open(QIODevice::WriteOnly));
        blocker.close();
        const QString size = output.contains("odd") ? "127x128" : "64x64";
        const test::CliRun run =
            test::runCli({"movie", ctPath(), "-o", dir_.filePath(output), "--size", size});
        QCOMPARE(run.exitCode, exitCode);
        QVERIFY2(run.err.contains(message), qPrintable(run.err));
        QVERIFY2(run.err.contains(QFileInfo(output).fileName()), qPrintable(run.err));
        QCOMPARE(test::filesIn(out), QStringList{"blocker"});
        QVERIFY(QFile::remove(out + "/blocker"));
    }
};

QTEST_GUILESS_MAIN(TestMovieCli)
#include "test_movie_cli.moc"
