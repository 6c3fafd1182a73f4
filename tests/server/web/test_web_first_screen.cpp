// A student's first screen, end to end with headless Chromium on a real
// lucent-server (real CT): a presenter (a C++ client) opens the series, places
// marks and the pointer and makes an invite; a student opens the join link at
// phone size (then rotated) and at desktop size, another joins by token and
// session id, and comes back after its connection drops. Each page shows no
// error, the server logs no error for any of them, the page sends nothing a
// follower may not send, and the marks and the pointer placed before the join
// are drawn with the first frame. Skips when
// chromium, chromedriver or the real data are missing.
#include <QFileInfo>
#include <QJsonArray>
#include <QRegularExpression>
#include <QTest>

#include <algorithm>

#include "WebDriver.h"
#include "WebServerFixture.h"

using namespace lucent::test;

namespace {

const QString kSeriesDir = QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";
constexpr int kSide = 256;
constexpr double kPointerX = 0.25;
constexpr double kPointerY = 0.7;

QString statusOf(WebDriver& driver) {
    return driver.execute("return document.getElementById('status').textContent;").toString() +
           "\n" + driver.consoleLog();
}

// Every error the server sent a client, as its log says ("client 3 error not-presenter").
QStringList errorsLogged(ServerProcess& server) {
    QStringList errors;
    auto it = QRegularExpression(R"(client \d+ error \S+)").globalMatch(server.log());
    while (it.hasNext()) {
        errors << it.next().captured(0);
    }
    return errors;
}

// The page's status line says no error (an error is shown as "bad", in red).
bool showsNoError(WebDriver& driver) {
    return driver
        .execute("const s = document.getElementById('status');"
                 "return !s.classList.contains('bad') && !s.textContent.includes('error');")
        .toBool();
}

// From now on the page records the type of every message it sends, and the socket.
bool recordSentMessages(WebDriver& driver) {
    return driver
        .execute("window.sentByPage = [];"
                 "const send = WebSocket.prototype.send;"
                 "WebSocket.prototype.send = function (data) {"
                 "  window.pageSocket = this;"
                 "  window.sentByPage.push(typeof data === 'string' ? JSON.parse(data).type"
                 "                                                  : 'binary');"
                 "  return send.call(this, data);"
                 "};"
                 "return true;")
        .toBool();
}
QStringList sentMessages(WebDriver& driver) {
    QStringList types;
    for (const QJsonValue& t : driver.execute("return window.sentByPage;").toArray()) {
        types << t.toString();
    }
    return types;
}

bool isMarkColour(const QJsonArray& rgba) { // #ff2bd6
    return rgba.size() == 4 && rgba[0].toInt() > 200 && rgba[1].toInt() < 110 &&
           rgba[2].toInt() > 160;
}
bool isPointerColour(const QJsonArray& rgba) { // #ff3b30
    return rgba.size() == 4 && rgba[0].toInt() > 200 && rgba[1].toInt() < 120 &&
           rgba[2].toInt() < 110;
}

QJsonArray canvasPixel(WebDriver& driver, const QJsonArray& at) {
    return driver
        .execute("const c = document.getElementById('view').getContext('2d');"
                 "return Array.from(c.getImageData(Math.floor(arguments[0]),"
                 "                                 Math.floor(arguments[1]), 1, 1).data);",
                 {at[0], at[1]})
        .toArray();
}

// The marks and the pointer of the presenter, drawn on the canvas now: each
// mark at its first point in the mark's colour, the dot in the pointer's, where
// the frame's rectangle puts it. Empty when so, else what is wrong.
QString marksDrawnNow(WebDriver& driver, int markCount) {
    const QJsonObject drawn = driver.execute("return window.lucent.marks();").toObject();
    const QJsonArray marks = drawn["marks"].toArray();
    if (marks.size() != markCount || drawn["pointer"].isNull() || drawn["rect"].isNull()) {
        return "drawn: " + QString::fromUtf8(QJsonDocument(drawn).toJson(QJsonDocument::Compact));
    }
    for (const QJsonValue& m : marks) {
        const QJsonArray pixels = m.toObject()["pixels"].toArray();
        if (pixels.isEmpty()) {
            return m.toObject()["kind"].toString() + " is not on the frame";
        }
        const QJsonArray colour = canvasPixel(driver, pixels[0].toArray());
        if (!isMarkColour(colour)) {
            return m.toObject()["kind"].toString() + " is drawn as " +
                   QString::fromUtf8(QJsonDocument(colour).toJson(QJsonDocument::Compact));
        }
    }
    const QJsonObject rect = drawn["rect"].toObject();
    const QJsonArray dot = drawn["pointer"].toArray();
    if (std::abs(dot[0].toDouble() - (rect["x"].toDouble() + kPointerX * rect["w"].toDouble())) >
            0.01 ||
        std::abs(dot[1].toDouble() - (rect["y"].toDouble() + kPointerY * rect["h"].toDouble())) >
            0.01) {
        return "the pointer is drawn elsewhere";
    }
    const QJsonArray colour = canvasPixel(driver, dot);
    if (!isPointerColour(colour)) {
        return "the pointer is drawn as " +
               QString::fromUtf8(QJsonDocument(colour).toJson(QJsonDocument::Compact));
    }
    return {};
}

// Waits for the page's first screen as a follower; then, without waiting
// more, the marks and the pointer must be on it.
QString firstScreen(WebDriver& driver, int markCount) {
    if (!driver.waitUntil("const s = window.lucent.session();"
                          "return s !== null && s.role === 'follower' && "
                          "window.lucent.stats.framesDrawn > 0;",
                          60000)) {
        return "no first screen: " + statusOf(driver);
    }
    return marksDrawnNow(driver, markCount);
}

} // namespace

