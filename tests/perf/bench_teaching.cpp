// Benchmark (label perf): a lecture hall on loopback. One presenter and 100
// followers of a teaching session for 10 minutes (LUCENT_BENCH_SECONDS,
// LUCENT_BENCH_FOLLOWERS and LUCENT_BENCH_FREE_LOOK change the 600, 100 and
// 10), the followers in four processes (teaching_followers). The presenter
// turns the camera in drags of 4 s (adaptive JPEG, a turn as soon as the last
// one's frame came) with 1 s rests (a lossless still), and points at 30 Hz
// all along; 10 followers look on their own (free look) at the same time.
// Prints: the server's memory (peak, after the first minute, at the end), the
// session's render rate and each follower's share of its frames, the free
// lookers' frame rate, and the pointer's latency from the presenter's send to
// each following follower's receipt (p50, p99, max, and the share that arrived).
// Asserts only that everything arrives: timing belongs to benchmarks.
#include <QFile>
#include <QProcess>
#include <QTest>
#include <QTimer>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <vector>

#include "tests/perf/PointerCode.h"
#include "tests/server/RemoteTestFixture.h"

using namespace lucent;
using namespace lucent::test;

namespace {

const QString kSeriesDir = QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";
constexpr int kFollowerProcesses = 4;

int envOr(const char* name, int fallback) {
    const QByteArray value = qgetenv(name);
    return value.isEmpty() ? fallback : value.toInt();
}

long long nowNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

// A value of /proc/PID/status in KiB ("VmRSS", "VmHWM"); 0 when unreadable.
long statusKib(qint64 pid, const QByteArray& key) {
    QFile file(QString("/proc/%1/status").arg(pid));
    if (!file.open(QIODevice::ReadOnly)) {
        return 0;
    }
    for (const QByteArray& line : file.readAll().split('\n')) {
        if (line.startsWith(key + ":")) {
            return line.mid(key.size() + 1).trimmed().split(' ').front().toLong();
        }
    }
    return 0;
}

double percentile(std::vector<double>& v, double p) {
    if (v.empty()) {
        return 0.0;
    }
    const auto at = v.begin() + std::ptrdiff_t(p * double(v.size() - 1));
    std::nth_element(v.begin(), at, v.end());
    return *at;
}

struct FollowerProcess {
    std::unique_ptr<QProcess> process = std::make_unique<QProcess>();
    QString arrivalsFile;
    QString output;
};

// Starts the followers, a quarter in each process, the free lookers spread, and
// waits until every process says its followers joined.
void startFollowers(std::vector<FollowerProcess>& processes, ServerProcess& server,
                    const QString& session, int followerCount, int freeLookCount,
                    const QTemporaryDir& dir) {
    for (int p = 0; p < kFollowerProcesses; ++p) {
        const int count =
            followerCount / kFollowerProcesses + (p < followerCount % kFollowerProcesses ? 1 : 0);
        const int looking =
            freeLookCount / kFollowerProcesses + (p < freeLookCount % kFollowerProcesses ? 1 : 0);
        FollowerProcess& f = processes[std::size_t(p)];
        f.arrivalsFile = dir.filePath(QString("arrivals-%1.txt").arg(p));
        f.process->start(QString(LUCENT_BIN_DIR) + "/teaching_followers",
                         {QString::number(server.port()), kToken, session, QString::number(count),
                          QString::number(looking), f.arrivalsFile});
    }
    for (FollowerProcess& f : processes) {
        QVERIFY2(QTest::qWaitFor(
                     [&] {
                         f.output += QString::fromUtf8(f.process->readAllStandardOutput());
                         return f.output.contains("joined\n");
                     },
                     180000),
                 qPrintable("followers did not join: " + f.output + server.log()));
    }
}

// What the followers saw, gathered over their processes.
struct FollowerReports {
    std::vector<double> latencies; // the pointer's, ms
    std::vector<double> shares;    // each follower's share of the session's frames
    std::vector<double> lookFps;   // each free looker's frame rate
};

// Asks one process for its report and reads it and its pointer arrivals.
void readReport(FollowerProcess& f, const std::vector<long long>& pointerSent, long presenterFrames,
                double runSeconds, FollowerReports& got) {
    f.process->write("report\n");
    QVERIFY(QTest::qWaitFor(
        [&] {
            f.output += QString::fromUtf8(f.process->readAllStandardOutput());
            return f.output.contains("done\n");
        },
        60000));
    for (const QString& line : f.output.split('\n')) {
        const QStringList w = line.split(' ');
        if (w.size() == 4 && w[0] == "frames") {
            const double frames = w[2].toDouble();
            if (w[3] == "1") {
                got.lookFps.push_back(frames / runSeconds);
            } else {
                got.shares.push_back(frames / double(std::max(1L, presenterFrames)));
            }
        }
    }
    QVERIFY2(!f.output.contains("error "), qPrintable(f.output));
    QFile arrivals(f.arrivalsFile);
    QVERIFY(arrivals.open(QIODevice::ReadOnly));
    for (const QByteArray& line : arrivals.readAll().split('\n')) {
        const QList<QByteArray> w = line.split(' ');
        if (w.size() == 4) {
            const std::size_t number = w[2].toULong();
            if (number < pointerSent.size()) {
                got.latencies.push_back(double(w[3].toLongLong() - pointerSent[number]) / 1e6);
            }
        }
    }
    f.process->closeWriteChannel();
    f.process->waitForFinished(10000);
}

} // namespace

