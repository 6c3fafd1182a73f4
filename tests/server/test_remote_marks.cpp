// The presenter's pointer and marks on the real lucent-server (version 4), on the
// demo head CT: both followers get the pointer as sent and each mark anchored
// where the local surfacePoint finds the surface (on the skull), every frame
// carries its projection; followers cannot mark, older connections get none of
// it, the limit holds, marks-clear and a new open remove them, and a member who
// joins later gets the marks at once.
#include <QEventLoop>
#include <QJsonArray>
#include <QTest>
#include <QTimer>

#include <filesystem>
#include <map>

#include "DemoHead.h"
#include "RemoteTestFixture.h"
#include "core/formats/InVesaliusProject.h"
#include "core/raycast/SurfaceDepth.h"
#include "core/scene/ImageProjection.h"
#include "core/scene/ViewFrame.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSide = 128;
const QStringList kV4 = {"lucent.v4"};

// Creates a session showing the server's only series at kSide with ct-bone; its id.
QString startSession(RemoteTestClient& presenter, QString* uid) {
    if (!presenter.waitConnected() || !presenter.authenticate()) {
        return {};
    }
    presenter.send({{"type", "session-create"}});
    const QString id = presenter.waitForText("session-created")["session"].toString();
    *uid = openOnlySeries(presenter, kSide);
    return presenter.waitForText("opened").isEmpty() || uid->isEmpty() ? QString() : id;
}

bool join(RemoteTestClient& follower, const QString& session) {
    if (!follower.waitConnected() || !follower.authenticate()) {
        return false;
    }
    follower.send({{"type", "session-join"}, {"session", session}});
    return !follower.waitForText("opened").isEmpty();
}

// How many messages of this type the client has received.
int countOf(const RemoteTestClient& client, const QString& type) {
    return int(std::count_if(client.texts.cbegin(), client.texts.cend(),
                             [&](const QJsonObject& t) { return t["type"].toString() == type; }));
}

bool waitCount(const RemoteTestClient& client, const QString& type, int n, int ms = 30000) {
    return QTest::qWaitFor([&] { return countOf(client, type) >= n; }, ms);
}

QJsonObject lastOf(const RemoteTestClient& client, const QString& type) {
    for (auto it = client.texts.crbegin(); it != client.texts.crend(); ++it) {
        if ((*it)["type"].toString() == type) {
            return *it;
        }
    }
    return {};
}

QJsonObject arrow(double x0, double y0, double x1, double y1) {
    return {{"type", "mark"},
            {"kind", "arrow"},
            {"points", QJsonArray{QJsonArray{x0, y0}, QJsonArray{x1, y1}}}};
}

glm::dvec3 anchorAt(const QJsonObject& mark, int n) {
    const QJsonArray a = mark["anchors"].toArray()[n].toArray();
    return {a[0].toDouble(), a[1].toDouble(), a[2].toDouble()};
}

} // namespace

class TestRemoteMarks : public QObject {
    Q_OBJECT
    std::unique_ptr<Volume> head_;

private slots:
    void initTestCase() {
        if (!std::filesystem::exists(kDemoHead.toStdString())) {
            QSKIP(kDemoHeadMissing);
        }
        head_ = std::make_unique<Volume>(readInVesalius(kDemoHead.toStdString()));
    }

