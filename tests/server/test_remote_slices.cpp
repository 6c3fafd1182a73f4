// MPR slices (protocol version 4) from the real lucent-server on loopback, on a
// real CT (28 slices of 5 mm: coronal and sagittal planes are resampled): each
// asked view arrives as a grey PNG frame equal to core/mpr's image of the same
// plane and window (the workstation's SliceView path), the wheel's step and a
// preset window move them, the crosshair stays inside the volume; in a teaching
// session every follower gets the presenter's slices (the same bytes, a late
// joiner the last ones), a follower's `slices` is not-presenter, and a version 3
// member is sent none. Skips when ../shared/data is absent.
#include <QDir>
#include <QJsonArray>
#include <QTest>

#include <array>
#include <map>

#include "RemoteTestFixture.h"
#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/mpr/CrosshairSlice.h"
#include "core/mpr/WindowPresets.h"
#include "tests/support/RealData.h"

using namespace lucent;
using namespace lucent::test;
using lucent::remote::SliceFrameInfo;

namespace {

const char* const kSeries = "dcm_qa_ct/Philips_S21570/S2010";
constexpr int kWidth = 200;
constexpr int kHeight = 160;

ImageRGBA8 greyImage(const std::vector<std::uint8_t>& grey, int width, int height) {
    ImageRGBA8 image = ImageRGBA8::filled(width, height);
    for (std::size_t i = 0; i < grey.size(); ++i) {
        image.pixels[4 * i] = image.pixels[4 * i + 1] = image.pixels[4 * i + 2] = grey[i];
        image.pixels[4 * i + 3] = 255;
    }
    return image;
}

// What the workstation's SliceView shows for this frame's view, crosshair and
// window at the frame's size (zoom 1, no pan, no turn).
ImageRGBA8 desktopSlice(const Volume& volume, const SliceFrameInfo& info, int width, int height) {
    const SlicePlane plane =
        crosshairPlane(volume.geometry(), info.view, info.crosshair, width, height);
    return greyImage(
        windowedGrey(sampleImage(volume, plane), info.window.center, info.window.width), width,
        height);
}

// Compares a received slice frame with the desktop's image; saves both on failure.
bool matchesDesktop(const Volume& volume, const ReceivedFrame& frame, double* db) {
    const SliceFrameInfo& info = *frame.header.slice;
    const ImageRGBA8 received = frame.decoded();
    const ImageRGBA8 expected = desktopSlice(volume, info, frame.header.width, frame.header.height);
    *db = psnr(received, expected);
    if (*db < 45.0) {
        const QString name =
            QString("slice-%1-seq%2")
                .arg(QString::fromStdString(std::string(remote::sliceViewName(info.view))))
                .arg(frame.header.seq);
        for (const auto& [image, suffix] :
             {std::pair{&received, "received"}, std::pair{&expected, "desktop"}}) {
            const QString file = QDir::temp().filePath(name + "-" + suffix + ".png");
            QImage(image->pixels.data(), image->width, image->height, QImage::Format_RGBA8888)
                .save(file);
            qWarning() << "saved" << file;
        }
    }
    return *db >= 45.0;
}

// The newest slice frame of each view with at least this seq (waits for all `views`).
std::map<Orientation, ReceivedFrame> slicesOf(RemoteTestClient& client, std::uint64_t seq,
                                              const std::vector<Orientation>& views,
                                              int timeoutMs = 60000) {
    std::map<Orientation, ReceivedFrame> found;
    (void)QTest::qWaitFor(
        [&] {
            found.clear();
            for (const ReceivedFrame& f : client.sliceFrames) {
                if (f.header.seq >= seq) {
                    found[f.header.slice->view] = f;
                }
            }
            return found.size() >= views.size();
        },
        timeoutMs);
    return found;
}

const std::vector<Orientation> kAll{Orientation::Axial, Orientation::Coronal,
                                    Orientation::Sagittal};

// A version 4 client, authenticated, with the server's only series open; its uid.
QString openV4(RemoteTestClient& client) {
    if (!client.waitConnected() || !client.authenticate()) {
        return {};
    }
    client.send({{"type", "list"}});
    const QJsonArray series = client.waitForText("series")["series"].toArray();
    if (series.size() != 1) {
        return {};
    }
    const QString uid = series[0].toObject()["uid"].toString();
    client.send({{"type", "open"}, {"series", uid}});
    return uid;
}

} // namespace

