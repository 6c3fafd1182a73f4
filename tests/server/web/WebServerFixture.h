#pragma once
// For the web tests: lucent-server runs to its end, raw HTTP over a socket, a
// self-signed certificate (the server process: tests/support/ServerProcess.h).

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QStandardPaths>
#include <QTcpSocket>
#include <QTemporaryDir>
#include <QTest>

#include "tests/server/RemoteTestFixture.h"

namespace lucent::test {

// Runs lucent-server to its end (for bad configurations): exit code and stderr.
struct ServerExit {
    int exitCode = -1;
    QString errors;
};
inline ServerExit runServerToEnd(const QStringList& args) {
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
