// Record and replay on the real lucent-server over loopback, with real CT: the
// presenter of a teaching session records camera turns, a preset and a mode
// while collecting the live still frames; the recording lies whole in the
// store; a stepped replay re-renders each recorded view, one lossless frame
// each, equal to its live frame (>= 50 dB), and a token follower watches it; a
// follower by invite may neither record, list nor replay. Then lucent-cli movie
// --replay on that recording: ffprobe's frame count and size, frame k against
// lucent-cli render of the same camera (>= 35 dB, lossy codec), and a
// recording of another series refused.
#include <QDir>
#include <QJsonArray>
#include <QTest>

#include <cmath>

#include "RemoteTestFixture.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "tests/support/CliRunner.h"
#include "tests/support/MovieProbe.h"
#include "tests/support/RealData.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSide = 96;
constexpr double kMinReplayPsnr = 50.0;
constexpr double kMinMoviePsnr = 35.0;
constexpr char kCt[] = "dcm_qa_ct/Philips_S21570/S2010"; // 28 slices 512x512, 5 mm
constexpr char kOtherSeries[] = "dcm_qa_ct/Philips_S21570/S1000";

QString dataPath(const char* sub) {
    return QString::fromStdString((kRealData / sub).string());
}

// The recorded changes and the lucent-cli render flags that make each view
// after it (the flags of all changes so far).
struct Change {
    QJsonObject message;
    QStringList flags;
};
const QList<Change>& changes() {
    static const QList<Change> list{
        {{{"type", "camera"}, {"azimuth", 40}}, {"--azimuth", "40"}},
        {{{"type", "camera"}, {"elevation", 25}}, {"--elevation", "25"}},
        {{{"type", "tf"}, {"preset", "ct-soft-tissue"}}, {"--preset", "ct-soft-tissue"}},
        {{{"type", "camera"}, {"azimuth", 130}, {"zoom", 1.4}},
         {"--azimuth", "130", "--zoom", "1.4"}},
        {{{"type", "mode"}, {"mode", "mip"}}, {"--mode", "mip"}},
    };
    return list;
}

// The flags of the view after the first `n` changes (later flags win).
QStringList flagsAfter(int n) {
    QStringList flags{"--preset", "ct-bone"};
    for (int k = 0; k < n; ++k) {
        flags += changes()[k].flags;
    }
    return flags;
}

// Where a failing comparison leaves its images.
QString failureDir() {
    const QString dir = QDir::temp().filePath("lucent-test-recordings");
    QDir().mkpath(dir);
    return dir;
}

QJsonObject textAfter(RemoteTestClient& client, const QString& type, qsizetype from) {
    return client.waitForText(type, 60000, from);
}

} // namespace

class TestRemoteRecordings : public QObject {
    Q_OBJECT
    std::unique_ptr<ServerProcess> server_;
    QString recordingFile_;
    QString recordingId_;
    QList<ImageRGBA8> live_;

    // In the store, whole; nothing left in its tmp/; listed.
    void verifyStoredRecording(RemoteTestClient& presenter, const QString& uid) {
        recordingFile_ = server_->storeDir() + "/recordings/" + recordingId_ + ".jsonl";
        QVERIFY2(QFile::exists(recordingFile_), qPrintable(recordingFile_));
        const remote::Recording recording = remote::readRecording(recordingFile_.toStdString());
        QCOMPARE(recording.header.series, uid.toStdString());
        QCOMPARE(recording.header.views, int(changes().size()) + 1);
        QCOMPARE(recording.header.width, kSide);
        QVERIFY(QDir(server_->storeDir() + "/tmp")
                    .entryList({"recording-*"}, QDir::Files | QDir::Hidden)
                    .isEmpty());
        const qsizetype from = presenter.texts.size();
        presenter.send({{"type", "recording-list"}});
        const QJsonArray listed = textAfter(presenter, "recordings", from)["recordings"].toArray();
        QCOMPARE(listed.size(), 1);
        QCOMPARE(listed[0].toObject()["id"].toString(), recordingId_);
        QCOMPARE(listed[0].toObject()["series"].toString(), uid);
    }

