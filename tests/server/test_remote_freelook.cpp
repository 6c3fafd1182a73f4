// Free look on the real lucent-server over loopback, with real CT: a follower's
// own view shows its camera (against a local render of that camera) while the
// other follower keeps the presenter's frames; it follows the presenter's
// transfer function; the per-session limit; snapping back by itself and by the
// presenter's recall gives the presenter's newest frame (>= 50 dB, the same
// bytes); free look ends on a new series, a handover, leaving and the end of the
// session; a follower by invite may look on its own; a busy server's cheaper
// frame is followed by the full still.
#include <QDir>
#include <QJsonArray>
#include <QTest>

#include "FreeLookClients.h"
#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/support/RealData.h"

using namespace lucent;
using namespace lucent::test;
using lucent::remote::FrameHeader;

namespace {

constexpr int kSide = 96;
constexpr char kRealSeries[] = "dcm_qa_ct/Philips_S21570/S2010";
const QStringList kV4 = {"lucent.v4"};

QString realSeriesDir() {
    return QString::fromStdString((kRealData / kRealSeries).string());
}

void saveOnFailure(const ImageRGBA8& image, const QString& name, bool failed) {
    if (failed) {
        QImage(image.pixels.data(), image.width, image.height, QImage::Format_RGBA8888)
            .save(QDir::temp().filePath(name));
        qWarning() << "saved" << QDir::temp().filePath(name);
    }
}

// The presenter's newest frame equals the follower's next frame after `count`
// (the snap back): >= 50 dB, in fact the same bytes.
void verifySnapBack(RemoteTestClient& presenter, RemoteTestClient& follower, qsizetype count,
                    const QString& what) {
    const ReceivedFrame* next = frameAfter(follower, count);
    QVERIFY2(next, qPrintable(what));
    const ReceivedFrame& theirs = presenter.frames.back();
    QCOMPARE(next->header.width, theirs.header.width); // not an own frame, nor a cheaper one
    QCOMPARE(next->header.height, theirs.header.height);
    const double db = psnr(theirs.decoded(), next->decoded());
    qInfo("snap back (%s): %.1f dB against the presenter's last frame", qPrintable(what), db);
    saveOnFailure(next->decoded(), "freelook_snapback_" + what + ".png", !(db >= 50.0));
    QVERIFY2(db >= 50.0, qPrintable(QString("%1: %2 dB").arg(what).arg(db)));
    QCOMPARE(next->image, theirs.image);
}

} // namespace

class TestRemoteFreeLook : public QObject {
    Q_OBJECT

private slots:
    void aFollowerLooksOnItsOwnAndSnapsBack() {
        REQUIRE_DATA(kRealSeries);
        ServerProcess server("cpu", realSeriesDir(), {"--max-free-look", "1"});
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port(), kV4);
        const QString session = presentOnlySeries(presenter, kSide);
        QVERIFY(!session.isEmpty());
        RemoteTestClient looker(server.port(), kV4), watcher(server.port(), kV4);
        QVERIFY(join(looker, session));
        QVERIFY(join(watcher, session));

        // Free look on; the presenter is told how many look on their own.
        qsizetype presenterFrom = presenter.texts.size();
        QVERIFY(startFreeLook(looker) >= 0);
        const QJsonObject state = presenter.waitForText("free-look-state", 20000, presenterFrom);
        QCOMPARE(state["looking"].toInt(), 1);
        QCOMPARE(state["limit"].toInt(), 1);

        // The limit: the second is refused, not fatal.
        qsizetype from = watcher.texts.size();
        watcher.send({{"type", "free-look"}, {"state", "start"}});
        const QJsonObject refused = watcher.waitForText("error", 20000, from);
        QCOMPARE(refused["code"].toString(), "free-look-limit");
        QVERIFY(!refused["fatal"].toBool());

        // Its own camera, rendered for it alone.
        const ReceivedFrame* own =
            ownFrame(looker, {{"type", "camera"}, {"azimuth", 70}, {"elevation", 20}});
        QVERIFY(own);
        QCOMPARE(own->header.format, "png");
        const Volume volume = loadPath(realSeriesDir().toStdString());
        CpuRayCaster cpu(volume);
        const ImageRGBA8 local =
            cpu.render(referenceDescription(volume, Camera{70, 20, 1.0}, kSide)).image;
        const double ownDb = psnr(local, own->decoded());
        qInfo("free look frame: %.1f dB against a local render of its camera", ownDb);
        saveOnFailure(own->decoded(), "freelook_own.png", !(ownDb >= 40.0));
        QVERIFY2(ownDb >= 40.0, qPrintable(QString("%1 dB").arg(ownDb)));
        QVERIFY(psnr(presenter.frames.back().decoded(), own->decoded()) <
                30.0); // not the session's

