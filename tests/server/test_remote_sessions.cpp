// Teaching sessions on the real lucent-server over loopback: the presenter
// controls the view, followers receive the same frame bytes (50 of them
// too), control is handed over and passes on when the presenter goes, killed
// clients free their places and sessions, bad session messages close only
// their own connection, a real DICOM series reaches followers de-identified,
// and the presenter's sampling is the session's.
#include <QJsonArray>
#include <QProcess>
#include <QTest>

#include <memory>

#include <signal.h>

#include "RemoteTestFixture.h"
#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSide = 96;

// Authenticates and answers the uid of the server's first series.
QString firstSeries(RemoteTestClient& client) {
    if (!client.waitConnected() || !client.authenticate()) {
        return {};
    }
    client.send({{"type", "list"}});
    const QJsonArray series = client.waitForText("series")["series"].toArray();
    return series.isEmpty() ? QString() : series[0].toObject()["uid"].toString();
}

// The newest text message of this type after index `from` (waits for one).
QJsonObject nextText(RemoteTestClient& client, const QString& type, qsizetype from,
                     int timeoutMs = 20000) {
    return client.waitForText(type, timeoutMs, from);
}

// Waits until the client holds a frame of at least this seq; null if none came.
const ReceivedFrame* frameOf(RemoteTestClient& client, std::uint64_t seq, int timeoutMs = 60000) {
    (void)QTest::qWaitFor(
        [&] { return !client.frames.isEmpty() && client.frames.back().header.seq >= seq; },
        timeoutMs);
    return !client.frames.isEmpty() && client.frames.back().header.seq >= seq
               ? &client.frames.back()
               : nullptr;
}

// Creates a session with the presenter's first series open at kSide; the id.
QString startSession(RemoteTestClient& presenter, std::uint64_t* seq) {
    const QString uid = firstSeries(presenter);
    if (uid.isEmpty()) {
        return {};
    }
    presenter.send({{"type", "session-create"}});
    const QString id = presenter.waitForText("session-created")["session"].toString();
    presenter.send({{"type", "open"}, {"series", uid}});
    presenter.send({{"type", "size"}, {"width", kSide}, {"height", kSide}});
    *seq = 2;
    return presenter.waitForText("opened").isEmpty() ? QString() : id;
}

// Authenticates and joins; the member number the session gave it.
quint64 join(RemoteTestClient& follower, const QString& session) {
    if (!follower.waitConnected() || !follower.authenticate()) {
        return 0;
    }
    const qsizetype from = follower.texts.size();
    follower.send({{"type", "session-join"}, {"session", session}});
    const QJsonObject state = nextText(follower, "session-state", from);
    return state["role"].toString() == "follower" ? quint64(state["you"].toInteger()) : 0;
}

} // namespace