    // The stepped replay: one lossless frame per recorded view, each its live
    // frame, in their order; the token follower watches it.
    void verifySteppedReplay(RemoteTestClient& presenter, RemoteTestClient& follower) {
        const qsizetype framesBefore = presenter.frames.size();
        const qsizetype followerFramesBefore = follower.frames.size();
        qsizetype from = presenter.texts.size();
        presenter.send({{"type", "replay"}, {"recording", recordingId_}, {"pace", "step"}});
        for (int k = 0; k < live_.size(); ++k) {
            if (k > 0) {
                presenter.send({{"type", "replay-step"}});
            }
            const QJsonObject progress = textAfter(presenter, "replay-progress", from);
            from = presenter.texts.indexOf(progress) + 1;
            QCOMPARE(progress["view"].toInt(), k);
            QCOMPARE(progress["views"].toInt(), int(live_.size()));
            presenter.seq = std::uint64_t(progress["seq"].toInteger());
            const ReceivedFrame* frame = presenter.waitForCurrentFrame();
            QVERIFY2(frame, qPrintable(presenter.allText()));
            QCOMPARE(frame->header.format, std::string("png"));
            const ImageRGBA8 replayed = frame->decoded();
            const double db = psnr(replayed, live_[k]);
            qInfo("replayed view %d against its live frame: %.2f dB", k, db);
            if (k > 0) { // the views come in their order: not the one before
                const double previous = psnr(replayed, live_[k - 1]);
                QVERIFY2(previous < kMinReplayPsnr,
                         qPrintable(
                             QString("view %1 is view %2: %3 dB").arg(k).arg(k - 1).arg(previous)));
            }
            if (db < kMinReplayPsnr) {
                const QString dir = failureDir();
                writePng(replayed, QString("%1/replayed-%2.png").arg(dir).arg(k).toStdString());
                writePng(live_[k], QString("%1/live-%2.png").arg(dir).arg(k).toStdString());
                QFAIL(qPrintable(
                    QString("view %1: %2 dB (images in %3)").arg(k).arg(db).arg(failureDir())));
            }
        }
        const QJsonObject ended = textAfter(presenter, "replay-ended", from);
        QCOMPARE(ended["reason"].toString(), QString("end"));
        QTest::qWait(500); // no late frame
        QCOMPARE(presenter.frames.size() - framesBefore, live_.size());
        // The token follower watched the replay (frames of the de-identified copy).
        QVERIFY(QTest::qWaitFor([&] {
            return follower.frames.size() > followerFramesBefore &&
                   follower.frames.back().header.seq == presenter.frames.back().header.seq;
        }));
    }

    // Refusals that keep the connection: an unknown recording, a step without a
    // replay, a recording file that is not whole; a follower by token does not
    // control the view.
    void verifyReplayRefusals(RemoteTestClient& presenter, RemoteTestClient& follower) {
        for (const auto& [message, code] :
             {std::pair{QJsonObject{{"type", "replay"}, {"recording", "nosuchrecording"}},
                        QString("not-found")},
              std::pair{QJsonObject{{"type", "replay"}, {"recording", "../../etc/passwd"}},
                        QString("bad-request")},
              std::pair{QJsonObject{{"type", "replay-step"}}, QString("bad-request")},
              std::pair{QJsonObject{{"type", "record"}, {"state", "stop"}},
                        QString("bad-request")}}) {
            const qsizetype before = presenter.texts.size();
            presenter.send(message);
            QCOMPARE(textAfter(presenter, "error", before)["code"].toString(), code);
        }
        // A recording file that is not whole: refused naming its line, the view kept.
        QFile broken(server_->storeDir() + "/recordings/broken.jsonl");
        QVERIFY(broken.open(QIODevice::WriteOnly));
        broken.write("{\"lucent_recording\":1}\n");
        broken.close();
        const qsizetype from = presenter.texts.size();
        presenter.send({{"type", "replay"}, {"recording", "broken"}});
        const QJsonObject unreadable = textAfter(presenter, "error", from);
        QCOMPARE(unreadable["code"].toString(), QString("render-failed"));
        QVERIFY2(unreadable["message"].toString().contains("broken.jsonl:1: 'series'"),
                 qPrintable(unreadable["message"].toString()));
        QVERIFY(broken.remove());
        // A follower by token does not control the view.
        const qsizetype before = follower.texts.size();
        follower.send({{"type", "record"}, {"state", "start"}});
        QCOMPARE(textAfter(follower, "error", before)["code"].toString(), QString("not-presenter"));
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        server_ = std::make_unique<ServerProcess>("cpu", dataPath(kCt));
        QVERIFY(server_->started());
    }