class TestRemoteSlices : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        REQUIRE_DATA(kSeries);
        const Catalog catalog = scanPath((kRealData / kSeries).string());
        QCOMPARE(catalog.series.size(), std::size_t(1));
        volume_ = std::make_unique<Volume>(loadSeries(catalog.series[0]));
        server_ = std::make_unique<ServerProcess>(
            "cpu", QString::fromStdString((kRealData / kSeries).string()));
        QVERIFY2(server_->started(), qPrintable(server_->startError()));
    }

    void slicesEqualTheDesktopsMpr() {
        RemoteTestClient client(server_->port(), {"lucent.v4"});
        QVERIFY(!openV4(client).isEmpty());
        QCOMPARE(client.subprotocol(), QString("lucent.v4"));
        const QJsonArray presets = client.waitForText("hello")["window_presets"].toArray();
        QCOMPARE(presets.size(), qsizetype(windowPresets().size()));
        QCOMPARE(presets[0].toObject()["name"].toString(), QString("Brain"));
        const QJsonArray centre = client.waitForText("opened")["centre"].toArray();
        QCOMPARE(centre.size(), 3);
        const glm::dvec3 mid = volumeCentre(volume_->geometry());
        for (int a = 0; a < 3; ++a) {
            QVERIFY(std::abs(centre[a].toDouble() - mid[a]) < 1e-6);
        }

        // The first slices: the volume's centre, its default window (CT: 40/400).
        client.send({{"type", "slices"}, {"size", QJsonArray{kWidth, kHeight}}});
        auto slices = slicesOf(client, 1, kAll);
        QCOMPARE(slices.size(), std::size_t(3));
        for (const auto& [view, frame] : slices) {
            const SliceFrameInfo& info = *frame.header.slice;
            QCOMPARE(frame.header.width, kWidth);
            QCOMPARE(frame.header.height, kHeight);
            QCOMPARE(frame.header.format, std::string("png"));
            QCOMPARE(info.window, (remote::SliceWindow{40.0, 400.0}));
            QVERIFY(glm::length(info.crosshair - mid) < 1e-6);
            double db = 0.0;
            QVERIFY2(matchesDesktop(*volume_, frame, &db), qPrintable(QString::number(db)));
            qInfo("%s at the centre: %.1f dB against the desktop's slice",
                  remote::sliceViewName(view).data(), db);
            // The plane in the header is the desktop's plane.
            const SlicePlane plane =
                crosshairPlane(volume_->geometry(), view, info.crosshair, kWidth, kHeight);
            QVERIFY(glm::length(info.centre - plane.centre) < 1e-9);
            QVERIFY(glm::length(info.u - plane.u) < 1e-12);
            QCOMPARE(info.pixelMm, plane.pixelSize);
            QCOMPARE(info.stepMm, sliceStep(volume_->geometry(), plane.normal()));
        }
        // The axial step of this CT is its 5 mm slice gap.
        QVERIFY(std::abs(slices[Orientation::Axial].header.slice->stepMm - 5.0) < 0.01);

        // Three wheel notches down the axial stack, and the lung window by name.
        const SliceFrameInfo axial = *slices[Orientation::Axial].header.slice;
        const QByteArray firstAxial = slices[Orientation::Axial].image;
        const glm::dvec3 moved =
            axial.crosshair - 3.0 * axial.stepMm * glm::cross(axial.u, axial.v);
        client.send({{"type", "slices"},
                     {"crosshair", QJsonArray{moved.x, moved.y, moved.z}},
                     {"window", "Lung"}});
        slices = slicesOf(client, 2, kAll);
        QCOMPARE(slices.size(), std::size_t(3));
        for (const auto& [view, frame] : slices) {
            const SliceFrameInfo& info = *frame.header.slice;
            QCOMPARE(frame.header.seq, std::uint64_t(2));
            QCOMPARE(info.window, (remote::SliceWindow{-600.0, 1500.0}));
            QVERIFY(glm::length(info.crosshair - moved) < 1e-6);
            double db = 0.0;
            QVERIFY2(matchesDesktop(*volume_, frame, &db), qPrintable(QString::number(db)));
        }
        QVERIFY(slices[Orientation::Axial].image != firstAxial);

        // One view only; a crosshair far outside is brought into the volume.
        const qsizetype before = client.sliceFrames.size();
        client.send({{"type", "slices"},
                     {"views", QJsonArray{"coronal"}},
                     {"crosshair", QJsonArray{0.0, 0.0, 90000.0}},
                     {"window", QJsonObject{{"center", 100.0}, {"width", 50.0}}}});
        slices = slicesOf(client, 3, {Orientation::Coronal});
        QVERIFY(slices.count(Orientation::Coronal));
        const ReceivedFrame& coronal = slices[Orientation::Coronal];
        const glm::dvec3 ijk = glm::dvec3(volume_->geometry().patientToIndex() *
                                          glm::dvec4(coronal.header.slice->crosshair, 1.0));
        QVERIFY2(ijk.z >= -1e-6 && ijk.z <= volume_->dims().z - 1 + 1e-6,
                 qPrintable(QString::number(ijk.z)));
        double db = 0.0;
        QVERIFY(matchesDesktop(*volume_, coronal, &db));
        QTest::qWait(300);
        for (qsizetype i = before; i < client.sliceFrames.size(); ++i) {
            QCOMPARE(client.sliceFrames[i].header.slice->view, Orientation::Coronal);
        }
        // Refusals name the key and keep the connection.
        client.send({{"type", "slices"}, {"window", "Sunny"}});
        const QJsonObject error = client.waitForText("error");
        QCOMPARE(error["code"].toString(), QString("bad-request"));
        QVERIFY2(error["message"].toString().contains("'window'"),
                 qPrintable(error["message"].toString()));
        QVERIFY(!client.disconnected);
        // Figures: 512 x 512 slices of all three views (render is sampling and windowing).
        client.send({{"type", "slices"},
                     {"views", QJsonArray{"axial", "coronal", "sagittal"}},
                     {"crosshair", QJsonArray{mid.x, mid.y, mid.z}},
                     {"window", QJsonObject{{"center", 40.0}, {"width", 400.0}}},
                     {"size", QJsonArray{512, 512}}});
        slices = slicesOf(client, 4, kAll); // the refused message is not counted
        QCOMPARE(slices.size(), std::size_t(3));
        for (const auto& [view, frame] : slices) {
            QCOMPARE(frame.header.width, 512);
            qInfo("%s 512x512: render %.1f ms, encode %.1f ms, %lld bytes",
                  remote::sliceViewName(view).data(), frame.header.renderMs, frame.header.encodeMs,
                  static_cast<long long>(frame.image.size()));
        }
        // The 3D view still gets its frames.
        client.send({{"type", "render"}});
        QVERIFY(QTest::qWaitFor([&] { return !client.frames.isEmpty(); }, 60000));
        QVERIFY(!client.frames.back().header.slice);
    }

    void slicesNeedVersionFourAndASeries() {
        RemoteTestClient old(server_->port(), {"lucent.v3"});
        QVERIFY(old.waitConnected() && old.authenticate());
        QVERIFY(!old.waitForText("hello").contains("window_presets"));
        old.send({{"type", "slices"}});
        const QJsonObject error = old.waitForText("error");
        QCOMPARE(error["code"].toString(), QString("unknown-type"));
        QVERIFY(error["fatal"].toBool());
        QVERIFY(old.waitDisconnected());

        RemoteTestClient early(server_->port(), {"lucent.v4"});
        QVERIFY(early.waitConnected() && early.authenticate());
        early.send({{"type", "slices"}});
        QCOMPARE(early.waitForText("error")["code"].toString(), QString("out-of-order"));
    }

    void followersSeeThePresentersSlices() {
        RemoteTestClient presenter(server_->port(), {"lucent.v4"});
        QVERIFY(!openV4(presenter).isEmpty());
        presenter.send({{"type", "session-create"}});
        const QString session = presenter.waitForText("session-created")["session"].toString();
        QVERIFY(!session.isEmpty());
        RemoteTestClient follower(server_->port(), {"lucent.v4"});
        RemoteTestClient older(server_->port(), {"lucent.v3"});
        for (RemoteTestClient* c : {&follower, &older}) {
            QVERIFY(c->waitConnected() && c->authenticate());
            c->send({{"type", "session-join"}, {"session", session}});
            QVERIFY(!c->waitForText("opened", 60000).isEmpty());
        }
        presenter.send({{"type", "slices"}, {"size", QJsonArray{96, 80}}, {"window", "Bone"}});
        const auto shown = slicesOf(presenter, 1, kAll);
        const auto seen = slicesOf(follower, 1, kAll);
        QCOMPARE(shown.size(), std::size_t(3));
        QCOMPARE(seen.size(), std::size_t(3));
        for (const Orientation view : kAll) {
            QCOMPARE(seen.at(view).image, shown.at(view).image);
            QVERIFY(seen.at(view).header == shown.at(view).header);
            QCOMPARE(seen.at(view).header.slice->window, (remote::SliceWindow{400.0, 1800.0}));
            double db = 0.0;
            QVERIFY(matchesDesktop(*volume_, seen.at(view), &db)); // the de-identified copy
        }
        // A follower follows: its slices are refused, not fatal.
        follower.send({{"type", "slices"}, {"window", "Brain"}});
        QCOMPARE(follower.waitForText("error")["code"].toString(), QString("not-presenter"));
        QVERIFY(!follower.disconnected);
        // A member who joins later gets the last slices at once.
        RemoteTestClient late(server_->port(), {"lucent.v4"});
        QVERIFY(late.waitConnected() && late.authenticate());
        late.send({{"type", "session-join"}, {"session", session}});
        const auto lateSeen = slicesOf(late, 1, kAll, 20000);
        QCOMPARE(lateSeen.size(), std::size_t(3));
        for (const Orientation view : kAll) {
            QCOMPARE(lateSeen.at(view).image, shown.at(view).image);
        }
        // A version 3 member gets the 3D frames but no slice frames.
        QVERIFY(QTest::qWaitFor([&] { return !older.frames.isEmpty(); }, 60000));
        QVERIFY(older.sliceFrames.isEmpty());
    }

private:
    std::unique_ptr<Volume> volume_;
    std::unique_ptr<ServerProcess> server_;
};

QTEST_GUILESS_MAIN(TestRemoteSlices)
#include "test_remote_slices.moc"
