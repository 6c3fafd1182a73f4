// lucent-server with --tls-cert/--tls-key: wss:// and https:// on one port with
// a self-signed certificate made by the openssl command; plain clients fail
// cleanly; unreadable, unparsable and mismatched files get a clear error.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QNetworkAccessManager>
#include <QNetworkReply>
#include <QSslConfiguration>
#include <QSslSocket>
#include <QTest>
#include <QWebSocket>

#include "WebServerFixture.h"

using namespace lucent;
using namespace lucent::test;

namespace {

QSslConfiguration trusting(const QString& certificateFile) {
    QSslConfiguration configuration = QSslConfiguration::defaultConfiguration();
    configuration.setCaCertificates(QSslCertificate::fromPath(certificateFile));
    return configuration;
}

// A wss:// client that trusts only the test's certificate.
class SecureClient {
public:
    SecureClient(quint16 port, const QSslConfiguration& configuration, const QString& scheme) {
        socket_.setSslConfiguration(configuration);
        QObject::connect(&socket_, &QWebSocket::textMessageReceived, [this](const QString& t) {
            texts.append(QJsonDocument::fromJson(t.toUtf8()).object());
        });
        QObject::connect(&socket_, &QWebSocket::binaryMessageReceived,
                         [this](const QByteArray& b) { frames.append(b); });
        QObject::connect(&socket_, &QWebSocket::disconnected, [this] { disconnected = true; });
        QObject::connect(&socket_, qOverload<QAbstractSocket::SocketError>(&QWebSocket::error),
                         [this](QAbstractSocket::SocketError) { failed = true; });
        socket_.open(QUrl(QString("%1://127.0.0.1:%2/").arg(scheme).arg(port)));
    }
    bool waitConnected() {
        return QTest::qWaitFor(
                   [this] {
                       return socket_.state() == QAbstractSocket::ConnectedState || failed ||
                              disconnected;
                   },
                   15000) &&
               !failed && !disconnected;
    }
    void send(const QJsonObject& message) {
        socket_.sendTextMessage(QJsonDocument(message).toJson(QJsonDocument::Compact));
    }
    QJsonObject waitForText(const QString& type) {
        QJsonObject found;
        (void)QTest::qWaitFor(
            [&] {
                for (const QJsonObject& t : std::as_const(texts)) {
                    if (t["type"].toString() == type) {
                        found = t;
                        return true;
                    }
                }
                return false;
            },
            30000);
        return found;
    }

    QList<QJsonObject> texts;
    QList<QByteArray> frames;
    bool disconnected = false;
    bool failed = false;

private:
    QWebSocket socket_;
};

} // namespace

class TestWebTls : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void wssAndHttpsOnOnePort();
    void plainClientsFailCleanly();
    void badFilesGetClearErrors();

private:
    QTemporaryDir dir_;
    SelfSigned files_;
};

void TestWebTls::initTestCase() {
    if (!QSslSocket::supportsSsl()) {
        QSKIP("Qt has no TLS backend here");
    }
    QVERIFY(dir_.isValid());
    files_ = makeSelfSigned(dir_.path());
    if (files_.certificate.isEmpty()) {
        QSKIP("the openssl command is missing or failed; cannot make a test certificate");
    }
}

