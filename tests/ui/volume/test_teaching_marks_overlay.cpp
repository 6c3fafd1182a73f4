// The workstation's remote 3D view and a session's pointer and marks, on a real
// lucent-server (loopback, the demo head CT): the remote backend presents, marks
// the skull and points; a follower gets both; the backend keeps what the server
// sent and each frame's projection; painted over the frame (as VolumeView does),
// the mark's tip lies where the projection of its anchor is, in the mark's
// colour, before and after a 90 degree turn (the projection checked against
// ViewFrame's within 2 pixels), and the pointer is drawn where it was sent.
// Offscreen.
#include <QApplication>
#include <QImage>
#include <QJsonArray>
#include <QPainter>
#include <QTest>

#include <filesystem>

#include "core/formats/InVesaliusProject.h"
#include "core/scene/ImageProjection.h"
#include "core/scene/ViewFrame.h"
#include "render/RemoteRenderBackend.h"
#include "tests/server/DemoHead.h"
#include "tests/server/RemoteTestFixture.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/volume/TeachingMarksOverlay.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSide = 128;

// The frame with the session's marks painted over it, as the view paints them.
QImage painted(const BackendFrame& frame, const TeachingMarks& marks) {
    QImage image(frame.image.pixels.data(), frame.image.width, frame.image.height,
                 4 * frame.image.width, QImage::Format_RGBA8888);
    QImage out = image.convertToFormat(QImage::Format_RGB32);
    QPainter painter(&out);
    paintTeachingMarks(painter, QRectF(0, 0, out.width(), out.height()), marks, *frame.projection);
    return out;
}

bool near(const QColor& a, const QColor& b) {
    return std::abs(a.red() - b.red()) < 40 && std::abs(a.green() - b.green()) < 40 &&
           std::abs(a.blue() - b.blue()) < 40;
}

} // namespace

class TestTeachingMarksOverlay : public QObject {
    Q_OBJECT

private slots:
    void theViewDrawsTheSessionsMarksOnTheAnatomy() {
        if (!std::filesystem::exists(kDemoHead.toStdString())) {
            QSKIP(kDemoHeadMissing);
        }
        ServerProcess server("cpu", kDemoHead);
        QVERIFY(server.port());
        const auto volume = std::make_shared<const Volume>(readInVesalius(kDemoHead.toStdString()));
        RemoteTestClient lister(server.port(), {"lucent.v4"});
        QVERIFY(lister.waitConnected() && lister.authenticate());
        lister.send({{"type", "list"}});
        const QString uid =
            lister.waitForText("series")["series"].toArray()[0].toObject()["uid"].toString();
        QVERIFY(!uid.isEmpty());

        RemoteRenderBackend backend;
        backend.setReconnectDelays(200, 1000);
        QList<BackendFrame> frames;
        QObject::connect(&backend, &RenderBackend::frameReady,
                         [&](const BackendFrame& f) { frames.append(f); });
        backend.setVolume(volume);
        backend.setPresenting(true);
        backend.connectTo({server.url(), kToken, uid});
        RenderDescription view;
        view.width = view.height = kSide;
        view.transferFunction = loadPreset("ct-bone");
        backend.request(view, {});
        QVERIFY2(QTest::qWaitFor([&] { return !backend.sessionId().isEmpty(); }, 30000),
                 qPrintable(backend.statusMessage()));
        QVERIFY(QTest::qWaitFor([&] { return !frames.isEmpty() && frames.back().current; }, 60000));
        QVERIFY(frames.back().projection);

        RemoteTestClient follower(server.port(), {"lucent.v4"});
        QVERIFY(follower.waitConnected() && follower.authenticate());
        follower.send({{"type", "session-join"}, {"session", backend.sessionId()}});
        QVERIFY(!follower.waitForText("opened").isEmpty());

        int changes = 0;
        QObject::connect(&backend, &RemoteRenderBackend::marksChanged, [&] { ++changes; });
        backend.placeMark({remote::MarkKind::Arrow, {{0.5, 0.4}, {0.7, 0.25}}, {}});
        backend.point(glm::dvec2(0.3, 0.62));
        const QJsonObject mark = follower.waitForText("mark");
        QCOMPARE(mark["kind"].toString(), "arrow");
        QCOMPARE(follower.waitForText("pointer")["x"].toDouble(), 0.3);
        QVERIFY(
            QTest::qWaitFor([&] { return backend.teachingMarks().pointer().has_value(); }, 20000));
        // The server sends the pointer at once, the mark once it is anchored.
        QVERIFY(
            QTest::qWaitFor([&] { return backend.teachingMarks().marks().size() == 1; }, 20000));
        QVERIFY(changes >= 2);
        const glm::dvec3 tip = backend.teachingMarks().marks().begin()->second.anchors[0];
        QVERIFY2(maxValueNear(*volume, tip, 2.0) > 300.0, "the arrow's tip is not on bone");

        for (const double azimuth : {0.0, 90.0}) {
            if (azimuth != 0.0) {
                view.camera.azimuth = azimuth;
                frames.clear();
                backend.request(view, {});
                QVERIFY(QTest::qWaitFor([&] { return !frames.isEmpty() && frames.back().current; },
                                        60000));
            }
            const BackendFrame& frame = frames.back();
            QVERIFY(frame.projection);
            const auto at = projectToImage(*frame.projection, tip);
            const auto expected = projectToImage(
                imageProjection(makeViewFrame(volume->geometry(), view.camera, kSide, kSide)), tip);
            QVERIFY(at && expected);
            QVERIFY2(glm::length(*at - *expected) * kSide < 2.0,
                     qPrintable(QString("azimuth %1: the frame puts the tip %2 pixels off")
                                    .arg(azimuth)
                                    .arg(glm::length(*at - *expected) * kSide)));
            const QImage image = painted(frame, backend.teachingMarks());
            const QColor tipColour = image.pixelColor(int(at->x * kSide), int(at->y * kSide));
            QVERIFY2(near(tipColour, kMarkColour),
                     qPrintable(
                         QString("azimuth %1: %2 at the tip").arg(azimuth).arg(tipColour.name())));
            const QColor dot = image.pixelColor(int(0.3 * kSide), int(0.62 * kSide));
            QVERIFY2(near(dot, kPointerColour), qPrintable(dot.name()));
        }

        backend.clearMarks();
        QVERIFY(!follower.waitForText("marks-cleared").isEmpty());
        QVERIFY(QTest::qWaitFor([&] { return backend.teachingMarks().marks().empty(); }, 20000));
    }
};

int main(int argc, char** argv) {
    useOffscreenPlatform();
    QApplication app(argc, argv);
    TestTeachingMarksOverlay test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_teaching_marks_overlay.moc"