    void pointerAndMarksReachEveryFollowerOnTheSurface() {
        ServerProcess server("cpu", kDemoHead);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        RemoteTestClient presenter(server.port(), kV4);
        QString uid;
        const QString session = startSession(presenter, &uid);
        QVERIFY(!session.isEmpty());
        RemoteTestClient a(server.port(), kV4), b(server.port(), kV4);
        QVERIFY(join(a, session) && join(b, session));
        QVERIFY(presenter.waitForCurrentFrame());

        presenter.send({{"type", "pointer"}, {"x", 0.25}, {"y", 0.75}});
        for (RemoteTestClient* member : {&presenter, &a, &b}) {
            const QJsonObject p = member->waitForText("pointer");
            QCOMPARE(p["x"].toDouble(), 0.25);
            QCOMPARE(p["y"].toDouble(), 0.75);
        }
        presenter.send({{"type", "pointer"}});
        QVERIFY(waitCount(a, "pointer", 2));
        QVERIFY(!lastOf(a, "pointer").contains("x")); // hidden

        // An arrow whose tip is on the forehead, whose tail is beside the head.
        presenter.send(arrow(0.5, 0.4, 0.97, 0.03));
        const QJsonObject ma = a.waitForText("mark"), mb = b.waitForText("mark");
        QCOMPARE(ma, mb);
        QCOMPARE(ma["kind"].toString(), "arrow");
        QCOMPARE(ma["anchors"].toArray().size(), 2);
        const RenderDescription d = referenceDescription(*head_, Camera{}, kSide);
        const std::vector<glm::dvec3> expected = surfaceAnchors(d, {{0.5, 0.4}, {0.97, 0.03}});
        for (int n = 0; n < 2; ++n) {
            QVERIFY2(glm::length(anchorAt(ma, n) - expected[std::size_t(n)]) < 1e-6,
                     qPrintable(QString("anchor %1 is %2 mm from the local one")
                                    .arg(n)
                                    .arg(glm::length(anchorAt(ma, n) - expected[std::size_t(n)]))));
        }
        QVERIFY(surfacePoint(d, {0.5, 0.4}));    // the tip has a surface:
        QVERIFY(!surfacePoint(d, {0.97, 0.03})); // the tail has none
        QVERIFY2(maxValueNear(*head_, anchorAt(ma, 0), 2.0) > 300.0, "the tip is not on bone");
        // The tail lies on the plane facing the viewer at the tip's depth.
        const ViewFrame frame = makeViewFrame(head_->geometry(), d.camera, kSide, kSide);
        QVERIFY(std::abs(glm::dot(anchorAt(ma, 1) - anchorAt(ma, 0), frame.forward)) < 1e-6);

        // Every frame carries the projection of its view.
        const ReceivedFrame* f = presenter.waitForCurrentFrame();
        QVERIFY(f && f->header.projection);
        const ImageProjection expectedProjection = imageProjection(frame);
        for (std::size_t n = 0; n < 12; ++n) {
            QVERIFY(std::abs((*f->header.projection)[n] - expectedProjection[n]) < 1e-9);
        }
        const auto tip = projectToImage(*f->header.projection, anchorAt(ma, 0));
        QVERIFY(tip && glm::length(*tip - glm::dvec2(0.5, 0.4)) * kSide < 1e-3);
    }

