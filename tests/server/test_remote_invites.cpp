// Invites to teaching sessions on the real lucent-server over loopback: an
// invite joins its session as a follower and receives the presenter's frames
// of the de-identified copy of real CT; it may do nothing else (list, open,
// present, invite, upload: each refused with its code, the connection kept);
// expired, revoked and ended invites are refused; older clients are refused
// cleanly; the follower never gets a frame of another session's series; the
// QR code decodes (zbarimg) to the link; no code reaches the server's log.
#include <QDir>
#include <QEventLoop>
#include <QImage>
#include <QJsonArray>
#include <QNetworkAccessManager>
#include <QNetworkReply>
#include <QProcess>
#include <QStandardPaths>
#include <QTest>
#include <QTimer>

#include "RemoteTestFixture.h"
#include "core/formats/MetaImage.h"
#include "tests/support/RealData.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSide = 80;

constexpr char kRealSeries[] = "dcm_qa_ct/Philips_S21570/S2010";

QString realSeriesDir() {
    return QString::fromStdString((kRealData / kRealSeries).string());
}

QByteArray firstFileOf(const QString& dir) {
    const QStringList files = QDir(dir).entryList(QDir::Files, QDir::Name);
    QFile file(dir + "/" + (files.isEmpty() ? QString() : files.front()));
    return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray();
}

// The server's series, the real CT (description and all) first.
QJsonArray listSeries(RemoteTestClient& presenter) {
    const qsizetype from = presenter.texts.size();
    presenter.send({{"type", "list"}});
    return presenter.waitForText("series", 20000, from)["series"].toArray();
}

// An authenticated client presents a new session showing `uid` at kSide; the
// session's id, empty when it failed. Two view messages (seq 2).
QString presentSeries(RemoteTestClient& presenter, const QString& uid) {
    presenter.send({{"type", "session-create"}});
    const QString id = presenter.waitForText("session-created")["session"].toString();
    presenter.change({{"type", "open"}, {"series", uid}});
    presenter.change({{"type", "size"}, {"width", kSide}, {"height", kSide}});
    return presenter.waitForText("opened").isEmpty() ? QString() : id;
}

QJsonObject createInvite(RemoteTestClient& presenter, const QJsonObject& fields = {}) {
    QJsonObject message = fields;
    message["type"] = "invite-create";
    const qsizetype from = presenter.texts.size();
    presenter.send(message);
    return presenter.waitForText("invite-created", 20000, from);
}

QStringList inviteSubprotocols(const QString& code, const QString& version = "lucent.v3") {
    return {version, "lucent.invite." + code};
}

// The error the client got after index `from` (waits for one).
QJsonObject errorAfter(RemoteTestClient& client, qsizetype from) {
    return client.waitForText("error", 20000, from);
}

const ReceivedFrame* frameOf(RemoteTestClient& client, std::uint64_t seq) {
    (void)QTest::qWaitFor(
        [&] { return !client.frames.isEmpty() && client.frames.back().header.seq >= seq; }, 60000);
    return !client.frames.isEmpty() && client.frames.back().header.seq >= seq
               ? &client.frames.back()
               : nullptr;
}

int uploadStatus(quint16 port, const QByteArray& bearer, const QByteArray& body) {
    QNetworkAccessManager manager;
    QNetworkRequest request(QUrl(QString("http://127.0.0.1:%1/studies").arg(port)));
    request.setHeader(QNetworkRequest::ContentTypeHeader, "application/dicom");
    request.setRawHeader("Authorization", "Bearer " + bearer);
    QNetworkReply* reply = manager.post(request, body);
    QEventLoop loop;
    QObject::connect(reply, &QNetworkReply::finished, &loop, &QEventLoop::quit);
    QTimer::singleShot(60000, &loop, &QEventLoop::quit);
    loop.exec();
    const int status = reply->attribute(QNetworkRequest::HttpStatusCodeAttribute).toInt();
    reply->deleteLater();
    return status;
}

// The matrix drawn as a reader sees it: 6 pixels a module, the quiet zone around.
QImage qrImage(const QJsonObject& qr) {
    const int size = qr["size"].toInt();
    const QJsonArray rows = qr["rows"].toArray();
    constexpr int kScale = 6;
    const int side = (size + 2 * remote::kQrQuietZone) * kScale;
    QImage image(side, side, QImage::Format_Grayscale8);
    image.fill(255);
    for (int y = 0; y < size; ++y) {
        const QString row = rows[y].toString();
        for (int x = 0; x < size && x < row.size(); ++x) {
            if (row[x] == '1') {
                for (int dy = 0; dy < kScale; ++dy) {
                    for (int dx = 0; dx < kScale; ++dx) {
                        image.setPixel((x + remote::kQrQuietZone) * kScale + dx,
                                       (y + remote::kQrQuietZone) * kScale + dy, 0);
                    }
                }
            }
        }
    }
    return image;
}

