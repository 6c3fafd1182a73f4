// The server's store fed by upload: POST /studies on the front door
// (application/dicom or multipart/related) with a bearer token, real CT; the
// refusals (401, 413, 415, 400) leave nothing in the store; bodies are
// spooled to the store's tmp/ as they arrive and removed after.
#include <QDirIterator>
#include <QEventLoop>
#include <QJsonArray>
#include <QNetworkAccessManager>
#include <QNetworkReply>
#include <QTcpSocket>
#include <QTest>
#include <QTimer>

#include "RemoteTestFixture.h"
#include "core/io/Catalog.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr char kBoundary[] = "lucent-upload-boundary-7f3a";

QString seriesDir() {
    return QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";
}

struct Answer {
    int status = 0;
    QByteArray body;
};

Answer post(quint16 port, const QByteArray& token, const QByteArray& contentType,
            const QByteArray& body) {
    QNetworkAccessManager manager;
    QNetworkRequest request(QUrl(QString("http://127.0.0.1:%1/studies").arg(port)));
    request.setHeader(QNetworkRequest::ContentTypeHeader, contentType);
    if (!token.isNull()) {
        request.setRawHeader("Authorization", "Bearer " + token);
    }
    QNetworkReply* reply = manager.post(request, body);
    QEventLoop loop;
    QObject::connect(reply, &QNetworkReply::finished, &loop, &QEventLoop::quit);
    QTimer::singleShot(120000, &loop, &QEventLoop::quit);
    loop.exec();
    Answer answer{reply->attribute(QNetworkRequest::HttpStatusCodeAttribute).toInt(),
                  reply->readAll()};
    reply->deleteLater();
    return answer;
}

QByteArray multipart(const QList<QByteArray>& parts) {
    QByteArray body;
    for (const QByteArray& part : parts) {
        body += QByteArray("--") + kBoundary + "\r\nContent-Type: application/dicom\r\n\r\n" +
                part + "\r\n";
    }
    return body + "--" + kBoundary + "--\r\n";
}

QByteArray multipartType() {
    return QByteArray("multipart/related; type=\"application/dicom\"; boundary=") + kBoundary;
}

QByteArray readFile(const QString& path) {
    QFile file(path);
    return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray();
}

int filesIn(const QString& dir) {
    int count = 0;
    for (QDirIterator it(dir, QDir::Files, QDirIterator::Subdirectories); it.hasNext(); it.next()) {
        ++count;
    }
    return count;
}

QJsonArray list(RemoteTestClient& client) {
    const qsizetype from = client.texts.size();
    client.send({{"type", "list"}});
    return client.waitForText("series", 20000, from)["series"].toArray();
}

} // namespace

