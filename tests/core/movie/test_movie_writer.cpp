// core/movie on synthetic frames: the writer's files decode (ffprobe) with the
// frames written; a cancelled or failed movie leaves nothing behind; refusals
// name the file; the GIF palette keeps images of up to 256 colours exact and
// others close; cine frames step evenly through the slices.
#include <QDir>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>

#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "core/movie/MovieFrames.h"
#include "core/movie/MovieWriter.h"
#include "core/movie/PaletteQuantizer.h"
#include "tests/support/MovieProbe.h"

using namespace lucent;

namespace {

// A smooth colour ramp that moves with k: many colours, like a shaded rendering.
ImageRGBA8 rampFrame(int width, int height, int k) {
    ImageRGBA8 image = ImageRGBA8::filled(width, height, 255);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = image.at(x, y);
            p[0] = std::uint8_t((x * 255) / (width - 1));
            p[1] = std::uint8_t((y * 255) / (height - 1));
            p[2] = std::uint8_t((x + y + 8 * k) % 256);
        }
    }
    return image;
}

// Frames from a function, stopping nothing: the movie's frames for writeMovie.
class RampFrames : public MovieFrames {
public:
    RampFrames(int count, int width, int height) : count_(count), width_(width), height_(height) {}
    int count() const override { return count_; }
    ImageRGBA8 frame(int k) override { return rampFrame(width_, height_, k); }

private:
    int count_, width_, height_;
};

} // namespace

class TestMovieWriter : public QObject {
    Q_OBJECT

private slots:
    void formatsFromTheExtension() {
        QCOMPARE(movieFormatOf("a/b.mp4"), MovieFormat::Mp4);
        QCOMPARE(movieFormatOf("B.WebM"), MovieFormat::WebM);
        QCOMPARE(movieFormatOf("c.gif"), MovieFormat::Gif);
        try {
            movieFormatOf("clip.mov");
            QFAIL("a .mov was taken");
        } catch (const MovieError& e) {
            QVERIFY2(QString(e.what()).contains("clip.mov"), e.what());
        }
    }