class TestRemoteSessions : public QObject {
    Q_OBJECT

private slots:
    void presenterControlsFollowersWatchAndControlIsHandedOver() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port());
        std::uint64_t seq = 0;
        const QString session = startSession(presenter, &seq);
        QVERIFY(!session.isEmpty());
        QVERIFY(frameOf(presenter, seq));

        RemoteTestClient follower(server.port());
        const quint64 followerId = join(follower, session);
        QVERIFY(followerId > 0);
        QVERIFY(!follower.waitForText("opened").isEmpty()); // a late joiner gets the series
        QVERIFY(frameOf(follower, seq));                    // and the last frame at once
        const QJsonObject state = follower.texts.back()["type"] == "session-state"
                                      ? follower.texts.back()
                                      : follower.waitForText("session-state");
        QCOMPARE(state["members"].toInt(), 2);

        presenter.send({{"type", "camera"}, {"azimuth", 40}});
        ++seq;
        const ReceivedFrame* mine = frameOf(presenter, seq);
        const ReceivedFrame* theirs = frameOf(follower, seq);
        QVERIFY(mine && theirs);
        QCOMPARE(theirs->header.seq, seq);
        QCOMPARE(theirs->image, mine->image); // the same bytes, encoded once

        // A follower's view message is refused, not fatal.
        qsizetype from = follower.texts.size();
        follower.send({{"type", "camera"}, {"azimuth", 90}});
        const QJsonObject refused = nextText(follower, "error", from);
        QCOMPARE(refused["code"].toString(), "not-presenter");
        QVERIFY(refused["message"].toString().contains("control"));
        QVERIFY(!refused["fatal"].toBool());
        follower.send({{"type", "session-handover"}, {"to", 1}});
        QCOMPARE(nextText(follower, "error", from + 1)["code"].toString(), "not-presenter");

        // The presenter hands control over.
        from = follower.texts.size();
        const qsizetype presenterFrom = presenter.texts.size();
        presenter.send({{"type", "session-handover"}, {"to", qint64(followerId)}});
        QCOMPARE(nextText(follower, "session-state", from)["role"].toString(), "presenter");
        QCOMPARE(nextText(presenter, "session-state", presenterFrom)["role"].toString(),
                 "follower");
        follower.send({{"type", "camera"}, {"azimuth", 120}});
        ++seq;
        QVERIFY(frameOf(follower, seq));
        QVERIFY(frameOf(presenter, seq));
        QCOMPARE(presenter.frames.back().image, follower.frames.back().image);
        from = presenter.texts.size();
        presenter.send({{"type", "camera"}, {"azimuth", 10}});
        QCOMPARE(nextText(presenter, "error", from)["code"].toString(), "not-presenter");
        QVERIFY(!presenter.disconnected && !follower.disconnected);

        // Leaving: the remaining member presents alone.
        from = presenter.texts.size();
        follower.send({{"type", "session-leave"}});
        QVERIFY(!follower.waitForText("session-left").isEmpty());
        const QJsonObject alone = nextText(presenter, "session-state", from);
        QCOMPARE(alone["members"].toInt(), 1);
        QCOMPARE(alone["role"].toString(), "presenter");
    }

    // The presenter's sampling message (version 2) changes the session's view:
    // followers (version 1 ones too: they only watch) get the same frame bytes, a
    // member who joins later gets that frame, and the sampling stays when
    // control passes on.
    void followersGetThePresentersSampling() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port(), {"lucent.v2"});
        std::uint64_t seq = 0;
        const QString session = startSession(presenter, &seq);
        QVERIFY(!session.isEmpty());
        QVERIFY(frameOf(presenter, seq));
        const ImageRGBA8 plain = presenter.frames.back().decoded();
        RemoteTestClient follower(server.port());
        const quint64 followerId = join(follower, session);
        QVERIFY(followerId > 0);

        presenter.send({{"type", "sampling"}, {"step", 2.0}, {"interp", "nearest"}});
        ++seq;
        const ReceivedFrame* mine = frameOf(presenter, seq);
        const ReceivedFrame* theirs = frameOf(follower, seq);
        QVERIFY(mine && theirs);
        QCOMPARE(theirs->header.seq, seq);
        QCOMPARE(theirs->image, mine->image);
        const double change = psnr(plain, mine->decoded());
        qInfo("the presenter's sampling against the default: %.1f dB", change);
        QVERIFY(change < 35.0);

        RemoteTestClient late(server.port());
        QVERIFY(join(late, session) > 0);
        QVERIFY(frameOf(late, seq));
        QCOMPARE(late.frames.back().image, mine->image);

        qsizetype from = follower.texts.size();
        presenter.send({{"type", "session-handover"}, {"to", qint64(followerId)}});
        QCOMPARE(nextText(follower, "session-state", from)["role"].toString(), "presenter");
        follower.send({{"type", "camera"}, {"azimuth", 60}});
        ++seq;
        const ReceivedFrame* turned = frameOf(follower, seq);
        QVERIFY(turned);
        const Volume volume = loadPath(server.volumeFile().toStdString());
        RenderDescription d;
        d.volume = &volume;
        d.width = kSide;
        d.height = kSide;
        d.transferFunction = loadPreset("ct-bone");
        d.camera.azimuth = 60.0;
        const ImageRGBA8 unsampled = CpuRayCaster(volume).render(d).image;
        d.sampling.step = 2.0;
        d.sampling.interpolation = Interpolation::Nearest;
        const ImageRGBA8 sampled = CpuRayCaster(volume).render(d).image;
        const double kept = psnr(sampled, turned->decoded());
        qInfo("after the handover: %.1f dB against the local render of that sampling, %.1f dB "
              "against the default",
              kept, psnr(unsampled, turned->decoded()));
        QVERIFY2(kept >= 40.0, qPrintable(QString("PSNR %1 dB").arg(kept)));
        QVERIFY(psnr(unsampled, turned->decoded()) < 35.0);
    }

    void fiftyFollowersReceiveTheSameFrames() {
        ServerProcess server("cpu", {}, {"--max-clients", "60"});
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port());
        std::uint64_t seq = 0;
        const QString session = startSession(presenter, &seq);
        QVERIFY(!session.isEmpty());
        std::vector<std::unique_ptr<RemoteTestClient>> followers;
        for (int n = 0; n < 50; ++n) {
            followers.push_back(std::make_unique<RemoteTestClient>(server.port()));
        }
        for (auto& f : followers) {
            QVERIFY(join(*f, session) > 0);
        }
        for (int turn = 1; turn <= 3; ++turn) {
            presenter.send({{"type", "camera"}, {"azimuth", 30.0 * turn}});
            ++seq;
            const ReceivedFrame* shown = frameOf(presenter, seq);
            QVERIFY(shown);
            for (auto& f : followers) {
                const ReceivedFrame* got = frameOf(*f, seq);
                QVERIFY(got);
                QCOMPARE(got->header.seq, seq);
                QCOMPARE(got->image, shown->image);
                QCOMPARE(got->header.renderMs, shown->header.renderMs); // one render
            }
        }
        const qsizetype from = presenter.texts.size();
        followers.front()->abort();
        QCOMPARE(nextText(presenter, "session-state", from)["members"].toInt(), 50);
    }

    void killedClientsFreeTheirPlacesAndSessions() {
        ServerProcess server("cpu", {}, {"--max-sessions", "1", "--max-session-members", "2"});
        QVERIFY(server.port());
        auto a = std::make_unique<RemoteTestClient>(server.port());
        std::uint64_t seq = 0;
        const QString session = startSession(*a, &seq);
        QVERIFY(!session.isEmpty());
        RemoteTestClient b(server.port());
        QVERIFY(join(b, session) > 0);

        RemoteTestClient c(server.port());
        QVERIFY(c.waitConnected() && c.authenticate());
        c.send({{"type", "session-join"}, {"session", session}});
        const QJsonObject full = c.waitForText("error");
        QCOMPARE(full["code"].toString(), "session-full");
        QVERIFY(!full["fatal"].toBool());
        qsizetype from = c.texts.size();
        c.send({{"type", "session-create"}});
        QCOMPARE(nextText(c, "error", from)["code"].toString(), "session-limit");

        // The presenter is killed: the follower presents, and the place is free.
        from = b.texts.size();
        a->abort();
        a.reset();
        const QJsonObject passed = nextText(b, "session-state", from);
        QCOMPARE(passed["role"].toString(), "presenter");
        QCOMPARE(passed["members"].toInt(), 1);
        b.send({{"type", "camera"}, {"azimuth", 33}});
        QVERIFY(frameOf(b, seq + 1));
        from = c.texts.size();
        c.send({{"type", "session-join"}, {"session", session}});
        QCOMPARE(nextText(c, "session-state", from)["members"].toInt(), 2);
        from = c.texts.size();
        c.send({{"type", "session-leave"}});
        QVERIFY(!nextText(c, "session-left", from).isEmpty());

        // The last member is killed: the session ends and another may start.
        b.abort();
        QVERIFY2(QTest::qWaitFor([&] { return server.log().contains("a session ended"); }, 20000),
                 qPrintable(server.log()));
        from = c.texts.size();
        c.send({{"type", "session-join"}, {"session", session}});
        QCOMPARE(nextText(c, "error", from)["code"].toString(), "not-found");
        from = c.texts.size();
        c.send({{"type", "session-create"}});
        QVERIFY(!nextText(c, "session-created", from).isEmpty());
        QVERIFY(!c.disconnected);
    }

    void aKilledFollowerProcessLeavesItsSession_data() {
        QTest::addColumn<bool>("freeze");
        QTest::newRow("killed") << false;
        // Stopped (SIGSTOP): its connection stays open but it answers no
        // ping; the server's keepalive drops it.
        QTest::newRow("frozen") << true;
    }
    void aKilledFollowerProcessLeavesItsSession() {
        QFETCH(bool, freeze);
        ServerProcess server("cpu", {}, {"--keepalive", "1"});
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port());
        std::uint64_t seq = 0;
        const QString session = startSession(presenter, &seq);
        QVERIFY(!session.isEmpty());
        QProcess follower;
        follower.start(QString(LUCENT_BIN_DIR) + "/remote_follower",
                       {QString::number(server.port()), kToken, session});
        QString out;
        QVERIFY(QTest::qWaitFor(
            [&] {
                out += QString::fromUtf8(follower.readAllStandardOutput());
                return out.contains("frame");
            },
            30000));
        QVERIFY2(out.contains("joined"), qPrintable(out));
        QVERIFY(QTest::qWaitFor(
            [&] {
                for (const QJsonObject& t : presenter.texts) {
                    if (t["type"] == "session-state" && t["members"].toInt() == 2) {
                        return true;
                    }
                }
                return false;
            },
            10000));
        const qsizetype from = presenter.texts.size();
        QElapsedTimer clock;
        clock.start();
        if (freeze) {
            QCOMPARE(::kill(pid_t(follower.processId()), SIGSTOP), 0);
        } else {
            follower.kill(); // SIGKILL: no close handshake
            QVERIFY(follower.waitForFinished(10000));
        }
        const QJsonObject state = nextText(presenter, "session-state", from);
        qInfo("the session saw the follower go after %lld ms", qlonglong(clock.elapsed()));
        if (freeze) {
            QVERIFY(clock.elapsed() >= 2000); // not before three silent seconds, give or take one
            follower.kill();
            QVERIFY(follower.waitForFinished(10000));
        }
        QCOMPARE(state["members"].toInt(), 1);
        QCOMPARE(state["role"].toString(), "presenter");
        presenter.send({{"type", "camera"}, {"azimuth", 5}});
        QVERIFY(frameOf(presenter, seq + 1));
    }

    void badSessionMessagesCloseOnlyTheirConnection() {
        ServerProcess server;
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port());
        std::uint64_t seq = 0;
        const QString session = startSession(presenter, &seq);
        QVERIFY(!session.isEmpty());
        RemoteTestClient follower(server.port());
        QVERIFY(join(follower, session) > 0);

        auto expectClosed = [&](const QString& text, const QString& code) {
            RemoteTestClient bad(server.port());
            QVERIFY(bad.waitConnected() && bad.authenticate());
            bad.sendRaw(text);
            const QJsonObject error = bad.waitForText("error");
            QVERIFY2(error["code"].toString() == code, qPrintable(text.left(80)));
            QVERIFY(error["fatal"].toBool());
            QVERIFY(bad.waitDisconnected());
        };
        expectClosed("{\"type\":\"session-leave\"}", "out-of-order");
        expectClosed("{\"type\":\"session-handover\",\"to\":1}", "out-of-order");
        expectClosed("{\"type\":\"session-join\",\"session\":", "malformed");
        expectClosed("{\"type\":\"session-create\",\"x\":\"" + QString(100 * 1024, 'x') + "\"}",
                     "too-large");
        expectClosed("{\"type\":\"session-start\"}", "unknown-type");
        {
            RemoteTestClient twice(server.port());
            QVERIFY(twice.waitConnected() && twice.authenticate());
            twice.send({{"type", "session-join"}, {"session", session}});
            QVERIFY(!twice.waitForText("session-state").isEmpty());
            twice.send({{"type", "session-create"}});
            QCOMPARE(twice.waitForText("error")["code"].toString(), "out-of-order");
            QVERIFY(twice.waitDisconnected());
        }
        {
            RemoteTestClient fields(server.port());
            QVERIFY(fields.waitConnected() && fields.authenticate());
            fields.sendRaw("{\"type\":\"session-join\",\"session\":42}");
            QCOMPARE(fields.waitForText("error")["code"].toString(), "bad-request");
            const qsizetype from = fields.texts.size();
            fields.send({{"type", "session-join"}, {"session", "no-such-session"}});
            QCOMPARE(nextText(fields, "error", from)["code"].toString(), "not-found");
            QTest::qWait(200);
            QVERIFY(!fields.disconnected);
        }
        // The session is still served, and counts its members right.
        const qsizetype from = presenter.texts.size();
        presenter.send({{"type", "camera"}, {"azimuth", 77}});
        QVERIFY(frameOf(presenter, seq + 1));
        QVERIFY(frameOf(follower, seq + 1));
        presenter.send({{"type", "render"}});
        QVERIFY(frameOf(follower, seq + 2));
        QVERIFY(!presenter.disconnected && !follower.disconnected);
        Q_UNUSED(from);
    }

    void followersSeeOnlyDeidentifiedData() {
        const QString data = QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";
        if (!QFileInfo(data).isDir()) {
            QSKIP("the real DICOM data (../shared/data) is absent");
        }
        const Catalog original = scanPath(data.toStdString());
        QCOMPARE(original.series.size(), std::size_t(1));
        const SeriesEntry& entry = original.series[0];
        QVERIFY(!entry.patientName.empty() && !entry.patientId.empty());

        ServerProcess server("cpu", data);
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port());
        std::uint64_t seq = 0;
        const QString session = startSession(presenter, &seq);
        QVERIFY(!session.isEmpty());
        RemoteTestClient follower(server.port());
        QVERIFY(join(follower, session) > 0);
        const QJsonObject opened = follower.waitForText("opened");
        QVERIFY(!opened.isEmpty());
        const glm::ivec3 d = entry.geometry.dims;
        QCOMPARE(opened["dims"].toArray(), QJsonArray({d.x, d.y, d.z}));
        QVERIFY(opened["series"].toString().toStdString() != entry.id);
        QVERIFY(frameOf(follower, seq));
        QCOMPARE(follower.frames.back().header.width, kSide);
        follower.send({{"type", "list"}});
        const QJsonArray listed = follower.waitForText("series")["series"].toArray();
        QCOMPARE(listed.size(), 1);
        QCOMPARE(listed[0].toObject()["uid"].toString(), opened["series"].toString());

        // Nothing the follower received names the patient, the study or the place.
        const QString received = follower.allText();
        qInfo("a follower received:\n%s", qPrintable(received.left(1500)));
        for (const std::string& secret :
             {entry.patientName, entry.patientId, entry.id, entry.seriesUid, entry.studyUid,
              entry.description, entry.studyDate, std::string("QMC")}) {
            if (!secret.empty()) {
                QVERIFY2(!received.contains(QString::fromStdString(secret)), secret.c_str());
            }
        }
        // The copy on disk is de-identified too (and the original untouched).
        const Catalog copies = scanPath((server.storeDir() + "/deidentified").toStdString());
        QCOMPARE(copies.series.size(), std::size_t(1));
        QVERIFY(copies.series[0].patientName.empty() && copies.series[0].patientId.empty());
        QCOMPARE(copies.series[0].id, opened["series"].toString().toStdString());
        QCOMPARE(scanPath(data.toStdString()).series[0].patientName, entry.patientName);
        QVERIFY(!server.log().contains(QString::fromStdString(entry.patientName)));
    }
};

QTEST_GUILESS_MAIN(TestRemoteSessions)
#include "test_remote_sessions.moc"