        // The presenter turns: the watcher gets the same bytes, the looker none of them.
        const qsizetype lookerFrames = looker.frames.size();
        presenter.change({{"type", "camera"}, {"azimuth", 20}});
        const ReceivedFrame* mine = presenter.waitForCurrentFrame();
        QVERIFY(mine);
        watcher.seq = presenter.seq;
        const ReceivedFrame* theirs = watcher.waitForCurrentFrame();
        QVERIFY(theirs);
        QCOMPARE(theirs->image, mine->image);
        for (qsizetype n = lookerFrames; n < looker.frames.size(); ++n) {
            QVERIFY(looker.frames[n].image != mine->image);
        }

        // The presenter's transfer function reaches the looker's own view, its camera kept.
        const qsizetype beforeTf = looker.frames.size();
        presenter.change({{"type", "tf"}, {"preset", "ct-soft-tissue"}});
        QVERIFY(presenter.waitForCurrentFrame());
        ++looker.seq; // the followed message counts in its own view
        const ReceivedFrame* soft = settledFrame(looker);
        QVERIFY(soft && looker.frames.size() > beforeTf);
        RenderDescription softTissue = referenceDescription(volume, Camera{70, 20, 1.0}, kSide);
        softTissue.transferFunction = loadPreset("ct-soft-tissue");
        const double softDb = psnr(cpu.render(softTissue).image, soft->decoded());
        QVERIFY2(softDb >= 40.0, qPrintable(QString("%1 dB").arg(softDb)));

        // Snap back by itself: the next frame is the presenter's newest.
        from = looker.texts.size();
        qsizetype count = looker.frames.size();
        presenterFrom = presenter.texts.size();
        looker.send({{"type", "free-look"}, {"state", "end"}});
        QCOMPARE(looker.waitForText("free-look-ended", 20000, from)["reason"].toString(), "own");
        verifySnapBack(presenter, looker, count, "own");
        QCOMPARE(presenter.waitForText("free-look-state", 20000, presenterFrom)["looking"].toInt(),
                 0);
        // Back on the session: its view messages are the presenter's again.
        from = looker.texts.size();
        looker.send({{"type", "camera"}, {"azimuth", 5}});
        QCOMPARE(looker.waitForText("error", 20000, from)["code"].toString(), "not-presenter");

