// The server's front door on a real lucent-server: the browser client's files
// over HTTP, refusals (404, 405, 400, 431), and WebSocket clients on the same
// port; plus the request-head parser on its own.
#include <QNetworkAccessManager>
#include <QNetworkReply>
#include <QRegularExpression>
#include <QTest>

#include "WebServerFixture.h"
#include "server/HttpFrontDoor.h"

using namespace lucent;
using namespace lucent::test;

namespace {

struct HttpAnswer {
    int status = 0;
    QByteArray contentType;
    QByteArray body;
    QNetworkReply::NetworkError error = QNetworkReply::NoError;
    QList<QNetworkReply::RawHeaderPair> fields;
};

HttpAnswer fetch(QNetworkAccessManager& manager, const QNetworkRequest& request,
                 const QByteArray& verb = "GET") {
    QNetworkReply* reply = manager.sendCustomRequest(request, verb);
    (void)QTest::qWaitFor([reply] { return reply->isFinished(); }, 20000);
    HttpAnswer answer;
    answer.status = reply->attribute(QNetworkRequest::HttpStatusCodeAttribute).toInt();
    answer.contentType = reply->rawHeader("Content-Type");
    answer.body = reply->readAll();
    answer.error = reply->error();
    answer.fields = reply->rawHeaderPairs();
    reply->deleteLater();
    return answer;
}

QNetworkRequest requestFor(quint16 port, const QString& path) {
    return QNetworkRequest(QUrl(QString("http://127.0.0.1:%1%2").arg(port).arg(path)));
}

} // namespace

class TestWebHttp : public QObject {
    Q_OBJECT
private slots:
    void parsesRequestHeads();
    void servesTheClientFiles();
    void refusesWhatItDoesNotServe();
    void refusesOversizedAndMalformedHeads();
    void webSocketsShareThePort();
    void aSlowClientDoesNotBlockOthers();
    void idleConnectionsAreBounded();
};

void TestWebHttp::parsesRequestHeads() {
    const auto upgrade = remote::parseHttpRequestHead(
        "GET /ws?x=1 HTTP/1.1\r\nHost: a\r\nConnection: Upgrade\r\nUpgrade: WebSocket\r\n\r\n");
    QVERIFY(upgrade);
    QCOMPARE(upgrade->method, QByteArray("GET"));
    QCOMPARE(upgrade->target, QByteArray("/ws?x=1"));
    QCOMPARE(upgrade->field("host"), QByteArray("a"));
    QVERIFY(upgrade->isWebSocketUpgrade());
    const auto plain = remote::parseHttpRequestHead("GET / HTTP/1.0\r\n\r\n");
    QVERIFY(plain);
    QVERIFY(!plain->isWebSocketUpgrade());
    QVERIFY(remote::parseHttpRequestHead("GET / HTTP/1.1\r\nUpgrade: h2c\r\n\r\n"));
    QVERIFY(!remote::parseHttpRequestHead("GET / HTTP/1.1\r\nUpgrade: h2c\r\n\r\n")
                 ->isWebSocketUpgrade());
    // Not HTTP/1.x, no origin-form target, folded or nameless fields, no end.
    QVERIFY(!remote::parseHttpRequestHead("PRI * HTTP/2.0\r\n\r\n"));
    QVERIFY(!remote::parseHttpRequestHead("GET http://x/ HTTP/1.1\r\n\r\n"));
    QVERIFY(!remote::parseHttpRequestHead("GET / HTTP/1.1\r\nA: b\r\n folded\r\n\r\n"));
    QVERIFY(!remote::parseHttpRequestHead("GET / HTTP/1.1\r\n: b\r\n\r\n"));
    QVERIFY(!remote::parseHttpRequestHead("get / HTTP/1.1\r\n\r\n"));
    QVERIFY(!remote::parseHttpRequestHead("GET / HTTP/1.1\r\n"));
    QVERIFY(!remote::parseHttpRequestHead("\x16\x03\x01 x\r\n\r\n"));
}

