// lucent-cli render SERIES --backend ws://HOST:PORT --token T against a real
// lucent-server: the still frame equals the local render; a wrong token, an
// unknown series and no server are exit 4 with a message that says which.
#include <QJsonArray>
#include <QTest>

#include "RemoteTestFixture.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/support/CliRunner.h"

using namespace lucent;
using namespace lucent::test;

namespace {

// The uid of the server's only series, through the protocol itself.
QString onlySeries(quint16 port) {
    RemoteTestClient client(port);
    if (!client.waitConnected() || !client.authenticate()) {
        return {};
    }
    client.send({{"type", "list"}});
    const QJsonArray series = client.waitForText("series")["series"].toArray();
    return series.size() == 1 ? series[0].toObject()["uid"].toString() : QString();
}

} // namespace

class TestRemoteCli : public QObject {
    Q_OBJECT
private slots:
    void stillFrameEqualsTheLocalRender() {
        ServerProcess server("cpu");
        const QString uid = onlySeries(server.port());
        QVERIFY(!uid.isEmpty());
        QTemporaryDir dir;
        const QString png = dir.filePath("remote.png");
        const QString url = QString("ws://127.0.0.1:%1").arg(server.port());
        const CliRun r = runCli({"render", uid, "-o", png, "--backend", url, "--token", kToken,
                                 "--size", "96x80", "--preset", "ct-bone", "--azimuth", "30",
                                 "--elevation", "-10", "--stats"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(r.out.contains("backend=remote"), qPrintable(r.out));
        const Volume v = loadPath(server.volumeFile().toStdString());
        RenderDescription d;
        d.volume = &v;
        d.width = 96;
        d.height = 80;
        d.transferFunction = loadPreset("ct-bone");
        d.camera.azimuth = 30.0;
        d.camera.elevation = -10.0;
        const ImageRGBA8 local = CpuRayCaster(v).render(d).image;
        const ImageRGBA8 remote = readPng(png.toStdString());
        QCOMPARE(remote.width, 96);
        QCOMPARE(remote.height, 80);
        const double p = psnr(remote, local);
        QVERIFY2(p >= 40.0, qPrintable(QString("remote vs local: %1 dB").arg(p)));
    }

    // --distance, --pan-right and --pan-up reach the server: the remote still
    // equals the local render of the same camera, and differs from the centred one.
    void panAndDistanceAreSent_data() {
        QTest::addColumn<QStringList>("arguments");
        QTest::addColumn<double>("distance");
        QTest::addColumn<double>("panRight");
        QTest::addColumn<double>("panUp");
        QTest::newRow("pan") << QStringList{"--pan-right", "9", "--pan-up", "-6"} << 0.0 << 9.0
                             << -6.0;
        QTest::newRow("distance") << QStringList{"--distance", "70"} << 70.0 << 0.0 << 0.0;
        QTest::newRow("both") << QStringList{"--distance", "120",      "--pan-right",
                                             "-7.5",       "--pan-up", "4"}
                              << 120.0 << -7.5 << 4.0;
    }
    void panAndDistanceAreSent() {
        QFETCH(QStringList, arguments);
        QFETCH(double, distance);
        QFETCH(double, panRight);
        QFETCH(double, panUp);
        ServerProcess server("cpu");
        const QString uid = onlySeries(server.port());
        QVERIFY(!uid.isEmpty());
        QTemporaryDir dir;
        const QString png = dir.filePath("remote.png");
        const QString url = QString("ws://127.0.0.1:%1").arg(server.port());
        const CliRun r = runCli(QStringList{"render", uid, "-o", png, "--backend", url, "--token",
                                            kToken, "--size", "96x96", "--preset", "ct-bone",
                                            "--azimuth", "20", "--zoom", "1.4"} +
                                arguments);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(!r.err.contains("not sent"), qPrintable(r.err));
        const Volume v = loadPath(server.volumeFile().toStdString());
        RenderDescription d;
        d.volume = &v;
        d.width = 96;
        d.height = 96;
        d.transferFunction = loadPreset("ct-bone");
        d.camera.azimuth = 20.0;
        d.camera.zoom = 1.4;
        const ImageRGBA8 centred = CpuRayCaster(v).render(d).image;
        d.camera.distance = distance;
        d.camera.panRight = panRight;
        d.camera.panUp = panUp;
        const ImageRGBA8 local = CpuRayCaster(v).render(d).image;
        const ImageRGBA8 remote = readPng(png.toStdString());
        const double p = psnr(remote, local);
        qInfo("%s: remote vs local %.1f dB, local vs centred %.1f dB", QTest::currentDataTag(), p,
              psnr(local, centred));
        QVERIFY2(p >= 40.0, qPrintable(QString("remote vs local: %1 dB").arg(p)));
        QVERIFY(psnr(local, centred) < 30.0); // the camera's change shows
    }

    void failuresSayWhich() {
        ServerProcess server("cpu");
        const QString uid = onlySeries(server.port());
        QTemporaryDir dir;
        const QString url = QString("ws://127.0.0.1:%1").arg(server.port());
        const QString png = dir.filePath("x.png");
        const CliRun wrong =
            runCli({"render", uid, "-o", png, "--backend", url, "--token", "not-the-token"});
        QCOMPARE(wrong.exitCode, 4);
        QVERIFY2(wrong.err.contains("auth-failed"), qPrintable(wrong.err));
        const CliRun unknown =
            runCli({"render", "1.2.3.4", "-o", png, "--backend", url, "--token", kToken});
        QCOMPARE(unknown.exitCode, 4);
        QVERIFY2(unknown.err.contains("not-found"), qPrintable(unknown.err));
        const CliRun noToken = runCli({"render", uid, "-o", png, "--backend", url});
        QCOMPARE(noToken.exitCode, 2);
        QVERIFY2(noToken.err.contains("--token"), qPrintable(noToken.err));
        QVERIFY(!QFile::exists(png));
    }

    void noServerIsANetworkError() {
        const CliRun r = runCli({"render", "1.2.3", "-o", "/tmp/never.png", "--backend",
                                 "ws://127.0.0.1:1", "--token", kToken});
        QCOMPARE(r.exitCode, 4);
        QVERIFY2(r.err.contains("ws://127.0.0.1:1"), qPrintable(r.err));
    }
};

QTEST_GUILESS_MAIN(TestRemoteCli)
#include "test_remote_cli.moc"