void TestWebTls::wssAndHttpsOnOnePort() {
    ServerProcess server("cpu", {}, {"--tls-cert", files_.certificate, "--tls-key", files_.key});
    QVERIFY2(server.started(), qPrintable(server.startError()));
    QVERIFY(server.startupOutput().contains("browser client at https://127.0.0.1:"));

    SecureClient client(server.port(), trusting(files_.certificate), "wss");
    QVERIFY(client.waitConnected());
    client.send({{"type", "auth"}, {"token", kToken}});
    QVERIFY(!client.waitForText("hello").isEmpty());
    client.send({{"type", "list"}});
    const QJsonArray series = client.waitForText("series")["series"].toArray();
    QCOMPARE(series.size(), 1);
    client.send({{"type", "open"}, {"series", series[0].toObject()["uid"].toString()}});
    client.send({{"type", "size"}, {"width", 64}, {"height", 64}});
    QVERIFY(QTest::qWaitFor([&] { return !client.frames.isEmpty(); }, 60000));
    const auto frame = remote::parseFrameMessage(std::string_view(
        client.frames.back().constData(), std::size_t(client.frames.back().size())));
    QVERIFY(!frame.image.empty());

    QNetworkAccessManager manager;
    QNetworkRequest request(QUrl(QString("https://127.0.0.1:%1/").arg(server.port())));
    request.setSslConfiguration(trusting(files_.certificate));
    QNetworkReply* reply = manager.get(request);
    QVERIFY(QTest::qWaitFor([reply] { return reply->isFinished(); }, 20000));
    QCOMPARE(reply->error(), QNetworkReply::NoError);
    QCOMPARE(reply->attribute(QNetworkRequest::HttpStatusCodeAttribute).toInt(), 200);
    QVERIFY(reply->readAll().contains("<canvas"));
    reply->deleteLater();

    // Without the certificate trusted the client refuses the server.
    SecureClient untrusting(server.port(), QSslConfiguration::defaultConfiguration(), "wss");
    QVERIFY(!untrusting.waitConnected());
}

void TestWebTls::plainClientsFailCleanly() {
    ServerProcess server("cpu", {}, {"--tls-cert", files_.certificate, "--tls-key", files_.key});
    QVERIFY2(server.started(), qPrintable(server.startError()));
    SecureClient plain(server.port(), QSslConfiguration::defaultConfiguration(), "ws");
    QVERIFY(!plain.waitConnected());
    QVERIFY(plain.texts.isEmpty());
    // A plain HTTP request gets no page (no HTTP answer in the clear).
    const QByteArray answer = rawExchange(server.port(), "GET / HTTP/1.1\r\nHost: x\r\n\r\n");
    QVERIFY(!answer.startsWith("HTTP/1.1"));
    // The server still serves secure clients.
    SecureClient client(server.port(), trusting(files_.certificate), "wss");
    QVERIFY(client.waitConnected());
    client.send({{"type", "auth"}, {"token", kToken}});
    QVERIFY(!client.waitForText("hello").isEmpty());
}

void TestWebTls::badFilesGetClearErrors() {
    const QString base = dir_.path();
    const QStringList common{"--listen",      "127.0.0.1:0",  "--store",
                             base + "/store", "--token-file", base + "/none"};
    // Half a pair is a usage error.
    ServerExit run = runServerToEnd(common + QStringList{"--tls-cert", files_.certificate});
    QCOMPARE(run.exitCode, 2);
    QVERIFY2(run.errors.contains("--tls-cert FILE and --tls-key FILE"), qPrintable(run.errors));
    // A file that is not there.
    run = runServerToEnd(common +
                         QStringList{"--tls-cert", base + "/missing.pem", "--tls-key", files_.key});
    QCOMPARE(run.exitCode, 3);
    QVERIFY2(run.errors.contains("TLS certificate " + base + "/missing.pem cannot be read"),
             qPrintable(run.errors));
    // A key file that holds a certificate, and a certificate file that holds a key.
    run = runServerToEnd(
        common + QStringList{"--tls-cert", files_.certificate, "--tls-key", files_.certificate});
    QCOMPARE(run.exitCode, 3);
    QVERIFY2(run.errors.contains("TLS key " + files_.certificate + " holds no"),
             qPrintable(run.errors));
    run = runServerToEnd(common + QStringList{"--tls-cert", files_.key, "--tls-key", files_.key});
    QCOMPARE(run.exitCode, 3);
    QVERIFY2(run.errors.contains("TLS certificate " + files_.key + " holds no PEM certificate"),
             qPrintable(run.errors));
    // A key of another certificate.
    const SelfSigned other = makeSelfSigned(base, "other");
    QVERIFY(!other.key.isEmpty());
    run = runServerToEnd(common +
                         QStringList{"--tls-cert", files_.certificate, "--tls-key", other.key});
    QCOMPARE(run.exitCode, 3);
    QVERIFY2(run.errors.contains("TLS key " + other.key + " does not match certificate " +
                                 files_.certificate),
             qPrintable(run.errors));
}

QTEST_GUILESS_MAIN(TestWebTls)
#include "test_web_tls.moc"