        // The place is free: the watcher looks; the presenter calls everyone back.
        qsizetype watcherFrom = watcher.texts.size();
        QVERIFY(startFreeLook(watcher) >= 0);
        // It starts from the session's camera, which the presenter turned to 20 degrees.
        const QJsonObject camera =
            watcher.waitForText("free-look-started", 20000, watcherFrom)["camera"].toObject();
        QCOMPARE(camera["azimuth"].toDouble(), 20.0);
        QCOMPARE(camera["zoom"].toDouble(), 1.0);
        QVERIFY(ownFrame(watcher, {{"type", "camera"}, {"azimuth", -60}, {"zoom", 1.5}}));
        from = watcher.texts.size();
        count = watcher.frames.size();
        presenter.send({{"type", "free-look-recall"}});
        QCOMPARE(watcher.waitForText("free-look-ended", 20000, from)["reason"].toString(),
                 "recalled");
        verifySnapBack(presenter, watcher, count, "recalled");
        // Followers follow again: the next turn reaches both.
        presenter.change({{"type", "camera"}, {"azimuth", 45}});
        QVERIFY(presenter.waitForCurrentFrame());
        QVERIFY(QTest::qWaitFor(
            [&] { return watcher.frames.back().image == presenter.frames.back().image; }, 60000));
        // A follower may not recall, nor the presenter look on its own.
        from = looker.texts.size();
        looker.send({{"type", "free-look-recall"}});
        QCOMPARE(looker.waitForText("error", 20000, from)["code"].toString(), "not-presenter");
        from = presenter.texts.size();
        presenter.send({{"type", "free-look"}, {"state", "start"}});
        const QJsonObject notFollower = presenter.waitForText("error", 20000, from);
        QCOMPARE(notFollower["code"].toString(), "bad-request");
        QVERIFY(notFollower["message"].toString().startsWith("free-look"));
        QVERIFY(!presenter.disconnected && !looker.disconnected && !watcher.disconnected);
    }

    void freeLookEndsWithTheSeriesAHandoverLeavingAndTheSession() {
        REQUIRE_DATA(kRealSeries);
        ServerProcess server("cpu", realSeriesDir());
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port(), kV4);
        const QString session = presentOnlySeries(presenter, kSide);
        QVERIFY(!session.isEmpty());
        RemoteTestClient a(server.port(), kV4), b(server.port(), kV4);
        QVERIFY(join(a, session));
        QVERIFY(join(b, session));

        // The presenter opens a series again: free look ends, the new view follows.
        QVERIFY(startFreeLook(a) >= 0);
        qsizetype from = a.texts.size();
        const qsizetype bOpened = b.texts.size();
        presenter.send({{"type", "list"}});
        const QString uid = presenter.waitForText("series")["series"][0]["uid"].toString();
        presenter.send({{"type", "open"}, {"series", uid}});
        QCOMPARE(a.waitForText("free-look-ended", 20000, from)["reason"].toString(), "series");
        QVERIFY(!a.waitForText("opened", 20000, from).isEmpty());

        // Handed control while looking: it ends, "presenting".
        QVERIFY(!b.waitForText("opened", 20000, bOpened).isEmpty());
        QVERIFY(startFreeLook(b) >= 0);
        from = b.texts.size();
        const quint64 bId = quint64(b.waitForText("session-state")["you"].toInteger());
        presenter.send({{"type", "session-handover"}, {"to", qint64(bId)}});
        QCOMPARE(b.waitForText("free-look-ended", 20000, from)["reason"].toString(), "presenting");
        QCOMPARE(b.waitForText("session-state", 20000, from)["role"].toString(), "presenter");

        // Leaving while looking: "left", then session-left.
        QVERIFY(startFreeLook(a) >= 0);
        from = a.texts.size();
        a.send({{"type", "session-leave"}});
        QCOMPARE(a.waitForText("free-look-ended", 20000, from)["reason"].toString(), "left");
        QVERIFY(!a.waitForText("session-left", 20000, from).isEmpty());

        // A follower by invite may look on its own; the session's end ends it.
        const qsizetype bFrom = b.texts.size();
        b.send({{"type", "invite-create"}});
        const QString code = b.waitForText("invite-created", 20000, bFrom)["code"].toString();
        QVERIFY(!code.isEmpty());
        RemoteTestClient student(server.port(), {"lucent.v4", "lucent.invite." + code});
        QVERIFY(student.waitConnected());
        QVERIFY(!student.waitForText("opened").isEmpty());
        QVERIFY(startFreeLook(student) >= 0);
        QVERIFY(ownFrame(student, {{"type", "camera"}, {"azimuth", 120}}));
        from = student.texts.size();
        presenter.send({{"type", "session-leave"}});
        b.send({{"type", "session-leave"}});
        QCOMPARE(student.waitForText("free-look-ended", 20000, from)["reason"].toString(),
                 "session-ended");
        QVERIFY(!student.waitForText("session-left", 20000, from).isEmpty());
        QVERIFY(student.waitDisconnected());
    }

    // Ten followers look on their own among forty while the presenter turns the
    // view: every other follower ends on the presenter's newest frame (the same
    // bytes), and every looker on its own view's still.
    void tenLookAmongForty() {
        ServerProcess server; // the synthetic CT: many renders, quickly
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port(), kV4);
        const QString session = presentOnlySeries(presenter, kSide);
        QVERIFY(!session.isEmpty());
        std::vector<std::unique_ptr<RemoteTestClient>> followers;
        for (int n = 0; n < 40; ++n) {
            followers.push_back(std::make_unique<RemoteTestClient>(server.port(), kV4));
            QVERIFY(join(*followers.back(), session));
        }
        for (int n = 0; n < 10; ++n) {
            QVERIFY(startFreeLook(*followers[n]) >= 0);
        }
        QElapsedTimer clock;
        clock.start();
        for (int turn = 1; turn <= 8; ++turn) {
            presenter.change({{"type", "camera"}, {"azimuth", 10.0 * turn}});
            for (int n = 0; n < 10; ++n) {
                followers[n]->change({{"type", "camera"}, {"azimuth", -15.0 * turn - n}});
            }
            QVERIFY(presenter.waitForCurrentFrame());
        }
        const double presenterMs = double(clock.elapsed()) / 8.0;
        for (int n = 0; n < 10; ++n) {
            QVERIFY2(settledFrame(*followers[n]), qPrintable(QString("looker %1").arg(n)));
        }
        const double allMs = double(clock.elapsed()) / 8.0;
        qsizetype fewest = presenter.frames.size();
        for (int n = 10; n < 40; ++n) {
            RemoteTestClient& watcher = *followers[n];
            QVERIFY(QTest::qWaitFor(
                [&] {
                    return !watcher.frames.isEmpty() &&
                           watcher.frames.back().image == presenter.frames.back().image;
                },
                30000));
            fewest = std::min(fewest, watcher.frames.size());
        }
        qInfo("10 lookers among 40 followers: %.0f ms per presenter turn, %.0f ms until every "
              "looker's still too; the followers got at least %lld of the presenter's %lld frames",
              presenterMs, allMs, qlonglong(fewest), qlonglong(presenter.frames.size()));
    }

    // A version 3 follower knows no free look: the type is unknown there (fatal).
    void versionThreeKnowsNoFreeLook() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient old(server.port(), {"lucent.v3"});
        QVERIFY(old.waitConnected() && old.authenticate());
        old.send({{"type", "free-look"}, {"state", "start"}});
        const QJsonObject error = old.waitForText("error");
        QCOMPARE(error["code"].toString(), "unknown-type");
        QVERIFY(error["message"].toString().contains("version 4"));
        QVERIFY(old.waitDisconnected());
        RemoteTestClient alone(server.port(), kV4);
        QVERIFY(alone.waitConnected() && alone.authenticate());
        alone.send({{"type", "free-look"}, {"state", "start"}});
        QCOMPARE(alone.waitForText("error")["code"].toString(), "out-of-order"); // no session
    }

    // A looker's still asked for while the presenter's frame is being rendered
    // comes cheaper (the fixed interactive frame: the server was busy); the
    // full still follows, and it equals a local render of the looker's camera.
    void aBusyServerSendsTheFullStillAfterwards() {
        REQUIRE_DATA(kRealSeries);
        ServerProcess server("cpu", realSeriesDir());
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port(), kV4);
        const QString session = presentOnlySeries(presenter, kSide);
        QVERIFY(!session.isEmpty());
        RemoteTestClient looker(server.port(), kV4);
        QVERIFY(join(looker, session));
        presenter.change({{"type", "size"}, {"width", 1024}, {"height", 1024}}); // slow frames
        QVERIFY(presenter.waitForCurrentFrame());
        QVERIFY(startFreeLook(looker) >= 0);
        QVERIFY(ownFrame(looker, {{"type", "size"}, {"width", kSide}, {"height", kSide}}));
        // The looker turns while the presenter's frame is being rendered.
        presenter.change({{"type", "camera"}, {"azimuth", 30}});
        QTest::qWait(30);
        looker.change({{"type", "camera"}, {"azimuth", -40}});
        QVERIFY(settledFrame(looker));
        QList<FrameHeader> mine;
        for (const ReceivedFrame& f : std::as_const(looker.frames)) {
            if (f.header.seq == looker.seq) {
                mine.append(f.header);
            }
        }
        QCOMPARE(mine.size(), 2); // the cheaper frame, then the still
        QCOMPARE(mine[0].format, "jpeg");
        QCOMPARE(mine[0].scale, 0.5);
        QCOMPARE(mine[0].width, kSide / 2);
        QCOMPARE(mine[1].format, "png");
        QCOMPARE(mine[1].width, kSide);
        qInfo("busy: the looker's cheaper frame %.1f ms, its still %.1f ms",
              mine[0].renderMs + mine[0].encodeMs, mine[1].renderMs + mine[1].encodeMs);
        const Volume volume = loadPath(realSeriesDir().toStdString());
        CpuRayCaster cpu(volume);
        const double db =
            psnr(cpu.render(referenceDescription(volume, Camera{-40, 0, 1.0}, kSide)).image,
                 looker.frames.back().decoded());
        QVERIFY2(db >= 40.0, qPrintable(QString("%1 dB").arg(db)));
        QVERIFY(presenter.waitForCurrentFrame());
    }
};

QTEST_GUILESS_MAIN(TestRemoteFreeLook)
#include "test_remote_freelook.moc"