void TestWebHttp::servesTheClientFiles() {
    ServerProcess server;
    QVERIFY2(server.started(), qPrintable(server.startError()));
    QNetworkAccessManager manager;

    const HttpAnswer page = fetch(manager, requestFor(server.port(), "/"));
    QCOMPARE(page.status, 200);
    QCOMPARE(page.contentType, QByteArray("text/html; charset=utf-8"));
    QVERIFY(page.body.contains("<canvas id=\"view\""));
    QVERIFY(page.body.contains("name=\"viewport\""));
    bool hasPolicy = false;
    for (const auto& [name, value] : page.fields) {
        hasPolicy |= name.toLower() == "content-security-policy" && value.contains("'self'");
    }
    QVERIFY(hasPolicy);
    QCOMPARE(fetch(manager, requestFor(server.port(), "/index.html")).body, page.body);

    const HttpAnswer script = fetch(manager, requestFor(server.port(), "/app.js?v=2"));
    QCOMPARE(script.status, 200);
    QCOMPARE(script.contentType, QByteArray("text/javascript; charset=utf-8"));
    QVERIFY(script.body.contains("createLucentConnection"));
    // Every script the page names is served (the client's files are embedded one by one).
    auto scripts = QRegularExpression(R"re(<script src="([a-z]+\.js)">)re")
                       .globalMatch(QString::fromUtf8(page.body));
    QStringList served;
    while (scripts.hasNext()) {
        const QString name = scripts.next().captured(1);
        const HttpAnswer file = fetch(manager, requestFor(server.port(), "/" + name));
        QVERIFY2(file.status == 200 && file.body.contains("\"use strict\";"), qPrintable(name));
        QCOMPARE(file.contentType, QByteArray("text/javascript; charset=utf-8"));
        served << name;
    }
    QVERIFY2(served.contains("connection.js") && served.contains("sessions.js") &&
                 served.last() == "app.js",
             qPrintable(served.join(", ")));
    QVERIFY(fetch(manager, requestFor(server.port(), "/connection.js")).body.contains("WebSocket"));
    const HttpAnswer style = fetch(manager, requestFor(server.port(), "/style.css"));
    QCOMPARE(style.status, 200);
    QCOMPARE(style.contentType, QByteArray("text/css; charset=utf-8"));

    const HttpAnswer head = fetch(manager, requestFor(server.port(), "/"), "HEAD");
    QCOMPARE(head.status, 200);
    QVERIFY(head.body.isEmpty());
}

void TestWebHttp::refusesWhatItDoesNotServe() {
    ServerProcess server;
    QVERIFY2(server.started(), qPrintable(server.startError()));
    QNetworkAccessManager manager;
    QCOMPARE(fetch(manager, requestFor(server.port(), "/missing.js")).status, 404);
    QCOMPARE(fetch(manager, requestFor(server.port(), "/web/app.js")).status, 404);
    const HttpAnswer post = fetch(manager, requestFor(server.port(), "/"), "POST");
    QCOMPARE(post.status, 405);
    bool allows = false;
    for (const auto& [name, value] : post.fields) {
        allows |= name.toLower() == "allow" && value == "GET, HEAD";
    }
    QVERIFY(allows);
    // Paths that try to leave the client's folder, sent raw (clients would normalise them).
    for (const QByteArray path :
         {"/../CMakeLists.txt", "/%2e%2e/x", "/.hidden", "/a/b.js", "/app.js/", "//etc/passwd"}) {
        const QByteArray answer =
            rawExchange(server.port(), "GET " + path + " HTTP/1.1\r\nHost: x\r\n\r\n");
        QVERIFY2(answer.startsWith("HTTP/1.1 404 "), path.constData());
    }
}