    void recordThenReplayStepped() {
        RemoteTestClient presenter(server_->port(), {"lucent.v4"});
        QVERIFY(presenter.waitConnected());
        QVERIFY(presenter.authenticate());
        presenter.send({{"type", "list"}});
        const QJsonArray series = presenter.waitForText("series")["series"].toArray();
        QCOMPARE(series.size(), 1);
        const QString uid = series[0].toObject()["uid"].toString();

        presenter.send({{"type", "session-create"}});
        const QString session = presenter.waitForText("session-created")["session"].toString();
        QVERIFY(!session.isEmpty());
        presenter.change({{"type", "open"}, {"series", uid}});
        presenter.change({{"type", "size"}, {"width", kSide}, {"height", kSide}});
        presenter.change({{"type", "tf"}, {"preset", "ct-bone"}});
        const ReceivedFrame* first = presenter.waitForCurrentFrame();
        QVERIFY2(first, qPrintable(presenter.allText()));
        QCOMPARE(first->header.format, std::string("png"));

        // A token follower watches; an invite's holder may only follow.
        RemoteTestClient follower(server_->port(), {"lucent.v4"});
        QVERIFY(follower.waitConnected());
        QVERIFY(follower.authenticate());
        follower.send({{"type", "session-join"}, {"session", session}});
        QVERIFY(!follower.waitForText("opened").isEmpty());
        qsizetype from = presenter.texts.size();
        presenter.send({{"type", "invite-create"}});
        const QString code = textAfter(presenter, "invite-created", from)["code"].toString();
        QVERIFY(!code.isEmpty());
        RemoteTestClient student(server_->port(), {"lucent.v4", "lucent.invite." + code});
        QVERIFY(student.waitConnected());
        QVERIFY(!student.waitForText("opened").isEmpty());

        // Recording: the view at its start, then each change's live still.
        from = presenter.texts.size();
        presenter.send({{"type", "record"}, {"state", "start"}});
        recordingId_ = textAfter(presenter, "recording-started", from)["recording"].toString();
        QVERIFY2(!recordingId_.isEmpty(), qPrintable(presenter.allText()));
        live_ = {first->decoded()};
        for (const Change& change : changes()) {
            presenter.change(change.message);
            const ReceivedFrame* frame = presenter.waitForCurrentFrame();
            QVERIFY2(frame, qPrintable(presenter.allText()));
            QCOMPARE(frame->header.format, std::string("png"));
            live_.append(frame->decoded());
            QTest::qWait(150); // the original pace has time in it
        }
        from = presenter.texts.size();
        presenter.send({{"type", "record"}, {"state", "stop"}});
        const QJsonObject stopped = textAfter(presenter, "recording-stopped", from);
        QCOMPARE(stopped["recording"].toString(), recordingId_);
        QCOMPARE(stopped["views"].toInt(), int(changes().size()) + 1);
        QCOMPARE(stopped["reason"].toString(), QString("stopped"));
        QVERIFY(stopped["duration_ms"].toInteger() >= 150 * changes().size());

        verifyStoredRecording(presenter, uid);
        if (QTest::currentTestFailed()) {
            return;
        }

        // The invite's holder: forbidden, and still following.
        for (const QJsonObject& refused :
             {QJsonObject{{"type", "record"}, {"state", "start"}},
              QJsonObject{{"type", "recording-list"}},
              QJsonObject{{"type", "replay"}, {"recording", recordingId_}, {"pace", "step"}}}) {
            const qsizetype before = student.texts.size();
            student.send(refused);
            const QJsonObject error = textAfter(student, "error", before);
            QCOMPARE(error["code"].toString(), QString("forbidden"));
            QCOMPARE(error["fatal"].toBool(), false);
        }
        QVERIFY(!student.disconnected);

        verifySteppedReplay(presenter, follower);
        if (QTest::currentTestFailed()) {
            return;
        }

        verifyReplayRefusals(presenter, follower);
    }