class TestRemoteUpload : public QObject {
    Q_OBJECT

private slots:
    void refusalsLeaveNothingInTheStore() {
        if (!QFileInfo::exists(seriesDir())) {
            QSKIP("no test data (dcm_qa_ct)");
        }
        ServerProcess server("cpu");
        QVERIFY(server.port());
        const QByteArray dicom = readFile(seriesDir() + "/I10");
        QVERIFY(dicom.size() > 132);

        Answer a = post(server.port(), QByteArray(), "application/dicom", dicom);
        QCOMPARE(a.status, 401);
        QVERIFY2(a.body.contains("Authorization: Bearer"), a.body.constData());
        a = post(server.port(), "wrong-token", "application/dicom", dicom);
        QCOMPARE(a.status, 401);
        QVERIFY2(a.body.contains("not accepted"), a.body.constData());

        a = post(server.port(), kToken, "text/plain", dicom);
        QCOMPARE(a.status, 415);
        QVERIFY2(a.body.contains("text/plain"), a.body.constData());

        a = post(server.port(), kToken, "application/dicom", QByteArray(4000, 'x'));
        QCOMPARE(a.status, 400);
        QVERIFY2(a.body.contains("DICM"), a.body.constData());

        // A good part and a bad one: nothing of either is stored.
        QByteArray noUid = dicom;
        const qsizetype sop = noUid.indexOf(QByteArray("\x08\x00\x18\x00UI", 6));
        QVERIFY(sop > 0);
        noUid[sop + 2] = '\x19'; // (0008,0019): the SOP Instance UID is gone
        a = post(server.port(), kToken, multipartType(), multipart({dicom, noUid}));
        QCOMPARE(a.status, 400);
        QVERIFY2(a.body.contains("part 2") && a.body.contains("SOPInstanceUID"),
                 a.body.constData());

        a = post(server.port(), kToken, multipartType(),
                 QByteArray("--") + kBoundary + "\r\nContent-Type: application/dicom\r\n\r\n" +
                     dicom);
        QCOMPARE(a.status, 400);
        QVERIFY2(a.body.contains("cut short"), a.body.constData());

        QCOMPARE(filesIn(server.storeDir() + "/files"), 0);
        QCOMPARE(filesIn(server.storeDir() + "/tmp"), 0);
        RemoteTestClient client(server.port());
        QVERIFY(client.waitConnected());
        QVERIFY(client.authenticate());
        QCOMPARE(list(client).size(), 1); // the synthetic --data volume only
    }

    void oversizedUploadIs413() {
        ServerProcess server("cpu", {}, {"--upload-limit", "1"});
        QVERIFY(server.port());
        const Answer a =
            post(server.port(), kToken, "application/dicom", QByteArray(2 << 20, '\0'));
        QCOMPARE(a.status, 413);
        QVERIFY2(a.body.contains("at most 1048576"), a.body.constData());
        QCOMPARE(filesIn(server.storeDir() + "/files"), 0);
    }

    void uploadedSeriesIsListedAndOpens() {
        if (!QFileInfo::exists(seriesDir())) {
            QSKIP("no test data (dcm_qa_ct)");
        }
        const Catalog local = scanPath(seriesDir().toStdString());
        QCOMPARE(local.series.size(), std::size_t(1));
        const SeriesEntry& entry = local.series.front();
        QList<QByteArray> parts;
        for (const SliceRef& slice : entry.slices) {
            parts << readFile(QString::fromStdString(slice.file));
        }
        ServerProcess server("cpu");
        QVERIFY(server.port());
        Answer a = post(server.port(), kToken, multipartType(), multipart(parts));
        QCOMPARE(a.status, 200);
        const QJsonObject summary = QJsonDocument::fromJson(a.body).object();
        QCOMPARE(summary["stored"].toInt(), int(parts.size()));
        QCOMPARE(summary["series"].toArray().at(0).toString(), QString::fromStdString(entry.id));

        // Listed at once (the answer comes after the store is scanned again).
        RemoteTestClient client(server.port());
        QVERIFY(client.waitConnected());
        QVERIFY(client.authenticate());
        QJsonObject found;
        for (const QJsonValue& v : list(client)) {
            if (v.toObject()["uid"].toString() == QString::fromStdString(entry.id)) {
                found = v.toObject();
            }
        }
        QCOMPARE(found["dims"].toArray().at(2).toInt(), int(parts.size()));
        client.change({{"type", "open"}, {"series", found["uid"]}});
        QVERIFY(!client.waitForText("opened").isEmpty());
        client.change({{"type", "size"}, {"width", 64}, {"height", 64}});
        QVERIFY(client.waitForCurrentFrame());

        // One instance again, as application/dicom: already stored.
        a = post(server.port(), kToken, "application/dicom", parts.front());
        QCOMPARE(a.status, 200);
        QCOMPARE(QJsonDocument::fromJson(a.body).object()["already_stored"].toInt(), 1);
        QCOMPARE(filesIn(server.storeDir() + "/files"), int(parts.size()));
    }

