// The workstation's "Invite Students" on a real lucent-server (loopback, real
// CT): the remote view's connection presents a teaching session, an invite
// comes with its link and QR code (read back with zbarimg), a student joins by
// the invite and gets the de-identified frames, the link is copied, revoking
// drops the student, and stopping presenting ends the session. Offscreen.
#include <QApplication>
#include <QClipboard>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QProcess>
#include <QPushButton>
#include <QStandardPaths>
#include <QTest>

#include "core/io/Catalog.h"
#include "render/RemoteRenderBackend.h"
#include "tests/server/RemoteTestFixture.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/RealData.h"
#include "ui/volume/InviteDialog.h"
#include "ui/volume/QrCodeView.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr char kRealSeries[] = "dcm_qa_ct/Philips_S21570/S2010";

} // namespace

class TestInviteDialog : public QObject {
    Q_OBJECT

private slots:
    void presentsAndInvitesStudents() {
        REQUIRE_DATA(kRealSeries);
        const QString zbarimg = QStandardPaths::findExecutable("zbarimg");
        QVERIFY2(!zbarimg.isEmpty(), "zbarimg is missing (apt-get install zbar-tools)");
        const QString data = QString::fromStdString((kRealData / kRealSeries).string());
        ServerProcess server("cpu", data);
        QVERIFY(server.port());
        const auto volume = std::make_shared<const Volume>(loadPath(data.toStdString()));

        RemoteRenderBackend backend;
        backend.setReconnectDelays(200, 1000);
        QList<BackendFrame> frames;
        QObject::connect(&backend, &RenderBackend::frameReady,
                         [&](const BackendFrame& f) { frames.append(f); });
        backend.setVolume(volume);
        backend.connectTo({server.url(), kToken, {}});
        RenderDescription view;
        view.width = 96;
        view.height = 96;
        view.transferFunction = loadPreset("ct-bone");
        backend.request(view, {});
        QVERIFY(
            QTest::qWaitFor([&] { return backend.status() == BackendStatus::Connected; }, 30000));

        InviteDialog dialog(backend);
        dialog.show();
        QVERIFY(!dialog.inviteButton()->isEnabled()); // not presenting yet
        QTest::mouseClick(dialog.presentButton(), Qt::LeftButton);
        QVERIFY2(QTest::qWaitFor([&] { return !backend.sessionId().isEmpty(); }, 30000),
                 qPrintable(backend.statusMessage()));
        QVERIFY(dialog.statusLabel()->text().contains(backend.sessionId()));
        // The view renders in the session, on the de-identified copy.
        QVERIFY(
            QTest::qWaitFor([&] { return backend.status() == BackendStatus::Connected; }, 30000));
        QVERIFY(backend.openSeries().toStdString() != volume->seriesUid);
        frames.clear();
        view.camera.azimuth = 30.0;
        backend.request(view, {});
        QVERIFY(QTest::qWaitFor([&] { return !frames.isEmpty() && frames.back().current; }, 60000));

        QVERIFY(dialog.inviteButton()->isEnabled());
        dialog.lifetimePicker()->setCurrentIndex(1); // an hour
        QTest::mouseClick(dialog.inviteButton(), Qt::LeftButton);
        QVERIFY(QTest::qWaitFor([&] { return !dialog.linkEdit()->text().isEmpty(); }, 20000));
        const QString link = dialog.linkEdit()->text();
        QVERIFY2(link.startsWith(QString("http://127.0.0.1:%1/#invite=").arg(server.port())),
                 qPrintable(link));
        const QString code = link.mid(link.indexOf("#invite=") + 8);

        // The QR code on screen reads back as the link.
        const QString png = server.dir() + "/qr.png";
        QVERIFY(dialog.qrView()->image(5).save(png));
        QProcess decoder;
        decoder.start(zbarimg, {"--raw", "-q", png});
        QVERIFY(decoder.waitForFinished(30000));
        QCOMPARE(QString::fromUtf8(decoder.readAllStandardOutput()).trimmed(), link);
        QTest::mouseClick(dialog.copyButton(), Qt::LeftButton);
        QCOMPARE(QGuiApplication::clipboard()->text(), link);

        // A student joins by the invite and watches the session's frames.
        RemoteTestClient student(server.port(), {"lucent.v3", "lucent.invite." + code});
        const QJsonObject opened = student.waitForText("opened");
        QCOMPARE(opened["series"].toString(), backend.openSeries());
        QVERIFY(QTest::qWaitFor([&] { return !student.frames.isEmpty(); }, 30000));

        // Revoked: the student is dropped and the dialog clears the link.
        QTest::mouseClick(dialog.revokeButton(), Qt::LeftButton);
        QVERIFY(student.waitDisconnected(20000));
        QVERIFY(QTest::qWaitFor([&] { return dialog.linkEdit()->text().isEmpty(); }, 20000));

        // Stopping: the session ends; the view renders on its own again.
        QTest::mouseClick(dialog.presentButton(), Qt::LeftButton);
        QVERIFY(backend.sessionId().isEmpty());
        QVERIFY(!dialog.inviteButton()->isEnabled());
        QVERIFY(
            QTest::qWaitFor([&] { return backend.status() == BackendStatus::Connected; }, 30000));
        QCOMPARE(backend.openSeries().toStdString(), volume->seriesUid);
        QVERIFY(!server.log().contains(code));
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestInviteDialog test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_invite_dialog.moc"
