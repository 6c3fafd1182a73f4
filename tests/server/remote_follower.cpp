// A follower in its own process, for the test that kills one:
//   remote_follower PORT TOKEN SESSION
// connects to lucent-server on 127.0.0.1:PORT, authenticates, joins the
// session, prints "joined" once it is a member, then prints "frame" for each
// frame until it is killed.
#include <QCoreApplication>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTextStream>
#include <QWebSocket>

int main(int argc, char** argv) {
    QCoreApplication app(argc, argv);
    const QStringList args = QCoreApplication::arguments();
    if (args.size() != 4) {
        QTextStream(stderr) << "usage: remote_follower PORT TOKEN SESSION\n";
        return 2;
    }
    QTextStream out(stdout);
    QWebSocket socket;
    const auto send = [&](const QJsonObject& m) {
        socket.sendTextMessage(QString::fromUtf8(QJsonDocument(m).toJson(QJsonDocument::Compact)));
    };
    QObject::connect(&socket, &QWebSocket::connected, [&] {
        send({{"type", "auth"}, {"token", args[2]}});
        send({{"type", "session-join"}, {"session", args[3]}});
    });
    QObject::connect(&socket, &QWebSocket::textMessageReceived, [&](const QString& text) {
        const QJsonObject m = QJsonDocument::fromJson(text.toUtf8()).object();
        if (m["type"] == "session-state") {
            out << "joined " << m["you"].toInteger() << Qt::endl;
        } else if (m["type"] == "error") {
            out << "error " << m["code"].toString() << Qt::endl;
        }
    });
    QObject::connect(&socket, &QWebSocket::binaryMessageReceived,
                     [&](const QByteArray&) { out << "frame" << Qt::endl; });
    QObject::connect(&socket, &QWebSocket::disconnected, &app, [] { QCoreApplication::exit(1); });
    socket.open(QUrl(QString("ws://127.0.0.1:%1/").arg(args[1])));
    return QCoreApplication::exec();
}
