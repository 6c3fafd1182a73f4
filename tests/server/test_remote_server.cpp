// The real lucent-server on loopback: authentication, list/open/render against
// the local CPU reference, JPEG while interacting, malformed and oversized
// messages, coalescing of a camera burst, the sampling message of version 2 and
// version 1 peers.
#include <QJsonArray>
#include <QProcess>
#include <QTest>

#include <sys/stat.h>

#include "RemoteTestFixture.h"
#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/quality/InteractiveQuality.h"
#include "core/raycast/CpuRayCaster.h"
#include "protocol/AdaptiveQuality.h"

using namespace lucent;
using namespace lucent::test;
using lucent::remote::FrameHeader;

namespace {

constexpr int kSide = 128;

// The description the server should render after openView() and `camera`.
RenderDescription localDescription(const Volume& volume, const Camera& camera) {
    return referenceDescription(volume, camera, kSide);
}

// Authenticates, opens the only series, sets size and preset.
QString openView(RemoteTestClient& client) {
    if (!client.waitConnected() || !client.authenticate()) {
        return {};
    }
    return openOnlySeries(client, kSide);
}

void saveOnFailure(const ImageRGBA8& image, const QString& name, bool failed) {
    if (failed) {
        QImage(image.pixels.data(), image.width, image.height, QImage::Format_RGBA8888)
            .save(QDir::temp().filePath(name));
        qWarning() << "saved" << QDir::temp().filePath(name);
    }
}

} // namespace

class TestRemoteServer : public QObject {
    Q_OBJECT

private slots:
    void refusesMissingAndWrongTokens() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient noToken(server.port());
        QVERIFY(noToken.waitConnected());
        noToken.send({{"type", "list"}});
        const QJsonObject e1 = noToken.waitForText("error");
        QCOMPARE(e1["code"].toString(), "auth-required");
        QVERIFY(e1["message"].toString().contains("auth"));
        QVERIFY(e1["fatal"].toBool());
        QVERIFY(noToken.waitDisconnected());

