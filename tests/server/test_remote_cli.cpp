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