    // Original pace into the presenter's own view: the views come in order and
    // the replay ends on the last one.
    void replayAtTheOriginalPace() {
        QVERIFY2(!recordingId_.isEmpty(), "needs recordThenReplayStepped");
        RemoteTestClient client(server_->port(), {"lucent.v4"});
        QVERIFY(client.waitConnected());
        QVERIFY(client.authenticate());
        QElapsedTimer clock;
        clock.start();
        client.send({{"type", "replay"}, {"recording", recordingId_}});
        const QJsonObject ended = client.waitForText("replay-ended", 60000);
        const qint64 replayMs = clock.elapsed();
        QCOMPARE(ended["reason"].toString(), QString("end"));
        // Not faster than it was recorded: the last message came at its time.
        const std::int64_t lastMs =
            remote::readRecording(recordingFile_.toStdString()).messages.back().atMs;
        qInfo("original pace: the last recorded message at %lld ms, replayed by %lld ms",
              static_cast<long long>(lastMs), static_cast<long long>(replayMs));
        QVERIFY(replayMs >= lastMs);
        QVERIFY(!client.waitForText("opened").isEmpty());
        int lastView = -1;
        std::uint64_t lastSeq = 0;
        for (const QJsonObject& t : std::as_const(client.texts)) {
            if (t["type"].toString() == "replay-progress") {
                QVERIFY(t["view"].toInt() > lastView);
                lastView = t["view"].toInt();
                lastSeq = std::uint64_t(t["seq"].toInteger());
            }
        }
        QCOMPARE(lastView, int(live_.size()) - 1);
        client.seq = lastSeq;
        const ReceivedFrame* frame = client.waitForCurrentFrame();
        QVERIFY2(frame, qPrintable(client.allText()));
        const double db = psnr(frame->decoded(), live_.back());
        qInfo("original pace, last view against its live frame: %.2f dB", db);
        QVERIFY2(db >= kMinReplayPsnr, qPrintable(QString("%1 dB").arg(db)));
    }

    // A recording ends with its view (another open, a dropped connection) and is kept.
    void aRecordingEndsWithItsView() {
        RemoteTestClient client(server_->port(), {"lucent.v4"});
        QVERIFY(client.waitConnected());
        QVERIFY(client.authenticate());
        QVERIFY(!client.waitForText("hello").isEmpty());
        client.send({{"type", "record"}, {"state", "start"}});
        QCOMPARE(client.waitForText("error")["code"].toString(),
                 QString("bad-request")); // no series
        const QString uid = openOnlySeries(client, kSide);
        QVERIFY(!uid.isEmpty());
        QVERIFY(client.waitForCurrentFrame());
        qsizetype from = client.texts.size();
        client.send({{"type", "record"}, {"state", "start"}});
        QVERIFY(!textAfter(client, "recording-started", from).isEmpty());
        client.change({{"type", "camera"}, {"azimuth", 90}});
        QVERIFY(client.waitForCurrentFrame());
        from = client.texts.size();
        client.change({{"type", "open"}, {"series", uid}});
        const QJsonObject stopped = textAfter(client, "recording-stopped", from);
        QCOMPARE(stopped["reason"].toString(), QString("view"));
        QCOMPARE(stopped["views"].toInt(), 2);
        QVERIFY(QFile::exists(server_->storeDir() + "/recordings/" +
                              stopped["recording"].toString() + ".jsonl"));

        // Dropped mid-recording: what was recorded reaches the store.
        QVERIFY(client.waitForCurrentFrame());
        from = client.texts.size();
        client.send({{"type", "record"}, {"state", "start"}});
        const QString id = textAfter(client, "recording-started", from)["recording"].toString();
        QVERIFY(!id.isEmpty());
        client.change({{"type", "camera"}, {"azimuth", 45}});
        QVERIFY(client.waitForCurrentFrame());
        client.abort();
        const QString file = server_->storeDir() + "/recordings/" + id + ".jsonl";
        QVERIFY2(QTest::qWaitFor([&] { return QFile::exists(file); }, 10000), qPrintable(file));
        QCOMPARE(remote::readRecording(file.toStdString()).header.views, 2);
    }

