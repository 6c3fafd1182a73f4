// Benchmark (label perf): the remote path of lucent-server on loopback.
//  1. The time it adds to a 1024 x 1024 frame: the server's encode, framing,
//     the WebSocket send and receive, and the client's decode, for PNG
//     (still) and JPEG (quality 85). Anchor: libjpeg-turbo encodes 1024 x 1024
//     in 1.6-8 ms; target: at most 15 ms added.
//  2. Frames a second delivered to 1, 10 and 50 followers of a teaching
//     session while the presenter turns the camera as fast as frames come, at
//     most 50 camera messages a second (target: 50 followers at the render rate).
// Prints the figures; asserts only that frames arrive (timing belongs to
// benchmarks, not tests). LUCENT_BENCH_BACKEND=gl renders on the GPU path.
#include <QElapsedTimer>
#include <QEventLoop>
#include <QJsonArray>
#include <QTest>
#include <QTimer>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "tests/server/RemoteTestFixture.h"

using namespace lucent;
using namespace lucent::test;

namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// A client that stamps each frame the moment it arrives and (optionally) decodes it.
class BenchClient {
public:
    BenchClient(quint16 port, bool decode) : decode_(decode) {
        QObject::connect(&socket_, &QWebSocket::textMessageReceived, [this](const QString& t) {
            texts.append(QJsonDocument::fromJson(t.toUtf8()).object());
            if (loop_) {
                loop_->quit();
            }
        });
        QObject::connect(&socket_, &QWebSocket::binaryMessageReceived, [this](const QByteArray& b) {
            const Clock::time_point arrived = Clock::now();
            const auto parsed =
                remote::parseFrameMessage(std::string_view(b.constData(), std::size_t(b.size())));
            Frame f{parsed.header, arrived, 0.0, b.size()};
            if (decode_) {
                const auto t0 = Clock::now();
                const QImage image = QImage::fromData(
                    QByteArray::fromRawData(parsed.image.data(), qsizetype(parsed.image.size())));
                f.decodeMs = msBetween(t0, Clock::now());
                if (image.width() != parsed.header.width) {
                    qWarning("a frame did not decode");
                }
            }
            frames.push_back(f);
            if (loop_ && f.header.seq >= waitedSeq_) {
                loop_->quit();
            }
        });
        socket_.open(QUrl(QString("ws://127.0.0.1:%1/").arg(port)));
    }
    void send(const QJsonObject& m) {
        socket_.sendTextMessage(QString::fromUtf8(QJsonDocument(m).toJson(QJsonDocument::Compact)));
    }
    // Runs the event loop until a frame of at least `seq` arrived (or the timeout).
    bool waitFrame(std::uint64_t seq, int timeoutMs = 60000) {
        const auto has = [&] { return !frames.empty() && frames.back().header.seq >= seq; };
        QElapsedTimer timer;
        timer.start();
        waitedSeq_ = seq;
        while (!has() && timer.elapsed() < timeoutMs) {
            QEventLoop loop; // a frame, a text message or the timeout ends it
            loop_ = &loop;
            QTimer::singleShot(int(timeoutMs - timer.elapsed()), &loop, &QEventLoop::quit);
            loop.exec();
            loop_ = nullptr;
        }
        return has();
    }
    QJsonObject waitText(const QString& type, int timeoutMs = 30000) {
        QJsonObject found;
        (void)QTest::qWaitFor(
            [&] {
                for (const auto& t : texts) {
                    if (t["type"].toString() == type) {
                        found = t;
                        return true;
                    }
                }
                return false;
            },
            timeoutMs);
        return found;
    }
    bool connected() {
        return QTest::qWaitFor(
            [this] { return socket_.state() == QAbstractSocket::ConnectedState; }, 10000);
    }

    struct Frame {
        remote::FrameHeader header;
        Clock::time_point arrived;
        double decodeMs;
        qsizetype bytes;
    };
    std::vector<Frame> frames;
    QList<QJsonObject> texts;

private:
    bool decode_;
    QWebSocket socket_;
    QEventLoop* loop_ = nullptr;
    std::uint64_t waitedSeq_ = 0;
};

QString backend() {
    const QByteArray b = qgetenv("LUCENT_BENCH_BACKEND");
    return b.isEmpty() ? QString("cpu") : QString::fromUtf8(b);
}

QString authenticateAndList(BenchClient& c) {
    if (!c.connected()) {
        return {};
    }
    c.send({{"type", "auth"}, {"token", kToken}});
    if (c.waitText("hello").isEmpty()) {
        return {};
    }
    c.send({{"type", "list"}});
    return c.waitText("series")["series"].toArray()[0].toObject()["uid"].toString();
}

} // namespace

