// The workstation presenting a session on a real lucent-server (loopback, real
// CT) while a student looks around on their own (free look): "Invite Students"
// says how many do, and "Bring Everyone Back" snaps the student back to the
// workstation's view (the student's next frame equals the workstation's newest
// frame, >= 50 dB). Offscreen.
#include <QApplication>
#include <QDir>
#include <QLabel>
#include <QPushButton>
#include <QTest>

#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "render/RemoteRenderBackend.h"
#include "tests/server/RemoteTestFixture.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/RealData.h"
#include "ui/volume/InviteDialog.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr char kRealSeries[] = "dcm_qa_ct/Philips_S21570/S2010";

} // namespace

class TestPresenterFreeLook : public QObject {
    Q_OBJECT

private slots:
    void theWorkstationSeesFreeLookAndBringsEveryoneBack() {
        REQUIRE_DATA(kRealSeries);
        const QString data = QString::fromStdString((kRealData / kRealSeries).string());
        ServerProcess server("cpu", data);
        QVERIFY(server.port());
        const auto volume = std::make_shared<const Volume>(loadPath(data.toStdString()));

        RemoteRenderBackend backend;
        QList<BackendFrame> frames;
        QObject::connect(&backend, &RenderBackend::frameReady,
                         [&](const BackendFrame& f) { frames.append(f); });
        backend.setVolume(volume);
        backend.connectTo({server.url(), kToken, {}});
        RenderDescription view;
        view.width = 96;
        view.height = 96;
        view.transferFunction = loadPreset("ct-bone");
        view.camera.azimuth = 25.0;
        backend.request(view, {});
        QVERIFY(
            QTest::qWaitFor([&] { return backend.status() == BackendStatus::Connected; }, 30000));
        InviteDialog dialog(backend);
        dialog.show();
        QVERIFY(!dialog.recallButton()->isEnabled());
        QTest::mouseClick(dialog.presentButton(), Qt::LeftButton);
        QVERIFY(QTest::qWaitFor(
            [&] {
                return !backend.sessionId().isEmpty() &&
                       backend.status() == BackendStatus::Connected;
            },
            30000));
        QVERIFY(QTest::qWaitFor([&] { return !frames.isEmpty() && frames.back().current; }, 60000));
        QCOMPARE(backend.serverVersion(), 4);

        // A student (token, version 4) follows, then looks around on their own.
        RemoteTestClient student(server.port(), {"lucent.v4"});
        QVERIFY(student.waitConnected() && student.authenticate());
        student.send({{"type", "session-join"}, {"session", backend.sessionId()}});
        QVERIFY(!student.waitForText("opened").isEmpty());
        student.send({{"type", "free-look"}, {"state", "start"}});
        const QJsonObject started = student.waitForText("free-look-started");
        QCOMPARE(started["camera"]["azimuth"].toDouble(), 25.0); // the workstation's camera
        student.seq = std::uint64_t(started["seq"].toInteger());
        student.change({{"type", "camera"}, {"azimuth", -70}, {"elevation", 30}});
        QVERIFY(QTest::qWaitFor(
            [&] {
                return !student.frames.isEmpty() &&
                       student.frames.back().header.seq == student.seq &&
                       student.frames.back().header.format == "png";
            },
            60000));
        QVERIFY(QTest::qWaitFor([&] { return dialog.recallButton()->isEnabled(); }, 20000));
        QVERIFY2(dialog.freeLookLabel()->text().contains("1 student"),
                 qPrintable(dialog.freeLookLabel()->text()));
        const ImageRGBA8 presenterView = frames.back().image;
        QVERIFY(psnr(presenterView, student.frames.back().decoded()) < 30.0);

        // Bring everyone back: the student's next frame is the workstation's view.
        const qsizetype count = student.frames.size();
        QTest::mouseClick(dialog.recallButton(), Qt::LeftButton);
        QCOMPARE(student.waitForText("free-look-ended")["reason"].toString(), "recalled");
        QVERIFY(QTest::qWaitFor([&] { return student.frames.size() > count; }, 30000));
        const ImageRGBA8 back = student.frames[count].decoded();
        const double db = psnr(presenterView, back);
        qInfo("brought back: %.1f dB against the workstation's frame", db);
        if (!(db >= 50.0)) {
            QImage(back.pixels.data(), back.width, back.height, QImage::Format_RGBA8888)
                .save(QDir::temp().filePath("presenter_free_look_back.png"));
        }
        QVERIFY2(db >= 50.0, qPrintable(QString("%1 dB").arg(db)));
        QVERIFY(QTest::qWaitFor([&] { return !dialog.recallButton()->isEnabled(); }, 20000));
        QVERIFY(dialog.freeLookLabel()->text().contains("follows your view"));
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestPresenterFreeLook test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_presenter_free_look.moc"