// Fails the test when the server's log holds any of the codes.
void verifyNoCodeLogged(ServerProcess& server, const QStringList& codes) {
    const QString log = server.log();
    QVERIFY(!log.isEmpty());
    for (const QString& code : codes) {
        QVERIFY2(!code.isEmpty() && !log.contains(code), "an invite code is in the server's log");
    }
}

} // namespace

class TestRemoteInvites : public QObject {
    Q_OBJECT

private slots:
    // An invite (in the subprotocol, as browsers send it, and in auth) joins the
    // session as a follower and gets the presenter's frames of the
    // de-identified copy; everything else it asks for is refused, the
    // connection kept.
    void anInviteJoinsFollowsAndMayDoNothingElse() {
        REQUIRE_DATA(kRealSeries);
        ServerProcess server("cpu", realSeriesDir());
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port(), {"lucent.v3"});
        const QJsonArray series = (presenter.waitConnected() && presenter.authenticate())
                                      ? listSeries(presenter)
                                      : QJsonArray();
        QCOMPARE(series.size(), 1);
        const QString original = series[0].toObject()["uid"].toString();
        const QString session = presentSeries(presenter, original);
        QVERIFY(!session.isEmpty());
        const QJsonObject invite = createInvite(presenter);
        const QString code = invite["code"].toString();
        QVERIFY2(code.size() >= 22, qPrintable(code)); // >= 128 bits in base64url
        QCOMPARE(invite["path"].toString(), "/#invite=" + code);
        QCOMPARE(invite["link"].toString(),
                 QString("http://127.0.0.1:%1/#invite=%2").arg(server.port()).arg(code));
        const qint64 now = QDateTime::currentSecsSinceEpoch();
        QVERIFY(invite["expires"].toInteger() > now + 86000); // the session's end, at most a day
        QVERIFY(invite["expires"].toInteger() <= now + 86400 + 1);
        QVERIFY(invite["invite"].toInteger() > 0);

        RemoteTestClient student(server.port(), inviteSubprotocols(code));
        QVERIFY(student.waitConnected());
        QCOMPARE(student.subprotocol(), "lucent.v3");
        QCOMPARE(student.waitForText("hello")["version"].toInt(), 3);
        const QJsonObject state = student.waitForText("session-state");
        QCOMPARE(state["role"].toString(), "follower");
        QCOMPARE(state["session"].toString(), session);
        const QJsonObject opened = student.waitForText("opened");
        QVERIFY(!opened.isEmpty());
        QVERIFY(opened["series"].toString() != original); // the de-identified copy
        presenter.change({{"type", "camera"}, {"azimuth", 35}});
        const ReceivedFrame* mine = frameOf(presenter, presenter.seq);
        const ReceivedFrame* theirs = frameOf(student, presenter.seq);
        QVERIFY(mine && theirs);
        QCOMPARE(theirs->image, mine->image);

        // The other way in: auth with an invite field.
        RemoteTestClient second(server.port(), {"lucent.v3"});
        QVERIFY(second.waitConnected());
        second.send({{"type", "auth"}, {"invite", code}});
        QVERIFY(!second.waitForText("hello").isEmpty());
        QCOMPARE(second.waitForText("session-state")["role"].toString(), "follower");
        QVERIFY(frameOf(second, presenter.seq));

        // Only following: each refused with its code, not fatal.
        const QList<std::pair<QJsonObject, QString>> refused = {
            {{{"type", "list"}}, "forbidden"},
            {{{"type", "open"}, {"series", original}}, "forbidden"},
            {{{"type", "session-create"}}, "forbidden"},
            {{{"type", "session-join"}, {"session", session}}, "forbidden"},
            {{{"type", "session-handover"}, {"to", 1}}, "forbidden"},
            {{{"type", "invite-create"}}, "forbidden"},
            {{{"type", "invite-revoke"}, {"invite", invite["invite"]}}, "forbidden"},
            {{{"type", "camera"}, {"azimuth", 90}}, "not-presenter"},
        };
        for (const auto& [message, code] : refused) {
            const qsizetype from = student.texts.size();
            student.send(message);
            const QJsonObject error = errorAfter(student, from);
            QVERIFY2(error["code"].toString() == code,
                     qPrintable(message["type"].toString() + ": " + error["code"].toString()));
            QVERIFY(!error["fatal"].toBool());
        }
        // Nor can it be handed control, nor upload with its code.
        const qsizetype from = presenter.texts.size();
        presenter.send({{"type", "session-handover"}, {"to", state["you"]}});
        QCOMPARE(errorAfter(presenter, from)["code"].toString(), "forbidden");
        QCOMPARE(uploadStatus(server.port(), code.toUtf8(), firstFileOf(realSeriesDir())), 401);
        QVERIFY(!QDir(server.storeDir() + "/files").exists() ||
                QDir(server.storeDir() + "/files").isEmpty());

