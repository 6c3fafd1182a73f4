// lucent-cli render SERIES --backend ws://HOST:PORT --token T against a real
// lucent-server: the still frame equals the local render, with the sampling
// options too (they travel in version 2's sampling message); a wrong token, an
// unknown series and no server are exit 4 with a message that says which.
// RemoteRenderBackend, which the command uses, speaking version 1 to the server:
// sampling it cannot send is refused, naming it.
#include <QJsonArray>
#include <QRegularExpression>
#include <QTest>

#include <limits>

#include "RemoteTestFixture.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "render/RemoteRenderBackend.h"
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

// A small real CT series (512 x 512 x 28).
QString realSeries() {
    return QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";
}

// `lucent-cli compare A B`'s PSNR (inf for equal images); NaN when it failed.
double comparePsnr(const QString& a, const QString& b) {
    const CliRun r = runCli({"compare", a, b});
    const auto match = QRegularExpression("psnr_db=(\\S+)").match(r.out);
    if (r.exitCode != 0 || !match.hasMatch()) {
        qWarning() << "compare failed:" << r.err << r.out;
        return std::numeric_limits<double>::quiet_NaN();
    }
    return match.captured(1) == "inf" ? std::numeric_limits<double>::infinity()
                                      : match.captured(1).toDouble();
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

    // Every sampling option goes to the server: the remote still equals the local
    // render of the same options (same size, camera, default preset), and options
    // that change the image change the remote one too.
    void samplingOptionsTravel_data() {
        QTest::addColumn<QStringList>("options");
        QTest::addColumn<bool>("changesTheImage");
        QTest::newRow("cubic") << QStringList{"--step", "0.25", "--interp", "cubic"} << true;
        QTest::newRow("coarse") << QStringList{"--step", "2", "--interp", "nearest"} << true;
        QTest::newRow("unshaded, pre-classified, pre-integrated")
            << QStringList{"--no-shading", "--preclassify", "--preintegrate"} << true;
        QTest::newRow("double, no leaping")
            << QStringList{"--precision", "double", "--no-leaping"} << false;
    }
    void samplingOptionsTravel() {
        QFETCH(QStringList, options);
        QFETCH(bool, changesTheImage);
        if (!QFileInfo(realSeries()).isDir()) {
            QSKIP(qPrintable("real data absent: " + realSeries()));
        }
        ServerProcess server("cpu", realSeries());
        const QString uid = onlySeries(server.port());
        QVERIFY(!uid.isEmpty());
        QTemporaryDir dir;
        const QString url = QString("ws://127.0.0.1:%1").arg(server.port());
        const QStringList view{"--size", "96x96", "--azimuth", "30", "--elevation", "10"};
        const auto remote = [&](const QString& name, const QStringList& more) {
            const QString png = dir.filePath(name);
            const CliRun r = runCli(QStringList{"render", uid, "-o", png, "--backend", url,
                                                "--token", kToken, "--stats"} +
                                    view + more);
            return r.exitCode == 0 && !r.err.contains("not sent") ? png : r.err;
        };
        const QString sampled = remote("sampled.png", options);
        QVERIFY2(QFile::exists(sampled), qPrintable(sampled));
        const QString local = dir.filePath("local.png");
        const CliRun l = runCli(
            QStringList{"render", realSeries(), "-o", local, "--backend", "cpu"} + view + options);
        QVERIFY2(l.exitCode == 0, qPrintable(l.err));
        const double same = comparePsnr(sampled, local);
        const QString plain = remote("plain.png", {});
        QVERIFY2(QFile::exists(plain), qPrintable(plain));
        const double change = comparePsnr(sampled, plain);
        qInfo("%s: remote vs local %.1f dB, vs the default sampling %.1f dB",
              QTest::currentDataTag(), same, change);
        QVERIFY2(same >= 40.0, qPrintable(QString("remote vs local: %1 dB").arg(same)));
        if (changesTheImage) {
            QVERIFY2(change < 35.0, "the options did not reach the server");
        }
    }

    // RemoteRenderBackend (what the command uses) served version 1: sampling
    // the server renders anyway goes through; other sampling is refused with a
    // message naming it, the frames after it are not current, and going back
    // to the default makes them current again. Served version 2, it is sent.
    void aVersionOneServerRefusesSamplingCleanly() {
        ServerProcess server("cpu");
        const QString uid = onlySeries(server.port());
        QVERIFY(!uid.isEmpty());
        RemoteServerSettings settings;
        settings.url = QUrl(QString("ws://127.0.0.1:%1/").arg(server.port()));
        settings.token = kToken;
        settings.series = uid;
        RenderDescription d;
        d.width = 64;
        d.height = 64;
        d.transferFunction = loadPreset("ct-bone");

        RemoteRenderBackend old;
        old.setProtocolVersion(1);
        old.setRetrying(false);
        QList<BackendFrame> frames;
        QStringList failures;
        QObject::connect(&old, &RenderBackend::frameReady,
                         [&](const BackendFrame& f) { frames.append(f); });
        QObject::connect(&old, &RenderBackend::frameFailed,
                         [&](const QString& why) { failures.append(why); });
        old.connectTo(settings);
        QVERIFY(QTest::qWaitFor([&] { return old.status() == BackendStatus::Connected; }, 20000));
        QCOMPARE(old.serverVersion(), 1);
        const auto currentFrame = [&] {
            return QTest::qWaitFor([&] { return !frames.isEmpty() && frames.back().current; },
                                   30000);
        };
        old.request(d, {});
        QVERIFY2(currentFrame(), qPrintable(failures.join("\n")));
        QVERIFY(failures.isEmpty());

        RenderDescription cubic = d;
        cubic.sampling.step = 0.25;
        cubic.sampling.interpolation = Interpolation::Cubic;
        cubic.camera.azimuth = 30.0;
        frames.clear();
        old.request(cubic, {});
        QVERIFY(QTest::qWaitFor([&] { return !failures.isEmpty(); }, 10000));
        const QString why = failures.join("\n");
        QVERIFY2(why.contains("version 1") && why.contains("step 0.25") &&
                     why.contains("interp cubic") && !why.contains("precision"),
                 qPrintable(why));
        QVERIFY(QTest::qWaitFor([&] { return !frames.isEmpty(); }, 30000)); // the camera's
        QVERIFY(!frames.back().current);
        QTest::qWait(300);
        QVERIFY(!frames.back().current);
        RenderDescription back = cubic;
        back.sampling = d.sampling;
        old.request(back, {});
        QVERIFY(currentFrame());
        QCOMPARE(failures.size(), 1);

        RemoteRenderBackend now;
        now.setRetrying(false);
        QList<BackendFrame> nowFrames;
        QObject::connect(&now, &RenderBackend::frameReady,
                         [&](const BackendFrame& f) { nowFrames.append(f); });
        QObject::connect(&now, &RenderBackend::frameFailed,
                         [&](const QString& why) { failures.append(why); });
        now.connectTo(settings);
        QVERIFY(QTest::qWaitFor([&] { return now.status() == BackendStatus::Connected; }, 20000));
        QCOMPARE(now.serverVersion(), remote::kProtocolVersion);
        now.request(cubic, {});
        QVERIFY(QTest::qWaitFor([&] { return !nowFrames.isEmpty() && nowFrames.back().current; },
                                30000));
        QCOMPARE(failures.size(), 1);
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
        QVERIFY2(unknown.err.contains("does not have series 1.2.3.4"), qPrintable(unknown.err));
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