class TestWebFirstScreen : public QObject {
    Q_OBJECT
private slots:
    void init() {
        if (const QString missing = browserTestMissing(kSeriesDir); !missing.isEmpty()) {
            QSKIP(qPrintable(missing));
        }
    }

    void aStudentsFirstScreenIsClean() {
        ServerProcess server("cpu", kSeriesDir);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        RemoteTestClient presenter(server.port(), {"lucent.v4"});
        QVERIFY(presenter.waitConnected() && presenter.authenticate());
        presenter.send({{"type", "session-create"}});
        const QString session = presenter.waitForText("session-created")["session"].toString();
        QVERIFY(!openOnlySeries(presenter, kSide).isEmpty());
        QVERIFY(!presenter.waitForText("opened", 60000).isEmpty());
        QVERIFY(presenter.waitForCurrentFrame() != nullptr);
        // Before anyone joins: two marks and the pointer.
        presenter.send({{"type", "mark"},
                        {"kind", "arrow"},
                        {"points", QJsonArray{QJsonArray{0.5, 0.4}, QJsonArray{0.7, 0.25}}}});
        presenter.send({{"type", "mark"},
                        {"kind", "circle"},
                        {"points", QJsonArray{QJsonArray{0.45, 0.55}, QJsonArray{0.5, 0.55}}}});
        QVERIFY(!presenter.waitForText("mark").isEmpty());
        QVERIFY(QTest::qWaitFor(
            [&] {
                return std::count_if(presenter.texts.begin(), presenter.texts.end(),
                                     [](const QJsonObject& t) {
                                         return t["type"].toString() == "mark";
                                     }) == 2;
            },
            20000));
        presenter.send({{"type", "pointer"}, {"x", kPointerX}, {"y", kPointerY}});
        QVERIFY(!presenter.waitForText("pointer").isEmpty());
        presenter.send({{"type", "invite-create"}});
        const QString link = presenter.waitForText("invite-created")["link"].toString();
        QVERIFY(!link.isEmpty());
        QVERIFY2(errorsLogged(server).isEmpty(), qPrintable(server.log()));

        // A student with a phone opens the join link.
        WebDriver phone(findBrowserTools());
        QVERIFY2(phone.start(390, 844), qPrintable(phone.error()));
        QVERIFY2(phone.navigate(link), qPrintable(phone.error()));
        QString wrong = firstScreen(phone, 2);
        QVERIFY2(wrong.isEmpty(), qPrintable(wrong));
        QVERIFY(recordSentMessages(phone));
        QTest::qWait(1000); // an answer to anything the page sent on joining has come by now
        QVERIFY2(showsNoError(phone), qPrintable(statusOf(phone)));
        QVERIFY2(server.log().contains("joined a session by invite"), qPrintable(server.log()));
        QVERIFY2(errorsLogged(server).isEmpty(), qPrintable(errorsLogged(server).join('\n')));

        // The phone turns: the canvas takes the new shape, the marks are drawn on it again.
        QVERIFY(phone.setWindowSize(844, 390));
        QVERIFY2(phone.waitUntil("const c = document.getElementById('view');"
                                 "return c.width > c.height && window.lucent.marks().rect !== null"
                                 " && window.lucent.marks().rect.w < c.width;",
                                 20000),
                 qPrintable(statusOf(phone)));
        QTest::qWait(1000);
        wrong = marksDrawnNow(phone, 2);
        QVERIFY2(wrong.isEmpty(), qPrintable(wrong));
        QVERIFY2(showsNoError(phone), qPrintable(statusOf(phone)));
        QVERIFY2(sentMessages(phone).isEmpty(), qPrintable(sentMessages(phone).join(", ")));
        QVERIFY2(errorsLogged(server).isEmpty(), qPrintable(errorsLogged(server).join('\n')));

        // A student at a desk opens the same link.
        WebDriver desk(findBrowserTools());
        QVERIFY2(desk.start(1280, 800), qPrintable(desk.error()));
        QVERIFY2(desk.navigate(link), qPrintable(desk.error()));
        wrong = firstScreen(desk, 2);
        QVERIFY2(wrong.isEmpty(), qPrintable(wrong));
        QTest::qWait(1000);
        QVERIFY2(showsNoError(desk), qPrintable(statusOf(desk)));
        QVERIFY2(errorsLogged(server).isEmpty(), qPrintable(errorsLogged(server).join('\n')));

        // A follower by token joins with the session id: it sends the join, nothing else.
        WebDriver byToken(findBrowserTools());
        QVERIFY2(byToken.start(1280, 800), qPrintable(byToken.error()));
        QVERIFY(byToken.navigate(QString("http://127.0.0.1:%1/").arg(server.port())));
        QVERIFY(byToken.sendKeys(byToken.findElement("#token"), kToken));
        QVERIFY(byToken.click(byToken.findElement("#connect")));
        QVERIFY(
            byToken.waitUntil("return !document.getElementById('join-session').disabled;", 20000));
        QVERIFY(byToken.sendKeys(byToken.findElement("#session-id"), session));
        QVERIFY(recordSentMessages(byToken));
        QVERIFY(byToken.click(byToken.findElement("#join-session")));
        wrong = firstScreen(byToken, 2);
        QVERIFY2(wrong.isEmpty(), qPrintable(wrong));
        const int wide = byToken.execute("return document.getElementById('view').width;").toInt();
        QVERIFY(byToken.setWindowSize(900, 700));
        QVERIFY(byToken.waitUntil(
            QString("return document.getElementById('view').width !== %1;").arg(wide), 20000));
        QTest::qWait(1000);
        QVERIFY2(showsNoError(byToken), qPrintable(statusOf(byToken)));
        QCOMPARE(sentMessages(byToken), QStringList{"session-join"});
        QVERIFY2(errorsLogged(server).isEmpty(), qPrintable(errorsLogged(server).join('\n')));

        // Its connection drops: it comes back to the session and asks for nothing else.
        const int drawn = byToken.execute("return window.lucent.stats.framesDrawn;").toInt();
        QVERIFY(byToken.execute("window.sentByPage = []; window.pageSocket.close(); return true;")
                    .toBool());
        QVERIFY2(byToken.waitUntil(QString("const s = window.lucent.session();"
                                           "return window.sentByPage.includes('session-join') &&"
                                           " s !== null && s.role === 'follower' &&"
                                           " window.lucent.stats.framesDrawn > %1;")
                                       .arg(drawn),
                                   30000),
                 qPrintable(statusOf(byToken)));
        wrong = marksDrawnNow(byToken, 2);
        QVERIFY2(wrong.isEmpty(), qPrintable(wrong));
        QTest::qWait(1000);
        QVERIFY2(showsNoError(byToken), qPrintable(statusOf(byToken)));
        QCOMPARE(sentMessages(byToken), (QStringList{"list", "recording-list", "session-join"}));
        QVERIFY2(errorsLogged(server).isEmpty(), qPrintable(errorsLogged(server).join('\n')));
        for (WebDriver* driver : {&phone, &desk, &byToken}) {
            const QString console = driver->consoleLog();
            QVERIFY2(!console.contains("SEVERE"), qPrintable(console));
        }
    }
};

QTEST_GUILESS_MAIN(TestWebFirstScreen)
#include "test_web_first_screen.moc"