        // Still following.
        presenter.change({{"type", "camera"}, {"azimuth", 70}});
        QVERIFY(frameOf(student, presenter.seq));
        QCOMPARE(student.frames.back().image, frameOf(presenter, presenter.seq)->image);
        QVERIFY(!student.disconnected && !second.disconnected);
        verifyNoCodeLogged(server, {code});
    }

    // Refused with auth-failed and a reason, the connection closed: an expired
    // invite, a revoked one (its followers are dropped), one whose session
    // ended (its followers are told session-left), an unknown one, and any
    // invite on a version 1 or 2 connection.
    void expiredRevokedEndedAndOldClientInvitesAreRefused() {
        ServerProcess server("cpu");
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port(), {"lucent.v3"});
        QVERIFY(presenter.waitConnected() && presenter.authenticate());
        const QJsonArray series = listSeries(presenter);
        QCOMPARE(series.size(), 1);
        QVERIFY(!presentSeries(presenter, series[0].toObject()["uid"].toString()).isEmpty());
        const QString shortLived = createInvite(presenter, {{"lifetime", 1}})["code"].toString();
        const QJsonObject revokedInvite = createInvite(presenter);
        const QString revoked = revokedInvite["code"].toString();
        const QString lasting = createInvite(presenter)["code"].toString();
        QVERIFY(!shortLived.isEmpty() && !revoked.isEmpty() && !lasting.isEmpty());

        const auto refusal = [&](const QStringList& subprotocols) {
            RemoteTestClient c(server.port(), subprotocols);
            const QJsonObject error = c.waitForText("error");
            c.waitDisconnected();
            return std::pair{error, c.disconnected};
        };
        // Old clients: the message says what is needed.
        for (const QString old : {"lucent.v2", "lucent.v1"}) {
            const auto [error, closed] = refusal(inviteSubprotocols(lasting, old));
            QCOMPARE(error["code"].toString(), "auth-failed");
            QVERIFY2(error["message"].toString().contains("version 3"),
                     qPrintable(error["message"].toString()));
            QVERIFY(error["fatal"].toBool() && closed);
        }
        RemoteTestClient v2(server.port(), {"lucent.v2"});
        QVERIFY(v2.waitConnected());
        v2.send({{"type", "auth"}, {"invite", lasting}});
        QVERIFY(errorAfter(v2, 0)["message"].toString().contains("version 3"));
        QVERIFY(v2.waitDisconnected());

        // Revoked: the follower it let in is dropped, and it lets no one in again.
        RemoteTestClient follower(server.port(), inviteSubprotocols(revoked));
        QVERIFY(!follower.waitForText("session-state").isEmpty());
        qsizetype from = presenter.texts.size();
        presenter.send({{"type", "invite-revoke"}, {"invite", revokedInvite["invite"]}});
        QCOMPARE(presenter.waitForText("invite-revoked", 20000, from)["invite"],
                 revokedInvite["invite"]);
        QVERIFY(errorAfter(follower, 0)["message"].toString().contains("revoked"));
        QVERIFY(follower.waitDisconnected());
        QVERIFY(
            refusal(inviteSubprotocols(revoked)).first["message"].toString().contains("revoked"));
        from = presenter.texts.size();
        presenter.send({{"type", "invite-revoke"}, {"invite", 999}});
        QCOMPARE(errorAfter(presenter, from)["code"].toString(), "not-found");

        // Expired (a lifetime of 1 s).
        QTest::qWait(1100);
        const auto expired = refusal(inviteSubprotocols(shortLived));
        QCOMPARE(expired.first["code"].toString(), "auth-failed");
        QVERIFY2(expired.first["message"].toString().contains("expired"),
                 qPrintable(expired.first["message"].toString()));
        QVERIFY(expired.second);
        QVERIFY(refusal(inviteSubprotocols("AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA"))
                    .first["message"]
                    .toString()
                    .contains("not valid"));

        // The session ends with its last presenter: its followers by invite are
        // told and closed, and its invites let no one in.
        RemoteTestClient watcher(server.port(), inviteSubprotocols(lasting));
        QVERIFY(!watcher.waitForText("session-state").isEmpty());
        presenter.send({{"type", "session-leave"}});
        QVERIFY(!watcher.waitForText("session-left").isEmpty());
        QVERIFY(watcher.waitDisconnected());
        QVERIFY(refusal(inviteSubprotocols(lasting)).first["message"].toString().contains("ended"));
        verifyNoCodeLogged(server, {shortLived, revoked, lasting});
    }

    // Another session's presenter opens and turns another series meanwhile: the
    // invited follower's frames are all frames of its own session.
    void anInvitedFollowerNeverGetsAFrameOfAnotherSeries() {
        REQUIRE_DATA(kRealSeries);
        ServerProcess server("cpu", realSeriesDir(), {}, ServerProcess::Start::Later);
        QVERIFY(QDir().mkpath(server.storeDir() + "/files"));
        writeMetaImage(syntheticCt(), (server.storeDir() + "/files/other.mhd").toStdString());
        QVERIFY2(server.start().isEmpty(), qPrintable(server.startError()));
        RemoteTestClient a(server.port(), {"lucent.v3"});
        RemoteTestClient b(server.port(), {"lucent.v3"});
        QVERIFY(a.waitConnected() && a.authenticate());
        QVERIFY(b.waitConnected() && b.authenticate());
        const QJsonArray series = listSeries(a);
        QCOMPARE(series.size(), 2);
        QString real;
        QString other;
        for (const auto& s : series) {
            // The synthetic CT is 48 voxels wide.
            (s.toObject()["dims"].toArray()[0].toInt() == 48 ? other : real) =
                s.toObject()["uid"].toString();
        }
        QVERIFY2(!real.isEmpty() && !other.isEmpty(), qPrintable(a.allText()));
        QVERIFY(!presentSeries(a, real).isEmpty());
        const QString code = createInvite(a)["code"].toString();
        RemoteTestClient student(server.port(), inviteSubprotocols(code));
        const QString shown = student.waitForText("opened")["series"].toString();
        QVERIFY(!shown.isEmpty());
        QVERIFY(!presentSeries(b, other).isEmpty());
        for (int turn = 1; turn <= 4; ++turn) {
            b.change({{"type", "camera"}, {"azimuth", 20 * turn}});
            a.change({{"type", "camera"}, {"azimuth", 15 * turn}});
            QVERIFY(frameOf(a, a.seq) && frameOf(b, b.seq));
        }
        QVERIFY(frameOf(student, a.seq));
        QVERIFY(student.frames.size() >= 2);
        for (const ReceivedFrame& f : std::as_const(student.frames)) {
            const bool ours = std::any_of(a.frames.cbegin(), a.frames.cend(), [&](const auto& x) {
                return x.header.seq == f.header.seq && x.image == f.image;
            });
            const bool theirs = std::any_of(b.frames.cbegin(), b.frames.cend(),
                                            [&](const auto& x) { return x.image == f.image; });
            QVERIFY(ours && !theirs);
        }
        for (const QJsonObject& t : std::as_const(student.texts)) {
            if (t["type"] == "opened" || t["type"] == "session-state") {
                QCOMPARE(t["series"].toString(), shown);
            }
        }
        verifyNoCodeLogged(server, {code});
    }

    // The QR code of the link, read back by a real decoder.
    void theQrCodeDecodesToTheLink() {
        const QString zbarimg = QStandardPaths::findExecutable("zbarimg");
        QVERIFY2(!zbarimg.isEmpty(), "zbarimg is missing (apt-get install zbar-tools; "
                                     "packaging/install-deps.sh)");
        ServerProcess server("cpu");
        QVERIFY(server.port());
        RemoteTestClient presenter(server.port(), {"lucent.v3"});
        QVERIFY(presenter.waitConnected() && presenter.authenticate());
        presenter.send({{"type", "session-create"}});
        QVERIFY(!presenter.waitForText("session-created").isEmpty());
        for (const QString origin : {"", "https://lecture-hall.example.org:8443"}) {
            const QJsonObject invite = createInvite(
                presenter, origin.isEmpty() ? QJsonObject() : QJsonObject{{"origin", origin}});
            const QString link = invite["link"].toString();
            QVERIFY(origin.isEmpty() || link == origin + invite["path"].toString());
            const QString png = server.dir() + "/qr.png";
            QVERIFY(qrImage(invite["qr"].toObject()).save(png));
            QProcess decoder;
            decoder.start(zbarimg, {"--raw", "-q", png});
            QVERIFY(decoder.waitForFinished(30000));
            QCOMPARE(QString::fromUtf8(decoder.readAllStandardOutput()).trimmed(), link);
        }
        const qsizetype from = presenter.texts.size();
        presenter.send({{"type", "invite-create"}, {"origin", "javascript:alert(1)"}});
        QCOMPARE(errorAfter(presenter, from)["code"].toString(), "bad-request");
    }
};

QTEST_GUILESS_MAIN(TestRemoteInvites)
#include "test_remote_invites.moc"