    void uploadIsSpooledToDiskAsItArrives() {
        if (!QFileInfo::exists(seriesDir())) {
            QSKIP("no test data (dcm_qa_ct)");
        }
        const QByteArray dicom = readFile(seriesDir() + "/I10");
        const QByteArray body = multipart({dicom, readFile(seriesDir() + "/I20")});
        const QByteArray head =
            "POST /studies HTTP/1.1\r\nHost: 127.0.0.1\r\nAuthorization: Bearer " +
            QByteArray(kToken) + "\r\nContent-Type: " + multipartType() +
            "\r\nContent-Length: " + QByteArray::number(body.size()) + "\r\n\r\n";
        ServerProcess server("cpu");
        QVERIFY(server.port());
        const QString spool = server.storeDir() + "/tmp";
        const auto spooledBytes = [&spool] {
            const QStringList names =
                QDir(spool).entryList({"incoming-*-upload-*.part"}, QDir::Files);
            return names.size() == 1 ? QFileInfo(spool + "/" + names.front()).size() : qint64(-1);
        };

        // Half of the body: it lies in the store's tmp/, not in the server's memory.
        QTcpSocket socket;
        socket.connectToHost(QHostAddress::LocalHost, server.port());
        QVERIFY(socket.waitForConnected(10000));
        const qsizetype half = body.size() / 2;
        socket.write(head + body.left(half));
        QVERIFY2(QTest::qWaitFor([&] { return spooledBytes() == half; }, 20000),
                 qPrintable(QString("spooled %1 of %2 bytes").arg(spooledBytes()).arg(half)));
        // The rest: stored, and the spooled file is gone before the answer.
        socket.write(body.mid(half));
        QByteArray answer;
        QVERIFY(QTest::qWaitFor(
            [&] {
                answer += socket.readAll();
                return answer.contains("}\n") || socket.state() != QAbstractSocket::ConnectedState;
            },
            60000));
        QVERIFY2(answer.startsWith("HTTP/1.1 200"), answer.constData());
        QVERIFY2(answer.contains("\"stored\":2"), answer.constData());
        QCOMPARE(spooledBytes(), qint64(-1));
        QCOMPARE(filesIn(server.storeDir() + "/files"), 2);

        // A client that goes away half-way leaves nothing behind.
        QTcpSocket quitter;
        quitter.connectToHost(QHostAddress::LocalHost, server.port());
        QVERIFY(quitter.waitForConnected(10000));
        quitter.write(head + body.left(half));
        QVERIFY(QTest::qWaitFor([&] { return spooledBytes() == half; }, 20000));
        quitter.abort();
        QVERIFY2(QTest::qWaitFor([&] { return filesIn(spool) == 0; }, 20000),
                 qPrintable(QDir(spool).entryList(QDir::Files).join(", ")));
        QCOMPARE(filesIn(server.storeDir() + "/files"), 2);
    }

    void unwritableSpoolIs507() {
        ServerProcess server("cpu");
        QVERIFY(server.port());
        // The store's tmp/ replaced by a file: no spool file can be made there
        // (as root, permissions would not stop the server).
        const QString spool = server.storeDir() + "/tmp";
        QVERIFY(QDir(spool).removeRecursively());
        QFile blocker(spool);
        QVERIFY(blocker.open(QIODevice::WriteOnly));
        blocker.close();
        const Answer a = post(server.port(), kToken, "application/dicom", QByteArray(4000, 'x'));
        QCOMPARE(a.status, 507);
        QVERIFY2(a.body.contains("cannot write the upload") && !a.body.contains(spool.toUtf8()),
                 a.body.constData());
        QVERIFY2(server.log().contains("cannot spool an upload"), qPrintable(server.log()));
        QCOMPARE(filesIn(server.storeDir() + "/files"), 0);
    }
};

QTEST_GUILESS_MAIN(TestRemoteUpload)
#include "test_remote_upload.moc"
