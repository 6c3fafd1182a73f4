// Followers of a teaching session in one process, for bench_teaching:
//   teaching_followers PORT TOKEN SESSION COUNT FREE_LOOK ARRIVALS_FILE
// opens COUNT WebSocket connections to lucent-server on 127.0.0.1:PORT, each
// authenticates and joins SESSION; the first FREE_LOOK of them then look on
// their own (free look, a camera turn at most every 100 ms, one at a time).
// Prints "joined" once every connection has its first frame. Every `pointer`
// message is stamped on arrival (steady clock, which is the system's monotonic
// clock and so comparable between processes) and its number decoded from its
// position (bench_teaching's pointerPosition). On "report" on stdin it writes
// "ARRIVAL follower number ns" lines to ARRIVALS_FILE, prints
// "frames follower count free_look" for each connection and "done", and exits.
#include <QCoreApplication>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QNetworkRequest>
#include <QSocketNotifier>
#include <QTextStream>
#include <QTimer>
#include <QWebSocket>
#include <QWebSocketHandshakeOptions>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <unistd.h>
#include <vector>

#include "tests/perf/PointerCode.h"

namespace {

struct Follower {
    QWebSocket socket;
    int index = 0;
    bool freeLook = false;
    bool joined = false;
    bool lookWaiting = false; // a free-look camera turn awaits its frame
    long frames = 0;
    double azimuth = 0.0;
    std::vector<std::pair<int, long long>> arrivals; // pointer number, ns
};

long long nowNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

void send(QWebSocket& socket, const QJsonObject& message) {
    socket.sendTextMessage(
        QString::fromUtf8(QJsonDocument(message).toJson(QJsonDocument::Compact)));
}

} // namespace

int main(int argc, char** argv) {
    QCoreApplication app(argc, argv);
    const QStringList args = QCoreApplication::arguments();
    if (args.size() != 7) {
        QTextStream(stderr)
            << "usage: teaching_followers PORT TOKEN SESSION COUNT FREE_LOOK ARRIVALS_FILE\n";
        return 2;
    }
    const QString token = args[2], session = args[3];
    const int count = args[4].toInt(), freeLookCount = args[5].toInt();
    QTextStream out(stdout);
    std::vector<std::unique_ptr<Follower>> followers;
    int joined = 0;
    for (int n = 0; n < count; ++n) {
        auto follower = std::make_unique<Follower>();
        Follower* f = follower.get();
        f->index = n;
        f->freeLook = n < freeLookCount;
        QObject::connect(&f->socket, &QWebSocket::connected, [f, token, session] {
            send(f->socket, {{"type", "auth"}, {"token", token}});
            send(f->socket, {{"type", "session-join"}, {"session", session}});
        });
        QObject::connect(&f->socket, &QWebSocket::textMessageReceived, [f, &out](const QString& t) {
            const long long arrived = nowNs();
            const QJsonObject m = QJsonDocument::fromJson(t.toUtf8()).object();
            const QString type = m["type"].toString();
            if (type == "pointer" && m.contains("x")) {
                f->arrivals.emplace_back(
                    lucent::bench::pointerNumber(m["x"].toDouble(), m["y"].toDouble()), arrived);
            } else if (type == "error") {
                out << "error " << f->index << ' ' << m["code"].toString() << ' '
                    << m["message"].toString() << Qt::endl;
            }
        });
        QObject::connect(&f->socket, &QWebSocket::binaryMessageReceived,
                         [f, &joined, count, &out](const QByteArray&) {
                             ++f->frames;
                             f->lookWaiting = false;
                             if (!f->joined) {
                                 f->joined = true;
                                 if (f->freeLook) {
                                     send(f->socket, {{"type", "free-look"}, {"state", "start"}});
                                 }
                                 if (++joined == count) {
                                     out << "joined" << Qt::endl;
                                 }
                             }
                         });
        QObject::connect(&f->socket, &QWebSocket::disconnected, [f, &out] {
            out << "closed " << f->index << ' ' << f->socket.closeCode() << Qt::endl;
        });
        QWebSocketHandshakeOptions options;
        options.setSubprotocols({"lucent.v4"}); // free look and the pointer came with version 4
        f->socket.open(QNetworkRequest(QUrl(QString("ws://127.0.0.1:%1/").arg(args[1]))), options);
        followers.push_back(std::move(follower));
    }

    // Free lookers turn their own camera, one turn in flight each.
    QTimer look;
    QObject::connect(&look, &QTimer::timeout, [&followers] {
        for (auto& f : followers) {
            if (f->freeLook && f->joined && !f->lookWaiting) {
                f->azimuth += 4.0;
                f->lookWaiting = true;
                send(f->socket, {{"type", "camera"}, {"azimuth", f->azimuth}});
            }
        }
    });
    look.start(100);

    QSocketNotifier input(STDIN_FILENO, QSocketNotifier::Read);
    QObject::connect(&input, &QSocketNotifier::activated, [&] {
        char line[64] = {};
        if (::read(STDIN_FILENO, line, sizeof line - 1) <= 0 ||
            QByteArray(line).trimmed() == "report") {
            QFile file(args[6]);
            if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate)) {
                out << "error cannot write " << args[6] << Qt::endl;
                QCoreApplication::exit(1);
                return;
            }
            QTextStream arrivals(&file);
            for (const auto& f : followers) {
                for (const auto& [number, ns] : f->arrivals) {
                    arrivals << "ARRIVAL " << f->index << ' ' << number << ' ' << ns << '\n';
                }
                out << "frames " << f->index << ' ' << f->frames << ' ' << int(f->freeLook) << '\n';
            }
            out << "done" << Qt::endl;
            QCoreApplication::exit(0);
        }
    });
    return QCoreApplication::exec();
}