class BenchRemote : public QObject {
    Q_OBJECT
private slots:
    void addedTimePerFrame1024() {
        ServerProcess server(backend());
        QVERIFY(server.port());
        for (const bool jpeg : {false, true}) {
            BenchClient client(server.port(), true);
            const QString uid = authenticateAndList(client);
            QVERIFY(!uid.isEmpty());
            std::uint64_t seq = 0;
            client.send({{"type", "open"}, {"series", uid}});
            // JPEG frames are the interactive description: half the size set here.
            const int side = jpeg ? 2048 : 1024;
            client.send({{"type", "size"}, {"width", side}, {"height", side}});
            client.send({{"type", "quality"}, {"quality", jpeg ? "interactive" : "still"}});
            seq = 3;
            QVERIFY(client.waitFrame(seq));
            std::vector<double> added, encode, decode, transfer, bytes;
            for (int n = 0; n < 12; ++n) {
                const auto t0 = Clock::now();
                client.send({{"type", "camera"}, {"azimuth", 15.0 * n}});
                ++seq;
                QVERIFY(client.waitFrame(seq));
                const auto& f = client.frames.back();
                QCOMPARE(f.header.width, 1024);
                const double roundTrip = msBetween(t0, f.arrived);
                encode.push_back(f.header.encodeMs);
                decode.push_back(f.decodeMs);
                transfer.push_back(roundTrip - f.header.renderMs - f.header.encodeMs);
                added.push_back(roundTrip - f.header.renderMs + f.decodeMs);
                bytes.push_back(double(f.bytes));
            }
            qInfo("remote_1024 %s: added_ms=%.1f encode_ms=%.1f transfer_ms=%.1f decode_ms=%.1f "
                  "frame_kib=%.0f (median of 12; backend %s; target added <= 15 ms)",
                  jpeg ? "jpeg85" : "png", median(added), median(encode), median(transfer),
                  median(decode), median(bytes) / 1024.0, qPrintable(backend()));
        }
    }

    void framesPerSecondToFollowers_data() {
        QTest::addColumn<int>("followers");
        QTest::addColumn<bool>("interactive");
        for (const int n : {1, 10, 50}) {
            QTest::newRow(qPrintable(QString("%1 png").arg(n))) << n << false;
            QTest::newRow(qPrintable(QString("%1 jpeg").arg(n))) << n << true;
        }
    }
    void framesPerSecondToFollowers() {
        QFETCH(int, followers);
        QFETCH(bool, interactive);
        ServerProcess server(backend());
        QVERIFY(server.port());
        BenchClient presenter(server.port(), false);
        const QString uid = authenticateAndList(presenter);
        QVERIFY(!uid.isEmpty());
        presenter.send({{"type", "session-create"}});
        const QString session = presenter.waitText("session-created")["session"].toString();
        presenter.send({{"type", "open"}, {"series", uid}});
        presenter.send({{"type", "size"}, {"width", 512}, {"height", 512}});
        std::uint64_t seq = 2;
        if (interactive) {
            presenter.send({{"type", "interaction"}, {"state", "start"}});
            ++seq;
        }
        QVERIFY(presenter.waitFrame(seq));
        std::vector<std::unique_ptr<BenchClient>> members;
        for (int n = 0; n < followers; ++n) {
            members.push_back(std::make_unique<BenchClient>(server.port(), false));
        }
        for (auto& m : members) {
            QVERIFY(m->connected());
            m->send({{"type", "auth"}, {"token", kToken}});
            m->send({{"type", "session-join"}, {"session", session}});
        }
        for (auto& m : members) {
            QVERIFY(!m->waitText("session-state").isEmpty());
            QVERIFY(m->waitFrame(seq));
        }
        const std::size_t before = presenter.frames.size();
        std::vector<std::size_t> memberBefore;
        for (auto& m : members) {
            memberBefore.push_back(m->frames.size());
        }
        // The presenter drags: a new camera as soon as the last one's frame came,
        // at most 50 a second (the server allows 60: more are refused).
        const auto start = Clock::now();
        auto lastSent = start - std::chrono::milliseconds(100);
        int turns = 0;
        while (msBetween(start, Clock::now()) < 4000.0 && turns < 400) {
            const double sinceLast = msBetween(lastSent, Clock::now());
            if (sinceLast < 20.0) {
                QTest::qWait(int(std::ceil(20.0 - sinceLast)));
            }
            lastSent = Clock::now();
            presenter.send({{"type", "camera"}, {"azimuth", 3.0 * ++turns}});
            ++seq;
            if (!presenter.waitFrame(seq, 20000)) {
                for (const auto& t : presenter.texts) {
                    qWarning("%s", QJsonDocument(t).toJson(QJsonDocument::Compact).constData());
                }
                QFAIL(qPrintable(QString("no frame %1; the last was %2")
                                     .arg(seq)
                                     .arg(presenter.frames.back().header.seq)));
            }
        }
        const auto presenterDone = Clock::now();
        for (auto& m : members) {
            QVERIFY(m->waitFrame(seq, 30000));
        }
        const auto allDone = Clock::now();
        const double renderFps =
            double(presenter.frames.size() - before) / (msBetween(start, presenterDone) / 1000.0);
        double slowest = 1e30, fewest = 1e30;
        for (std::size_t n = 0; n < members.size(); ++n) {
            const auto& frames = members[n]->frames;
            const double got = double(frames.size() - memberBefore[n]);
            fewest = std::min(fewest, got);
            slowest = std::min(slowest, got / (msBetween(start, frames.back().arrived) / 1000.0));
        }
        std::vector<double> renderMs;
        for (std::size_t n = before; n < presenter.frames.size(); ++n) {
            renderMs.push_back(presenter.frames[n].header.renderMs +
                               presenter.frames[n].header.encodeMs);
        }
        qInfo("session_%d_followers %s: render_fps=%.1f follower_fps_min=%.1f "
              "frames=%zu follower_frames_min=%.0f render_encode_ms=%.1f last_follower_lag_ms=%.0f "
              "frame_kib=%.0f",
              followers, interactive ? "jpeg_adaptive" : "png_512", renderFps, slowest,
              presenter.frames.size() - before, fewest, median(renderMs),
              msBetween(presenterDone, allDone), double(presenter.frames.back().bytes) / 1024.0);
    }
};

QTEST_GUILESS_MAIN(BenchRemote)
#include "bench_remote.moc"