class BenchTeaching : public QObject {
    Q_OBJECT
private slots:
    void lectureHall() {
        if (!QFileInfo::exists(kSeriesDir)) {
            QSKIP("the real DICOM data (../shared/data) is absent");
        }
        const int seconds = envOr("LUCENT_BENCH_SECONDS", 600);
        const int followerCount = envOr("LUCENT_BENCH_FOLLOWERS", 100);
        const int freeLookCount = envOr("LUCENT_BENCH_FREE_LOOK", 10);
        const QString limit = QString::number(followerCount + 8);
        ServerProcess server("cpu", kSeriesDir,
                             {"--max-clients", limit, "--max-session-members", limit,
                              "--max-free-look", QString::number(freeLookCount)});
        QVERIFY(server.started());

        RemoteTestClient presenter(server.port(), {"lucent.v4"});
        QVERIFY(presenter.waitConnected());
        QVERIFY(presenter.authenticate());
        presenter.send({{"type", "session-create"}});
        const QString session = presenter.waitForText("session-created")["session"].toString();
        QVERIFY(!session.isEmpty());
        QVERIFY(!openOnlySeries(presenter, 512).isEmpty());
        QVERIFY(presenter.waitForCurrentFrame());

        // The followers, a quarter in each process, the free lookers spread.
        QTemporaryDir dir;
        std::vector<FollowerProcess> processes(kFollowerProcesses);
        startFollowers(processes, server, session, followerCount, freeLookCount, dir);
        if (QTest::currentTestFailed()) {
            return;
        }

        // The lecture: drags and rests, the pointer at 30 Hz, memory each second.
        std::vector<long long> pointerSent;
        long presenterFrames = 0;
        std::uint64_t lastSeq = presenter.seq;
        double azimuth = 0.0;
        bool dragging = false;
        long rssAfterMinute = 0;
        const auto start = std::chrono::steady_clock::now();
        const auto elapsed = [&] {
            return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        };
        QTimer tick;
        QObject::connect(&tick, &QTimer::timeout, [&] {
            presenterFrames += presenter.frames.size();
            if (!presenter.frames.isEmpty()) {
                lastSeq = presenter.frames.back().header.seq;
            }
            presenter.frames.clear();
            presenter.texts.clear();
            const bool drag = std::fmod(elapsed(), 5.0) < 4.0;
            if (drag != dragging) {
                dragging = drag;
                presenter.change({{"type", "interaction"}, {"state", drag ? "start" : "end"}});
            } else if (drag && lastSeq >= presenter.seq) {
                azimuth += 2.0;
                presenter.change({{"type", "camera"}, {"azimuth", azimuth}});
            }
        });
        QTimer point;
        QObject::connect(&point, &QTimer::timeout, [&] {
            const auto [x, y] = bench::pointerPosition(int(pointerSent.size()));
            pointerSent.push_back(nowNs());
            presenter.send({{"type", "pointer"}, {"x", x}, {"y", y}});
        });
        QTimer memory;
        QObject::connect(&memory, &QTimer::timeout, [&] {
            if (rssAfterMinute == 0 && elapsed() >= 60.0) {
                rssAfterMinute = statusKib(server.pid(), "VmRSS");
            }
        });
        tick.start(20);
        point.start(33);
        memory.start(1000);
        QTest::qWait(seconds * 1000);
        tick.stop();
        point.stop();
        memory.stop();
        const long peakKib = statusKib(server.pid(), "VmHWM");
        const long endKib = statusKib(server.pid(), "VmRSS");
        const double runSeconds = elapsed();
        QTest::qWait(2000); // the last pointers and frames land

        // What each follower got.
        FollowerReports got;
        for (FollowerProcess& f : processes) {
            readReport(f, pointerSent, presenterFrames, runSeconds, got);
            if (QTest::currentTestFailed()) {
                return;
            }
        }
        std::vector<double>& latencies = got.latencies;
        std::vector<double>& shares = got.shares;
        const std::vector<double>& lookFps = got.lookFps;
        QVERIFY(!latencies.empty());
        QVERIFY(presenterFrames > 0);
        std::sort(shares.begin(), shares.end());
        // Followers in free look get the marks but not the pointer, which points
        // into the presenter's view.
        const double delivered =
            double(latencies.size()) /
            double(pointerSent.size() * std::size_t(std::max(1, followerCount - freeLookCount)));
        qInfo("teaching_%d_followers_%ds: server_peak_mib=%.0f rss_after_1min_mib=%.0f "
              "rss_end_mib=%.0f render_fps=%.1f follower_share_min=%.2f follower_share_median=%.2f "
              "free_look=%zu free_look_fps_min=%.1f pointer_sent=%zu pointer_delivered=%.3f "
              "pointer_ms_p50=%.1f pointer_ms_p99=%.1f pointer_ms_max=%.1f",
              followerCount, seconds, peakKib / 1024.0, rssAfterMinute / 1024.0, endKib / 1024.0,
              double(presenterFrames) / runSeconds, shares.empty() ? 0.0 : shares.front(),
              shares.empty() ? 0.0 : shares[shares.size() / 2], lookFps.size(),
              lookFps.empty() ? 0.0 : *std::min_element(lookFps.begin(), lookFps.end()),
              pointerSent.size(), delivered, percentile(latencies, 0.5),
              percentile(latencies, 0.99), *std::max_element(latencies.begin(), latencies.end()));
    }
};

int main(int argc, char** argv) {
    // The lecture runs 10 minutes; QtTest stops a test function after 5 unless told.
    if (qEnvironmentVariableIsEmpty("QTEST_FUNCTION_TIMEOUT")) {
        qputenv("QTEST_FUNCTION_TIMEOUT", "1800000");
    }
    QCoreApplication app(argc, argv);
    BenchTeaching bench;
    return QTest::qExec(&bench, argc, argv);
}
#include "bench_teaching.moc"