    // lucent-cli movie --replay: at the original pace (frame k the view k/fps s
    // in) and stepped (frame k recorded view k).
    void movieOfTheRecording() {
        QVERIFY2(!recordingFile_.isEmpty(), "needs recordThenReplayStepped");
        QVERIFY2(!ffmpegTool("ffprobe").isEmpty() && !ffmpegTool("ffmpeg").isEmpty(),
                 "ffprobe and ffmpeg are needed (apt-get install ffmpeg)");
        QTemporaryDir dir;
        const remote::Recording recording = remote::readRecording(recordingFile_.toStdString());
        constexpr int kFps = 10;
        const int expectedFrames = int(recording.header.durationMs * kFps / 1000) + 1;

        const QString movie = dir.filePath("replay.mp4");
        const CliRun run = runCli({"movie", dataPath(kCt), "--replay", recordingFile_, "-o", movie,
                                   "--fps", QString::number(kFps)});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const ProbedMovie probed = probeMovie(movie);
        QVERIFY2(probed.error.isEmpty(), qPrintable(probed.error));
        QCOMPARE(probed.codec, QString("h264"));
        QCOMPARE(probed.frames, expectedFrames);
        QCOMPARE(probed.width, kSide);
        QCOMPARE(probed.height, kSide);
        const QString frames = dir.filePath("frames");
        const QString decodeError = decodeFrames(movie, frames);
        QVERIFY2(decodeError.isEmpty(), qPrintable(decodeError));
        // The frame's time: the number of changes made by then.
        for (const int k : {0, expectedFrames / 2, expectedFrames - 1}) {
            const std::int64_t at = std::int64_t(k) * 1000 / kFps;
            int made = 0;
            for (const remote::RecordedMessage& m : recording.messages) {
                made += m.atMs <= at && remote::showsRecordedView(m.message) ? 1 : 0;
            }
            compareWithStill(readPng(framePng(frames, k).toStdString()), made, dir,
                             QString("original pace frame %1 (view %2)").arg(k).arg(made));
        }

        const QString stepped = dir.filePath("stepped.gif");
        const CliRun steppedRun =
            runCli({"movie", dataPath(kCt), "--replay", recordingFile_, "--replay-pace", "step",
                    "-o", stepped, "--size", "64x48"});
        QVERIFY2(steppedRun.exitCode == 0, qPrintable(steppedRun.err));
        const ProbedMovie steppedProbe = probeMovie(stepped);
        QVERIFY2(steppedProbe.error.isEmpty(), qPrintable(steppedProbe.error));
        QCOMPARE(steppedProbe.frames, int(changes().size()) + 1);
        QCOMPARE(steppedProbe.width, 64);
        QCOMPARE(steppedProbe.height, 48);

        // Another series than the recording's: refused, naming both, no file.
        const QString other = dir.filePath("other.mp4");
        const CliRun refused =
            runCli({"movie", dataPath(kOtherSeries), "--replay", recordingFile_, "-o", other});
        QCOMPARE(refused.exitCode, 3);
        QVERIFY2(refused.err.contains("records series"), qPrintable(refused.err));
        QVERIFY(!QFile::exists(other));
        const CliRun missing =
            runCli({"movie", dataPath(kCt), "--replay", dir.filePath("none.jsonl"), "-o", other});
        QCOMPARE(missing.exitCode, 3);
        QVERIFY2(missing.err.contains("none.jsonl: cannot read the recording"),
                 qPrintable(missing.err));
        const CliRun usage = runCli(
            {"movie", dataPath(kCt), "--replay", recordingFile_, "-o", other, "--turntable", "90"});
        QCOMPARE(usage.exitCode, 2);
        QVERIFY2(usage.err.contains("--turntable is not for --replay"), qPrintable(usage.err));
    }

private:
    void compareWithStill(const ImageRGBA8& frame, int view, QTemporaryDir& dir,
                          const QString& what) {
        const QString still = dir.filePath(QString("still-%1.png").arg(view));
        if (!QFile::exists(still)) {
            const CliRun render = runCli(QStringList{"render", dataPath(kCt), "-o", still, "--size",
                                                     QString("%1x%1").arg(kSide)} +
                                         flagsAfter(view));
            QVERIFY2(render.exitCode == 0, qPrintable(render.err));
        }
        const double db = psnr(frame, readPng(still.toStdString()));
        qInfo("%s against lucent-cli render: %.2f dB", qPrintable(what), db);
        if (db < kMinMoviePsnr) {
            writePng(frame, (failureDir() + "/movie-frame.png").toStdString());
            QFAIL(
                qPrintable(QString("%1: %2 dB (frame in %3)").arg(what).arg(db).arg(failureDir())));
        }
    }
};

QTEST_GUILESS_MAIN(TestRemoteRecordings)
#include "test_remote_recordings.moc"