    void onlyThePresenterMarksAndOldConnectionsGetNone() {
        ServerProcess server("cpu", kDemoHead);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        RemoteTestClient presenter(server.port(), kV4);
        QString uid;
        const QString session = startSession(presenter, &uid);
        QVERIFY(!session.isEmpty());
        RemoteTestClient follower(server.port(), kV4), old(server.port(), {"lucent.v3"});
        QVERIFY(join(follower, session) && join(old, session));

        for (const QJsonObject& m :
             {QJsonObject{{"type", "pointer"}, {"x", 0.5}, {"y", 0.5}}, arrow(0.1, 0.1, 0.2, 0.2),
              QJsonObject{{"type", "marks-clear"}}}) {
            const qsizetype from = follower.texts.size();
            follower.send(m);
            const QJsonObject refused = follower.waitForText("error", 20000, from);
            QCOMPARE(refused["code"].toString(), "not-presenter");
            QVERIFY(!refused["fatal"].toBool());
        }
        // A follower by invite may only follow: forbidden.
        presenter.send({{"type", "invite-create"}});
        const QString code = presenter.waitForText("invite-created")["code"].toString();
        RemoteTestClient invited(server.port(), {"lucent.v4", "lucent.invite." + code});
        QVERIFY(!invited.waitForText("opened").isEmpty());
        invited.send(arrow(0.1, 0.1, 0.2, 0.2));
        QCOMPARE(invited.waitForText("error")["code"].toString(), "forbidden");
        // Refusals name the field; nothing is placed.
        qsizetype from = presenter.texts.size();
        presenter.send({{"type", "mark"}, {"kind", "circle"}, {"points", QJsonArray{}}});
        QVERIFY(presenter.waitForText("error", 20000, from)["message"].toString().contains(
            "mark: 'points'"));

        // The limit: 64 marks a view (those being anchored count).
        for (int n = 0; n < 64; ++n) {
            presenter.send(arrow(0.5, 0.3 + n * 0.001, 0.6, 0.2));
        }
        from = presenter.texts.size();
        presenter.send(arrow(0.5, 0.3, 0.6, 0.2));
        const QJsonObject limit = presenter.waitForText("error", 20000, from);
        QCOMPARE(limit["code"].toString(), "mark-limit");
        QVERIFY(waitCount(follower, "mark", 64, 60000));
        QCOMPARE(lastOf(follower, "mark")["id"].toInteger(), 64);

        // A version 3 follower is sent none of it, and may not send it.
        presenter.send({{"type", "pointer"}, {"x", 0.5}, {"y", 0.5}});
        QVERIFY(waitCount(follower, "pointer", 1));
        QCOMPARE(countOf(old, "pointer") + countOf(old, "mark"), 0);
        old.send({{"type", "pointer"}, {"x", 0.5}, {"y", 0.5}});
        QCOMPARE(old.waitForText("error")["code"].toString(), "unknown-type");
        QVERIFY(old.waitDisconnected());
    }

    // The pointer costs no render-thread work: 10 followers get 100 pointer updates
    // (30 a second) within a loose bound; p50 and p99 are printed for the record.
    void thePointerIsRelayedAtOnce() {
        ServerProcess server("cpu", kDemoHead);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        RemoteTestClient presenter(server.port(), kV4);
        QString uid;
        const QString session = startSession(presenter, &uid);
        QVERIFY(!session.isEmpty());
        QElapsedTimer clock;
        clock.start();
        constexpr int kFollowers = 10, kUpdates = 100;
        std::vector<std::unique_ptr<QWebSocket>> followers;
        std::vector<std::map<int, qint64>> arrived(kFollowers); // update -> ns
        for (int f = 0; f < kFollowers; ++f) {
            auto socket = std::make_unique<QWebSocket>();
            QObject::connect(
                socket.get(), &QWebSocket::textMessageReceived,
                [&clock, &arrived, f](const QString& text) {
                    const QJsonObject m = QJsonDocument::fromJson(text.toUtf8()).object();
                    if (m["type"].toString() == "pointer" && m.contains("x")) {
                        arrived[std::size_t(f)][int(std::lround(m["x"].toDouble() * 1000))] =
                            clock.nsecsElapsed();
                    }
                });
            QWebSocketHandshakeOptions options;
            options.setSubprotocols({"lucent.v4", QString("lucent.token.") + kToken});
            socket->open(QNetworkRequest(QUrl(QString("ws://127.0.0.1:%1/").arg(server.port()))),
                         options);
            QVERIFY(QTest::qWaitFor(
                [&] { return socket->state() == QAbstractSocket::ConnectedState; }, 10000));
            socket->sendTextMessage(
                QString(R"({"type":"session-join","session":"%1"})").arg(session));
            followers.push_back(std::move(socket));
        }
        QTest::qWait(1000); // all joined
        std::vector<qint64> sent(kUpdates);
        for (int n = 0; n < kUpdates; ++n) {
            sent[std::size_t(n)] = clock.nsecsElapsed();
            presenter.send({{"type", "pointer"}, {"x", (n + 1) / 1000.0}, {"y", 0.5}});
            // An event loop that wakes on each arrival (qWait polls in 10 ms slices).
            QEventLoop wait;
            QTimer::singleShot(33, &wait, &QEventLoop::quit);
            wait.exec();
        }
        QVERIFY(QTest::qWaitFor(
            [&] {
                return std::all_of(arrived.cbegin(), arrived.cend(),
                                   [](const auto& a) { return a.size() >= std::size_t(kUpdates); });
            },
            20000));
        std::vector<double> ms;
        for (const auto& a : arrived) {
            for (const auto& [n, at] : a) {
                ms.push_back(double(at - sent[std::size_t(n - 1)]) / 1e6);
            }
        }
        std::sort(ms.begin(), ms.end());
        const double p50 = ms[ms.size() / 2], p99 = ms[ms.size() * 99 / 100];
        qInfo(
            "pointer presenter -> %d followers, %d updates: p50 %.2f ms, p99 %.2f ms, max %.2f ms",
            kFollowers, kUpdates, p50, p99, ms.back());
        // Loopback on a shared machine: far above the 50 ms goal, only a gross regression fails.
        QVERIFY2(p99 < 250.0, qPrintable(QString("p99 %1 ms").arg(p99)));
    }