void TestWebHttp::refusesOversizedAndMalformedHeads() {
    ServerProcess server;
    QVERIFY2(server.started(), qPrintable(server.startError()));
    const QByteArray huge =
        "GET / HTTP/1.1\r\nX-Filler: " + QByteArray(remote::kMaxRequestHeadBytes + 100, 'a') +
        "\r\n\r\n";
    QVERIFY(rawExchange(server.port(), huge).startsWith("HTTP/1.1 431 "));
    QVERIFY(rawExchange(server.port(), "HELLO\r\n\r\n").startsWith("HTTP/1.1 400 "));
    QVERIFY(
        rawExchange(server.port(), "PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n").startsWith("HTTP/1.1 400 "));
    // The server still serves afterwards.
    QVERIFY(rawExchange(server.port(), "GET / HTTP/1.1\r\n\r\n").startsWith("HTTP/1.1 200 "));
}

void TestWebHttp::webSocketsShareThePort() {
    ServerProcess server;
    QVERIFY2(server.started(), qPrintable(server.startError()));
    RemoteTestClient client(server.port());
    QVERIFY(client.waitConnected());
    QVERIFY(client.authenticate());
    client.send({{"type", "list"}});
    QVERIFY(!client.waitForText("series").isEmpty());
    // A wrong token is still refused through the front door.
    RemoteTestClient intruder(server.port());
    QVERIFY(intruder.waitConnected());
    intruder.send({{"type", "auth"}, {"token", "wrong"}});
    QCOMPARE(intruder.waitForText("error")["code"].toString(), QString("auth-failed"));
    QVERIFY(intruder.waitDisconnected());
    // HTTP goes on beside a WebSocket.
    QNetworkAccessManager manager;
    QCOMPARE(fetch(manager, requestFor(server.port(), "/")).status, 200);
}

void TestWebHttp::aSlowClientDoesNotBlockOthers() {
    ServerProcess server;
    QVERIFY2(server.started(), qPrintable(server.startError()));
    QTcpSocket slow;
    slow.connectToHost(QHostAddress::LocalHost, server.port());
    QVERIFY(slow.waitForConnected(5000));
    slow.write("GET / HT");
    QVERIFY(slow.waitForBytesWritten(5000));
    QNetworkAccessManager manager;
    QCOMPARE(fetch(manager, requestFor(server.port(), "/")).status, 200);
    RemoteTestClient client(server.port());
    QVERIFY(client.waitConnected());
    QVERIFY(client.authenticate());
    // The rest of the slow request still gets its page.
    slow.write("TP/1.1\r\n\r\n");
    QByteArray answer;
    QVERIFY(QTest::qWaitFor(
        [&] {
            answer += slow.readAll();
            return answer.contains("</html>");
        },
        10000));
    QVERIFY(answer.startsWith("HTTP/1.1 200 "));
}

void TestWebHttp::idleConnectionsAreBounded() {
    ServerProcess server;
    QVERIFY2(server.started(), qPrintable(server.startError()));
    std::vector<std::unique_ptr<QTcpSocket>> idle;
    for (int n = 0; n < remote::kMaxConnectionsWaitingForHead; ++n) {
        idle.push_back(std::make_unique<QTcpSocket>());
        idle.back()->connectToHost(QHostAddress::LocalHost, server.port());
        QVERIFY(idle.back()->waitForConnected(5000));
    }
    // The server has accepted them all (each holds a place) before the next one comes.
    QTest::qWait(500);
    // One more waiting connection is closed at once, with no answer.
    QElapsedTimer clock;
    clock.start();
    QCOMPARE(rawExchange(server.port(), "GET / HTTP/1.1\r\n\r\n", 5000), QByteArray());
    QVERIFY2(clock.elapsed() < 4000, "the extra connection was not closed at once");
    // Once the idle ones go, pages are served again.
    idle.clear();
    QVERIFY(QTest::qWaitFor(
        [&] {
            return rawExchange(server.port(), "GET / HTTP/1.1\r\n\r\n").startsWith("HTTP/1.1 200 ");
        },
        10000));
}

QTEST_GUILESS_MAIN(TestWebHttp)
#include "test_web_http.moc"
