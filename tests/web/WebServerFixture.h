#pragma once
// For the web tests: a real lucent-server process on a free loopback port with
// its own temporary store and token file, started with any extra options
// (TLS), and small helpers for raw HTTP over a socket.

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QStandardPaths>
#include <QTcpSocket>
#include <QTemporaryDir>
#include <QTest>

#include "tests/server/RemoteTestFixture.h"

namespace lucent::test {

// A second token that cannot ride in a WebSocket subprotocol ('/', '=' are
// separators): the browser client sends it in the first message instead.
inline constexpr char kTokenNotASubprotocol[] = "b64/token+for=tests==";

class WebServerProcess {
public:
    // Starts lucent-server serving `data` (the synthetic CT when empty) with `extraArgs`.
    // started() is false (and startError() says why) when it did not come up.
    explicit WebServerProcess(const QStringList& extraArgs = {}, QString data = {},
                              quint16 port = 0) {
        if (!dir_.isValid()) {
            error_ = "no temporary directory";
            return;
        }
        if (data.isEmpty()) {
            data = dir_.filePath("ct.mhd");
            writeMetaImage(syntheticCt(), data.toStdString());
        }
        QFile tokens(dir_.filePath("tokens"));
        if (!tokens.open(QIODevice::WriteOnly)) {
            error_ = "cannot write the token file";
            return;
        }
        tokens.write(QByteArray("# test tokens\n") + kToken + "\n" + kTokenNotASubprotocol + "\n");
        tokens.close();
        process_.setProcessChannelMode(QProcess::SeparateChannels);
        process_.start(QString(LUCENT_BIN_DIR) + "/lucent-server",
                       QStringList{"--listen", QString("127.0.0.1:%1").arg(port), "--store",
                                   dir_.filePath("store"), "--data", data, "--token-file",
                                   dir_.filePath("tokens"), "--backend", "cpu"} +
                           extraArgs);
        QString out;
        (void)QTest::qWaitFor(
            [&] {
                out += QString::fromUtf8(process_.readAllStandardOutput());
                return out.contains("listening on") || process_.state() == QProcess::NotRunning;
            },
            60000);
        const qsizetype at = out.indexOf("listening on 127.0.0.1:");
        if (at < 0) {
            error_ = "server did not start: " + out + log();
            return;
        }
        port_ = quint16(out.mid(at + 23).trimmed().toUInt());
        output_ = out;
    }
    ~WebServerProcess() { stop(); }
    WebServerProcess(const WebServerProcess&) = delete;
    WebServerProcess& operator=(const WebServerProcess&) = delete;

    void stop() {
        if (process_.state() != QProcess::NotRunning) {
            process_.terminate();
            if (!process_.waitForFinished(10000)) {
                process_.kill();
                process_.waitForFinished();
            }
        }
    }
    bool started() const { return port_ > 0; }
    QString startError() const { return error_; }
    quint16 port() const { return port_; }
    QString dir() const { return dir_.path(); }
    QString output() const { return output_; }
    QString log() { return log_ += QString::fromUtf8(process_.readAllStandardError()); }

private:
    QTemporaryDir dir_;
    QProcess process_;
    quint16 port_ = 0;
    QString error_;
    QString output_;
    QString log_;
};

// Runs lucent-server to its end (for bad configurations): exit code and stderr.
struct ServerRun {
    int exitCode = -1;
    QString errors;
};
inline ServerRun runServerToEnd(const QStringList& args) {
    QProcess process;
    process.start(QString(LUCENT_BIN_DIR) + "/lucent-server", args);
    if (!process.waitForFinished(60000)) {
        process.kill();
        process.waitForFinished();
        return {-1, "did not end"};
    }
    return {process.exitCode(), QString::fromUtf8(process.readAllStandardError())};
}

// Sends raw bytes to the port and returns all that comes back until the
// server closes the connection (or the timeout).
inline QByteArray rawExchange(quint16 port, const QByteArray& request, int timeoutMs = 10000) {
    QTcpSocket socket;
    socket.connectToHost(QHostAddress::LocalHost, port);
    if (!socket.waitForConnected(timeoutMs)) {
        return {};
    }
    socket.write(request);
    QByteArray answer;
    (void)QTest::qWaitFor(
        [&] {
            answer += socket.readAll();
            return socket.state() == QAbstractSocket::UnconnectedState;
        },
        timeoutMs);
    return answer + socket.readAll();
}

// A self-signed certificate for 127.0.0.1 and its key, made with the openssl
// command in `dir`. Empty when openssl is missing or fails.
struct SelfSigned {
    QString certificate;
    QString key;
};
inline SelfSigned makeSelfSigned(const QString& dir, const QString& name = "server") {
    const QString openssl = QStandardPaths::findExecutable("openssl");
    if (openssl.isEmpty()) {
        return {};
    }
    SelfSigned files{QDir(dir).filePath(name + "-cert.pem"), QDir(dir).filePath(name + "-key.pem")};
    QProcess process;
    process.start(openssl, {"req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", files.key,
                            "-out", files.certificate, "-days", "2", "-subj", "/CN=localhost",
                            "-addext", "subjectAltName=IP:127.0.0.1,DNS:localhost"});
    if (!process.waitForFinished(60000) || process.exitCode() != 0) {
        return {};
    }
    return files;
}

} // namespace lucent::test