    void clearNewSeriesAndLateJoiners() {
        ServerProcess server("cpu", kDemoHead);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        RemoteTestClient presenter(server.port(), kV4);
        QString uid;
        const QString session = startSession(presenter, &uid);
        QVERIFY(!session.isEmpty());
        presenter.send(arrow(0.5, 0.3, 0.6, 0.2));
        presenter.send({{"type", "mark"},
                        {"kind", "text"},
                        {"points", QJsonArray{QJsonArray{0.45, 0.5}}},
                        {"text", "Orbit"}});
        presenter.send({{"type", "pointer"}, {"x", 0.3}, {"y", 0.4}});
        QVERIFY(waitCount(presenter, "mark", 2));

        // A member who joins later gets both marks and the pointer at once.
        RemoteTestClient late(server.port(), kV4);
        QVERIFY(join(late, session));
        QVERIFY(waitCount(late, "mark", 2));
        QVERIFY(waitCount(late, "pointer", 1));
        QCOMPARE(lastOf(late, "mark")["text"].toString(), "Orbit");
        QCOMPARE(lastOf(late, "mark")["anchors"].toArray().size(), 1);

        // Control passes on: the marks stay, the last presenter's pointer goes.
        const int pointers = countOf(late, "pointer");
        const QJsonObject lateState = lastOf(late, "session-state");
        presenter.send({{"type", "session-handover"}, {"to", lateState["you"]}});
        QVERIFY(waitCount(late, "pointer", pointers + 1));
        QVERIFY(!lastOf(late, "pointer").contains("x"));
        late.send(
            {{"type", "session-handover"}, {"to", lastOf(presenter, "session-state")["you"]}});
        QVERIFY(QTest::qWaitFor(
            [&] { return lastOf(presenter, "session-state")["role"].toString() == "presenter"; },
            20000));
        QCOMPARE(countOf(late, "marks-cleared"), 0);

        presenter.send({{"type", "marks-clear"}});
        QVERIFY(!late.waitForText("marks-cleared").isEmpty());
        QVERIFY(!presenter.waitForText("marks-cleared").isEmpty());
        RemoteTestClient later(server.port(), kV4);
        QVERIFY(join(later, session));
        QVERIFY(later.waitForCurrentFrame(60000) || !later.frames.isEmpty());
        QCOMPARE(countOf(later, "mark"), 0);

        // Opening a series again removes the marks it had.
        presenter.send(arrow(0.5, 0.3, 0.6, 0.2));
        QVERIFY(waitCount(later, "mark", 1));
        const int cleared = countOf(later, "marks-cleared");
        presenter.send({{"type", "open"}, {"series", uid}});
        QVERIFY(waitCount(later, "marks-cleared", cleared + 1));
    }
};

QTEST_GUILESS_MAIN(TestRemoteMarks)
#include "test_remote_marks.moc"