        RemoteTestClient wrong(server.port());
        QVERIFY(wrong.waitConnected());
        wrong.send({{"type", "auth"}, {"token", "not-the-token"}});
        const QJsonObject e2 = wrong.waitForText("error");
        QCOMPARE(e2["code"].toString(), "auth-failed");
        QVERIFY(e2["message"].toString().contains("token"));
        QVERIFY(wrong.waitDisconnected());
        QVERIFY(wrong.frames.isEmpty());
        QVERIFY2(!server.log().contains("not-the-token"), "a token reached the log");
    }

    // A token file that its group or others may read has leaked: the server
    // does not start on it, and says which file and which mode; at 0600 the
    // same file serves.
    void refusesATokenFileOthersCanRead_data() {
        QTest::addColumn<int>("mode");
        QTest::addColumn<QString>("who");
        QTest::newRow("0644") << 0644 << "its group and others";
        QTest::newRow("0640") << 0640 << "its group";
        QTest::newRow("0604") << 0604 << "others";
        QTest::newRow("0660") << 0660 << "its group";
    }
    void refusesATokenFileOthersCanRead() {
        QFETCH(int, mode);
        QFETCH(QString, who);
        const QTemporaryDir dir;
        const QString tokens = dir.filePath("tokens");
        QVERIFY(writeTokenFile(tokens, QByteArray(kToken) + "\n"));
        QVERIFY(::chmod(QFile::encodeName(tokens).constData(), mode_t(mode)) == 0);
        const QString server = QString(LUCENT_BIN_DIR) + "/lucent-server";
        const QStringList arguments = {"--store", dir.filePath("store"), "--token-file", tokens,
                                       "--check"};
        QProcess process;
        process.start(server, arguments);
        QVERIFY(process.waitForFinished(30000));
        const QString err = QString::fromUtf8(process.readAllStandardError());
        QCOMPARE(process.exitCode(), 3);
        const QString modeText = QString::number(mode, 8).rightJustified(4, '0');
        QVERIFY2(err.contains("token file " + tokens + " has mode " + modeText), qPrintable(err));
        QVERIFY2(err.contains(who + " may use it"), qPrintable(err));
        QVERIFY2(err.contains("chmod 600 " + tokens), qPrintable(err));

        QVERIFY(::chmod(QFile::encodeName(tokens).constData(), 0600) == 0);
        process.start(server, arguments);
        QVERIFY(process.waitForFinished(30000));
        QVERIFY2(process.exitCode() == 0, qPrintable(process.readAllStandardError()));
        QVERIFY(QString::fromUtf8(process.readAllStandardOutput()).contains("0 series"));
    }

    void listHoldsNoPatientData() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient client(server.port());
        QVERIFY(client.waitConnected() && client.authenticate());
        client.send({{"type", "list"}});
        const QJsonObject entry = client.waitForText("series")["series"].toArray()[0].toObject();
        QCOMPARE(entry["dims"].toArray(), QJsonArray({48, 40, 36}));
        QCOMPARE(entry["description"].toString(), "synthetic");
        QVERIFY(!entry.contains("patientName") && !entry.contains("patient_name"));
        QVERIFY(!server.log().contains(kToken));
    }

    void stillFrameEqualsLocalRender_data() {
        QTest::addColumn<QString>("backend");
        QTest::newRow("cpu") << "cpu";
        QTest::newRow("gl") << "gl"; // the CPU where EGL gives no GL 4.3 context
    }
    void stillFrameEqualsLocalRender() {
        QFETCH(QString, backend);
        ServerProcess server(backend);
        QVERIFY(server.port());
        RemoteTestClient client(server.port());
        QVERIFY(!openView(client).isEmpty());
        client.change({{"type", "camera"}, {"azimuth", 35}, {"elevation", 15}, {"zoom", 1.3}});
        client.change({{"type", "render"}});
        const ReceivedFrame* frame = client.waitForCurrentFrame();
        QVERIFY(frame);
        QCOMPARE(frame->header.format, "png");
        QCOMPARE(frame->header.width, kSide);

        const Volume volume = loadPath(server.volumeFile().toStdString());
        CpuRayCaster cpu(volume);
        const ImageRGBA8 local = cpu.render(localDescription(volume, {35, 15, 1.3})).image;
        const ImageRGBA8 remote = frame->decoded();
        const double db = psnr(local, remote);
        qInfo("still %s: PSNR %.1f dB, render %.1f ms, encode %.1f ms", qPrintable(backend), db,
              frame->header.renderMs, frame->header.encodeMs);
        saveOnFailure(remote, "remote_still_" + backend + ".png", !(db >= 40.0));
        QVERIFY2(db >= 40.0, qPrintable(QString("PSNR %1 dB").arg(db)));
        // Not a blank image: the ball and the block show.
        QVERIFY(psnr(local, ImageRGBA8::filled(kSide, kSide, 0)) < 30.0);
    }

    void interactiveFrameIsJpegOfTheInteractiveDescription() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient client(server.port());
        QVERIFY(!openView(client).isEmpty());
        client.change({{"type", "quality"}, {"quality", "interactive"}});
        client.change({{"type", "camera"}, {"azimuth", -50}});
        const ReceivedFrame* frame = client.waitForCurrentFrame();
        QVERIFY(frame);
        QCOMPARE(frame->header.format, "jpeg");
        QVERIFY(frame->image.startsWith("\xff\xd8"));

        const Volume volume = loadPath(server.volumeFile().toStdString());
        CpuRayCaster cpu(volume);
        const RenderDescription d =
            interactiveDescription(localDescription(volume, {-50, 0, 1, 30}));
        const ImageRGBA8 local = cpu.render(d).image;
        const ImageRGBA8 remote = frame->decoded();
        QCOMPARE(remote.width, d.width);
        const double db = psnr(local, remote);
        qInfo("interactive: PSNR %.1f dB, %lld JPEG bytes", db, qlonglong(frame->image.size()));
        saveOnFailure(remote, "remote_interactive.png", !(db >= 32.0));
        QVERIFY2(db >= 32.0, qPrintable(QString("PSNR %1 dB").arg(db)));
    }

    void interactionAdaptsJpegAndEndsWithALosslessStill() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient client(server.port());
        QVERIFY(!openView(client).isEmpty());
        QVERIFY(client.waitForCurrentFrame());
        client.change({{"type", "interaction"}, {"state", "start"}});
        for (int n = 1; n <= 12; ++n) {
            client.change({{"type", "camera"}, {"azimuth", 10.0 * n}});
            QVERIFY(client.waitForCurrentFrame()); // a drag that waits for each frame
            const FrameHeader& h = client.frames.back().header;
            QCOMPARE(h.format, "jpeg");
            QVERIFY(h.quality == remote::Quality::Interactive);
            QVERIFY2(h.jpegQuality >= 60 && h.jpegQuality <= 85,
                     qPrintable(QString::number(h.jpegQuality)));
            bool onLadder = false;
            for (const auto& setting : remote::kInteractiveLadder) {
                onLadder |= setting.scale == h.scale && setting.jpegQuality == h.jpegQuality;
            }
            QVERIFY2(onLadder, qPrintable(QString("scale %1").arg(h.scale)));
            QCOMPARE(h.width, std::max(1, int(kSide * h.scale)));
            QVERIFY(client.frames.back().image.startsWith("\xff\xd8"));
        }
        // A small volume renders fast: the server chose better than its start
        // (half size, quality 60).
        const FrameHeader& last = client.frames.back().header;
        qInfo("after 12 frames: scale %.2f, JPEG quality %d, render %.1f ms, encode %.1f ms",
              last.scale, last.jpegQuality, last.renderMs, last.encodeMs);
        QVERIFY(last.scale > 0.5 || last.jpegQuality > 60 || last.renderMs + last.encodeMs > 22);

        client.change({{"type", "interaction"}, {"state", "end"}});
        const ReceivedFrame* still = client.waitForCurrentFrame();
        QVERIFY(still);
        QCOMPARE(still->header.format, "png");
        QVERIFY(still->header.quality == remote::Quality::Still);
        QCOMPARE(still->header.width, kSide);
        QCOMPARE(still->header.scale, 1.0);
        const Volume volume = loadPath(server.volumeFile().toStdString());
        CpuRayCaster cpu(volume);
        const ImageRGBA8 local = cpu.render(localDescription(volume, {120, 0, 1, 30})).image;
        const double db = psnr(local, still->decoded());
        QVERIFY2(db >= 40.0, qPrintable(QString("PSNR %1 dB").arg(db)));

        // The `quality` message still works as before.
        client.change({{"type", "quality"}, {"quality", "interactive"}});
        const ReceivedFrame* fixed = client.waitForCurrentFrame();
        QVERIFY(fixed);
        QCOMPARE(fixed->header.format, "jpeg");
        QCOMPARE(fixed->header.scale, 0.5);
        QCOMPARE(fixed->header.jpegQuality, 85);
    }

    void tokenInTheSubprotocol() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient client(server.port(), {"lucent.v1", QString("lucent.token.") + kToken});
        QVERIFY(client.waitConnected());
        QCOMPARE(client.subprotocol(), "lucent.v1");
        QCOMPARE(client.waitForText("hello")["version"].toInt(), 1); // no auth message sent
        client.send({{"type", "list"}});
        QCOMPARE(client.waitForText("series")["series"].toArray().size(), 1);
        client.send({{"type", "auth"}, {"token", kToken}});
        QCOMPARE(client.waitForText("error")["code"].toString(), "out-of-order");

        RemoteTestClient wrong(server.port(), {"lucent.v1", "lucent.token.not-the-token"});
        const QJsonObject error = wrong.waitForText("error");
        QCOMPARE(error["code"].toString(), "auth-failed");
        QVERIFY(error["message"].toString().contains("token"));
        QVERIFY(wrong.waitDisconnected());
        QVERIFY(wrong.waitForText("hello", 200).isEmpty());

        // Without a token subprotocol the auth message is still required.
        RemoteTestClient plain(server.port(), {"lucent.v1"});
        QVERIFY(plain.waitConnected());
        QCOMPARE(plain.subprotocol(), "lucent.v1");
        plain.send({{"type", "list"}});
        QCOMPARE(plain.waitForText("error")["code"].toString(), "auth-required");
        QVERIFY(!server.log().contains("not-the-token"));
        QVERIFY(!server.log().contains(kToken));
    }

    void staleDeidentifiedCopiesGoAtStart() {
        QTemporaryDir store;
        QVERIFY(QDir(store.path()).mkpath("deidentified/1.2.3/sub"));
        QVERIFY(QDir(store.path()).mkpath("deidentified/.partial-4.5.6-7"));
        QFile stale(store.filePath("deidentified/1.2.3/00001.dcm"));
        QVERIFY(stale.open(QIODevice::WriteOnly) && stale.write("x") == 1);
        stale.close();
        ServerProcess server("cpu", {}, {"--store", store.path()}); // the last --store counts
        QVERIFY(server.port());
        QVERIFY(!QFileInfo::exists(store.filePath("deidentified")));
        QVERIFY(QFileInfo(store.path()).isDir());
    }

    void badMessagesCloseOnlyTheirConnection() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient good(server.port());
        QVERIFY(!openView(good).isEmpty());
        QVERIFY(good.waitForCurrentFrame());

        RemoteTestClient malformed(server.port());
        QVERIFY(malformed.waitConnected() && malformed.authenticate());
        malformed.sendRaw("{\"type\": \"camera\", azimuth: ");
        QCOMPARE(malformed.waitForText("error")["code"].toString(), "malformed");
        QVERIFY(malformed.waitDisconnected());

        RemoteTestClient oversized(server.port());
        QVERIFY(oversized.waitConnected() && oversized.authenticate());
        oversized.sendRaw("{\"type\":\"list\",\"pad\":\"" + QString(100 * 1024, 'x') + "\"}");
        QCOMPARE(oversized.waitForText("error")["code"].toString(), "too-large");
        QVERIFY(oversized.waitDisconnected());

        RemoteTestClient outOfOrder(server.port());
        QVERIFY(outOfOrder.waitConnected() && outOfOrder.authenticate());
        outOfOrder.send({{"type", "render"}});
        QCOMPARE(outOfOrder.waitForText("error")["code"].toString(), "out-of-order");
        QVERIFY(outOfOrder.waitDisconnected());

        // The first client is still served.
        good.change({{"type", "camera"}, {"azimuth", 90}});
        QVERIFY(good.waitForCurrentFrame());
        QVERIFY(!good.disconnected);
    }

    void cameraBurstCoalescesToTheLastCamera() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient client(server.port());
        QVERIFY(!openView(client).isEmpty());
        QVERIFY(client.waitForCurrentFrame());
        const qsizetype before = client.frames.size();
        for (int n = 1; n <= 20; ++n) {
            client.change({{"type", "camera"}, {"azimuth", 7.0 * n}, {"elevation", -n}});
        }
        const ReceivedFrame* last = client.waitForCurrentFrame();
        QVERIFY(last);
        QTest::qWait(300); // nothing stale may follow
        const qsizetype burstFrames = client.frames.size() - before;
        qInfo("20 camera messages gave %lld frame(s)", qlonglong(burstFrames));
        QCOMPARE(client.frames.back().header.seq, client.seq);
        QVERIFY2(burstFrames <= 5, qPrintable(QString("%1 frames").arg(burstFrames)));

        const Volume volume = loadPath(server.volumeFile().toStdString());
        CpuRayCaster cpu(volume);
        const ImageRGBA8 local = cpu.render(localDescription(volume, {140, -20, 1, 30})).image;
        const double db = psnr(local, client.frames.back().decoded());
        QVERIFY2(db >= 40.0, qPrintable(QString("PSNR %1 dB").arg(db)));
    }

    // Version 2's sampling message: the still equals the local render of that
    // sampling, refused settings name their key and cost no frame, `open` resets
    // the sampling. A version 1 peer (lucent.v1 offered, or no version) is served
    // version 1, and its sampling message is an unknown type (fatal), as a
    // version 1 server answers it; other connections go on.
    void samplingIsVersionTwo() {
        ServerProcess server;
        QVERIFY(server.port());
        const Volume volume = loadPath(server.volumeFile().toStdString());
        CpuRayCaster cpu(volume);
        RemoteTestClient v2(server.port(), {"lucent.v2"});
        const QString uid = openView(v2);
        QVERIFY(!uid.isEmpty());
        QCOMPARE(v2.subprotocol(), "lucent.v2");
        QCOMPARE(v2.waitForText("hello")["version"].toInt(), 2);
        const ReceivedFrame* first = v2.waitForCurrentFrame();
        QVERIFY(first);
        const ImageRGBA8 plain = first->decoded();

        const std::pair<const char*, QJsonObject> refused[] = {
            {"step", {{"type", "sampling"}, {"step", 0.001}}},
            {"early_termination", {{"type", "sampling"}, {"early_termination", 1.5}}},
            {"interp", {{"type", "sampling"}, {"interp", "sinc"}}},
            {"leaping", {{"type", "sampling"}, {"leaping", "no"}}},
            {"gradient", {{"type", "sampling"}, {"gradient", true}}},
        };
        for (const auto& [key, message] : refused) {
            const qsizetype from = v2.texts.size();
            v2.send(message);
            const QJsonObject error = v2.waitForText("error", 20000, from);
            QCOMPARE(error["code"].toString(), "bad-request");
            QVERIFY(!error["fatal"].toBool());
            QVERIFY2(error["message"].toString().contains(QString("'") + key + "'"),
                     qPrintable(error["message"].toString()));
        }
        v2.change({{"type", "sampling"}, {"step", 2.0}, {"interp", "nearest"}});
        const ReceivedFrame* coarse = v2.waitForCurrentFrame();
        QVERIFY2(coarse, qPrintable(v2.allText()));
        RenderDescription d = localDescription(volume, {});
        d.sampling.step = 2.0;
        d.sampling.interpolation = Interpolation::Nearest;
        const ImageRGBA8 local = cpu.render(d).image;
        const double db = psnr(local, coarse->decoded());
        const double change = psnr(plain, coarse->decoded());
        qInfo("sampling: remote vs local %.1f dB; coarse vs default %.1f dB", db, change);
        QVERIFY2(db >= 40.0, qPrintable(QString("PSNR %1 dB").arg(db)));
        QVERIFY2(change < 35.0, "the sampling did not change the image");
        // `open` resets the sampling to the server's default.
        const qsizetype from = v2.texts.size();
        v2.change({{"type", "open"}, {"series", uid}});
        QVERIFY(!v2.waitForText("opened", 20000, from).isEmpty());
        v2.change({{"type", "tf"}, {"preset", "ct-bone"}});
        const ReceivedFrame* reopened = v2.waitForCurrentFrame();
        QVERIFY(reopened);
        QVERIFY(psnr(plain, reopened->decoded()) >= 40.0);

        for (const QStringList& offered : {QStringList{"lucent.v1"}, QStringList{}}) {
            RemoteTestClient v1(server.port(), offered);
            QVERIFY(!openView(v1).isEmpty());
            QCOMPARE(v1.waitForText("hello")["version"].toInt(), 1);
            QVERIFY(v1.waitForCurrentFrame()); // version 1's view messages work
            v1.send({{"type", "sampling"}, {"step", 0.25}});
            const QJsonObject error = v1.waitForText("error");
            QCOMPARE(error["code"].toString(), "unknown-type");
            QVERIFY(error["fatal"].toBool());
            QVERIFY2(error["message"].toString().contains("version 1"),
                     qPrintable(error["message"].toString()));
            QVERIFY(v1.waitDisconnected());
        }
        v2.change({{"type", "camera"}, {"azimuth", 20}});
        QVERIFY(v2.waitForCurrentFrame());
        QVERIFY(!v2.disconnected);
    }

    // Pan and distance in the camera message: absent fields keep their value,
    // `open` resets them, and each still equals the local render.
    void panAndDistanceEqualTheLocalRender() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient client(server.port());
        const QString uid = openView(client);
        QVERIFY(!uid.isEmpty());
        const Volume volume = loadPath(server.volumeFile().toStdString());
        CpuRayCaster cpu(volume);
        const auto check = [&](const Camera& camera, const char* what) {
            const ReceivedFrame* frame = client.waitForCurrentFrame();
            QVERIFY2(frame, what);
            QCOMPARE(frame->header.format, "png");
            const ImageRGBA8 local = cpu.render(localDescription(volume, camera)).image;
            const double db = psnr(local, frame->decoded());
            qInfo("%s: PSNR %.1f dB", what, db);
            saveOnFailure(frame->decoded(), QString("remote_pan_%1.png").arg(what), !(db >= 40.0));
            QVERIFY2(db >= 40.0, qPrintable(QString("%1: PSNR %2 dB").arg(what).arg(db)));
        };
        client.change({{"type", "camera"},
                       {"azimuth", 25},
                       {"zoom", 1.5},
                       {"distance", 90},
                       {"pan_right", 8},
                       {"pan_up", -5}});
        check({25, 0, 1.5, 30, 90, 8, -5}, "panned");
        client.change({{"type", "camera"}, {"elevation", 12}});
        check({25, 12, 1.5, 30, 90, 8, -5}, "kept");
        client.change({{"type", "camera"}, {"distance", 0}, {"pan_up", 3}});
        check({25, 12, 1.5, 30, 0, 8, 3}, "fit");
        const qsizetype from = client.texts.size();
        client.change({{"type", "open"}, {"series", uid}});
        QVERIFY(!client.waitForText("opened", 20000, from).isEmpty());
        client.change({{"type", "tf"}, {"preset", "ct-bone"}});
        check({0, 0, 1, 30, 0, 0, 0}, "reopened");
        client.send({{"type", "camera"}, {"pan_right", 1e9}});
        const QJsonObject error = client.waitForText("error", 20000, from);
        QVERIFY2(error["message"].toString().contains("pan_right"), qPrintable(client.allText()));
        QVERIFY(!error["fatal"].toBool());
    }
};

QTEST_GUILESS_MAIN(TestRemoteServer)
#include "test_remote_server.moc"
