// Invites in the browser client, end to end with headless Chromium: a student
// opens the join link (http://host:port/#invite=CODE) and watches the
// presenter's frames, the code gone from the address bar; a presenter's page
// makes an invite with its button and draws a QR code that zbarimg reads back
// as the link. Skips when chromium, chromedriver or the real data are missing.
#include <QFileInfo>
#include <QJsonArray>
#include <QProcess>
#include <QStandardPaths>
#include <QTest>

#include "WebDriver.h"
#include "WebServerFixture.h"

using namespace lucent::test;

namespace {

const QString kSeriesDir = QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";

QString statusOf(WebDriver& driver) {
    return driver.execute("return document.getElementById('status').textContent;").toString() +
           "\n" + driver.consoleLog();
}

int framesDrawn(WebDriver& driver) {
    return driver.execute("return window.lucent.stats.framesDrawn;").toInt();
}

} // namespace

class TestWebInvites : public QObject {
    Q_OBJECT
private slots:
    void init() {
        if (const QString missing = browserTestMissing(kSeriesDir); !missing.isEmpty()) {
            QSKIP(qPrintable(missing));
        }
    }

    void aJoinLinkFollowsTheSession() {
        ServerProcess server("cpu", kSeriesDir);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        RemoteTestClient presenter(server.port(), {"lucent.v3"});
        QVERIFY(presenter.waitConnected() && presenter.authenticate());
        presenter.send({{"type", "list"}});
        const QJsonArray series = presenter.waitForText("series")["series"].toArray();
        QVERIFY(!series.isEmpty());
        presenter.send({{"type", "session-create"}});
        QVERIFY(!presenter.waitForText("session-created").isEmpty());
        presenter.send({{"type", "open"}, {"series", series[0].toObject()["uid"].toString()}});
        presenter.send({{"type", "size"}, {"width", 200}, {"height", 160}});
        QVERIFY(!presenter.waitForText("opened").isEmpty());
        presenter.send({{"type", "invite-create"}});
        const QJsonObject invite = presenter.waitForText("invite-created");
        const QString code = invite["code"].toString();
        QVERIFY(!code.isEmpty());

        WebDriver driver(findBrowserTools());
        QVERIFY2(driver.start(390, 800), qPrintable(driver.error())); // a phone
        QVERIFY2(driver.navigate(invite["link"].toString()), qPrintable(driver.error()));
        QVERIFY2(driver.waitUntil("const s = window.lucent.session();"
                                  "return s !== null && s.role === 'follower' && "
                                  "window.lucent.stats.framesDrawn > 0;",
                                  30000),
                 qPrintable(statusOf(driver)));
        QCOMPARE(driver.execute("return window.lucent.protocolVersion();").toInt(),
                 lucent::remote::kProtocolVersion); // invites came with 3
        QVERIFY(driver.execute("return window.lucent.invited();").toBool());
        // The code left the address bar; the page is the view alone.
        QVERIFY(!driver.execute("return location.href;").toString().contains(code));
        QCOMPARE(driver.execute("return location.hash;").toString(), "");
        QCOMPARE(driver
                     .execute("return getComputedStyle(document.getElementById('panel'))"
                              ".display;")
                     .toString(),
                 "none");

        // No page of the server lets the browser send a Referer.
        QCOMPARE(driver.execute("return fetch('/').then((r) => r.headers.get('referrer-policy'));")
                     .toString(),
                 "no-referrer");

        const int drawn = framesDrawn(driver);
        presenter.send({{"type", "camera"}, {"azimuth", 90}});
        QVERIFY2(driver.waitUntil(
                     QString("return window.lucent.stats.framesDrawn > %1;").arg(drawn), 30000),
                 qPrintable(statusOf(driver)));
        QVERIFY(!server.log().contains(code));

        // Revoked: the page says so and stops.
        presenter.send({{"type", "invite-revoke"}, {"invite", invite["invite"]}});
        QVERIFY2(driver.waitUntil("return document.getElementById('status').textContent"
                                  ".includes('revoked');",
                                  20000),
                 qPrintable(statusOf(driver)));
    }

    void thePresentersPageInvitesWithAQrCode() {
        const QString zbarimg = QStandardPaths::findExecutable("zbarimg");
        QVERIFY2(!zbarimg.isEmpty(), "zbarimg is missing (apt-get install zbar-tools)");
        ServerProcess server("cpu", kSeriesDir);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        WebDriver driver(findBrowserTools());
        QVERIFY2(driver.start(640, 720), qPrintable(driver.error()));
        QVERIFY(driver.navigate(QString("http://127.0.0.1:%1/").arg(server.port())));
        QVERIFY(driver.sendKeys(driver.findElement("#token"), kToken));
        QVERIFY(driver.click(driver.findElement("#connect")));
        QVERIFY(
            driver.waitUntil("return !document.getElementById('start-session').disabled;", 20000));
        QVERIFY(driver.execute("return document.getElementById('create-invite').disabled;")
                    .toBool()); // no session yet
        QVERIFY(driver.click(driver.findElement("#start-session")));
        QVERIFY2(
            driver.waitUntil("return !document.getElementById('create-invite').disabled;", 20000),
            qPrintable(statusOf(driver)));
        QVERIFY(driver.click(driver.findElement("#create-invite")));
        QVERIFY2(driver.waitUntil("return window.lucent.shownInvite() !== null;", 20000),
                 qPrintable(statusOf(driver)));
        const QString link =
            driver.execute("return document.getElementById('invite-link').value;").toString();
        QVERIFY2(link.startsWith(QString("http://127.0.0.1:%1/#invite=").arg(server.port())),
                 qPrintable(link));

        // The QR code as the page drew it, read by a real decoder.
        const QString dataUrl =
            driver.execute("return document.getElementById('invite-qr').toDataURL('image/png');")
                .toString();
        QVERIFY(dataUrl.startsWith("data:image/png;base64,"));
        QTemporaryDir dir;
        QFile png(dir.filePath("qr.png"));
        QVERIFY(png.open(QIODevice::WriteOnly));
        png.write(QByteArray::fromBase64(dataUrl.mid(dataUrl.indexOf(',') + 1).toLatin1()));
        png.close();
        QProcess decoder;
        decoder.start(zbarimg, {"--raw", "-q", png.fileName()});
        QVERIFY(decoder.waitForFinished(30000));
        QCOMPARE(QString::fromUtf8(decoder.readAllStandardOutput()).trimmed(), link);

        QVERIFY(driver.click(driver.findElement("#revoke-invite")));
        QVERIFY(driver.waitUntil("return window.lucent.shownInvite() === null;", 20000));
        QVERIFY(!driver.consoleLog().contains("SEVERE"));
    }
};

QTEST_GUILESS_MAIN(TestWebInvites)
#include "test_web_invites.moc"