    void writesEveryFrame_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<QString>("codec");
        QTest::newRow("mp4") << "ramp.mp4"
                             << "h264";
        QTest::newRow("webm") << "ramp.webm"
                              << "vp9";
        QTest::newRow("gif") << "ramp.gif"
                             << "gif";
    }

    void writesEveryFrame() {
        QFETCH(QString, name);
        QFETCH(QString, codec);
        QTemporaryDir dir;
        const QString file = dir.filePath(name);
        {
            MovieWriter writer(file.toStdString(), {96, 64, 10});
            RampFrames frames(7, 96, 64);
            int calls = 0;
            QVERIFY(writeMovie(frames, writer, [&](int done, int total) {
                ++calls;
                return done <= total;
            }));
            QCOMPARE(calls, 8); // before the first frame and after each
            QCOMPARE(writer.framesWritten(), 7);
        }
        QCOMPARE(test::filesIn(dir.path()), QStringList{name}); // no temporary file left
        const test::ProbedMovie probed = test::probeMovie(file);
        QVERIFY2(probed.error.isEmpty(), qPrintable(probed.error));
        QCOMPARE(probed.codec, codec);
        QCOMPARE(probed.frames, 7);
        QCOMPARE(probed.width, 96);
        QCOMPARE(probed.height, 64);
        const QString decoded = dir.filePath("frames");
        const QString error = test::decodeFrames(file, decoded);
        QVERIFY2(error.isEmpty(), qPrintable(error));
        const double db =
            psnr(rampFrame(96, 64, 3), readPng(test::framePng(decoded, 3).toStdString()));
        qInfo("%s frame 3: %.2f dB", qPrintable(name), db);
        QVERIFY2(db >= 35.0, qPrintable(QString::number(db)));
    }

    void cancelLeavesNoFile() {
        QTemporaryDir dir;
        const QString file = dir.filePath("cancelled.mp4");
        {
            MovieWriter writer(file.toStdString(), {64, 64, 25});
            RampFrames frames(20, 64, 64);
            QVERIFY(!writeMovie(frames, writer, [](int done, int) { return done < 5; }));
            QCOMPARE(writer.framesWritten(), 5);
            QCOMPARE(test::filesIn(dir.path()).size(), 1); // the temporary file, while writing
            QVERIFY(!QFile::exists(file));
        }
        QCOMPARE(test::filesIn(dir.path()), QStringList{});
    }

    void failedFrameLeavesNoFile() {
        QTemporaryDir dir;
        const QString file = dir.filePath("failed.webm");
        {
            MovieWriter writer(file.toStdString(), {64, 64, 25});
            writer.add(rampFrame(64, 64, 0));
            QVERIFY_THROWS_EXCEPTION(MovieError, writer.add(rampFrame(32, 64, 1)));
        }
        QCOMPARE(test::filesIn(dir.path()), QStringList{});
    }

    void refusesWhatItCannotWrite() {
        QTemporaryDir dir;
        QFile blocker(dir.filePath("blocker"));
        QVERIFY(blocker.open(QIODevice::WriteOnly));
        blocker.close();
        const auto refusal = [](const QString& file, const MovieSettings& settings) {
            try {
                MovieWriter writer(file.toStdString(), settings);
            } catch (const MovieError& e) {
                return QString(e.what());
            }
            return QString();
        };
        QVERIFY(refusal(dir.filePath("blocker/x.mp4"), {}).contains("cannot write a file in"));
        QVERIFY(refusal(dir.filePath("x.mp4"), {63, 64, 25}).contains("even width and height"));
        QVERIFY(refusal(dir.filePath("x.gif"), {64, 64, 0}).contains("frame rate"));
        QVERIFY(refusal(dir.filePath("x.tiff"), {}).contains("x.tiff"));
        QCOMPARE(test::filesIn(dir.path()), QStringList{"blocker"});
        // GIF takes odd sizes (no 4:2:0).
        QVERIFY(refusal(dir.filePath("odd.gif"), {63, 33, 25}).isEmpty());
        MovieWriter empty(dir.filePath("empty.gif").toStdString(), {8, 8, 25});
        QVERIFY_THROWS_EXCEPTION(MovieError, empty.finish());
    }

    void paletteKeepsFewColoursExact() {
        ImageRGBA8 image = ImageRGBA8::filled(40, 30, 255);
        for (int y = 0; y < 30; ++y) {
            for (int x = 0; x < 40; ++x) {
                const int c = (x / 4) * 20 + y / 2; // 10 x 15 = 150 colours
                image.at(x, y, 0) = std::uint8_t(c);
                image.at(x, y, 1) = std::uint8_t(255 - c);
                image.at(x, y, 2) = std::uint8_t((c * 7) % 256);
            }
        }
        const PalettedImage p = quantizeToPalette(image);
        QCOMPARE(p.palette.size(), std::size_t(150));
        for (int y = 0; y < 30; ++y) {
            for (int x = 0; x < 40; ++x) {
                const auto& c = p.palette[p.indices[std::size_t(y * 40 + x)]];
                QCOMPARE(int(c[0]), int(image.at(x, y, 0)));
                QCOMPARE(int(c[1]), int(image.at(x, y, 1)));
                QCOMPARE(int(c[2]), int(image.at(x, y, 2)));
            }
        }
        const PalettedImage ramp = quantizeToPalette(rampFrame(128, 128, 0));
        QCOMPARE(ramp.palette.size(), std::size_t(256));
    }

    void cineSlicesSpreadEvenly() {
        QCOMPARE(cineSlice(28, 0, 27), 27);
        QCOMPARE(cineSlice(28, 12, 0), 0);
        QCOMPARE(cineSlice(28, 12, 11), 27);
        QCOMPARE(cineSlice(28, 12, 4), int(std::lround(4 * 27.0 / 11.0)));
        QCOMPARE(cineSlice(28, 1, 0), 14);
        QCOMPARE(cineSlice(10, 40, 7), 7); // more frames than slices: every slice
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseIndexAxis("x"));
    }

    // Slice k of a small volume holds k * 100 everywhere: each frame is its slice's
    // value through the window, and asking more frames than slices gives each slice once.
    void cineFramesShowTheirSlices() {
        VolumeGeometry g;
        g.dims = {6, 4, 5};
        Volume volume(g, VoxelType::Int16);
        auto voxels = volume.voxels<std::int16_t>();
        for (int k = 0; k < 5; ++k) {
            for (int n = 0; n < 24; ++n) {
                voxels[std::size_t(k * 24 + n)] = std::int16_t(k * 100);
            }
        }
        const WindowLevel window{200.0, 400.0, 1.0};
        CineFrames cine(volume, IndexAxis::K, 12, window, 12, 8);
        QCOMPARE(cine.count(), 5);
        for (int k = 0; k < 5; ++k) {
            const ImageRGBA8 frame = cine.frame(k);
            QCOMPARE(frame.width, 12);
            QCOMPARE(frame.height, 8);
            QCOMPARE(int(frame.at(6, 4, 0)), int(windowToGrey(k * 100.0, 200.0, 400.0)));
            QCOMPARE(int(frame.at(6, 4, 3)), 255);
        }
        QCOMPARE(CineFrames(volume, IndexAxis::I, 0, window, 8, 8).count(), 6);
        QCOMPARE(CineFrames(volume, IndexAxis::J, 3, window, 8, 8).count(), 3);
    }

    // Axis i of a volume turned 90 degrees about z: the plane is spanned by j and k
    // and samples slice i exactly.
    void cinePlaneLiesInTheSlice() {
        VolumeGeometry g;
        g.dims = {6, 8, 10};
        g.spacing = {1.0, 2.0, 3.0};
        g.direction = glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 0, 1));
        for (const int slice : {0, 3, 5}) {
            const SlicePlane plane = cinePlane(g, IndexAxis::I, slice, 40, 30);
            for (const auto& [x, y] : {std::pair{0.0, 0.0}, {39.0, 29.0}, {12.0, 7.0}}) {
                QCOMPARE(g.toIndex(plane.pointAt(x, y)).x + 1.0, slice + 1.0);
            }
        }
        // i runs posterior: the nearest view is coronal (right = +x, down = -z).
        const SlicePlane plane = cinePlane(g, IndexAxis::I, 2, 40, 30);
        QVERIFY(glm::dot(plane.u, glm::dvec3(1, 0, 0)) > 0.999);
        QVERIFY(glm::dot(plane.v, glm::dvec3(0, 0, -1)) > 0.999);
    }
};

QTEST_GUILESS_MAIN(TestMovieWriter)
#include "test_movie_writer.moc"
