// The browser client end to end: headless Chromium (driven by chromedriver)
// opens the page a real lucent-server serves on loopback, authenticates, opens
// a real CT series, and a mouse drag, a touch drag and a pinch each bring new
// frames that change the canvas. The server is then restarted on the same port
// and the page reconnects by itself. A follower of a teaching session sees the
// presenter's view; the page works over https:// and wss:// too. Skips when
// chromium, chromedriver or the real data are missing.
#include <QDir>
#include <QFileInfo>
#include <QJsonArray>
#include <QTest>

#include <cmath>

#include "WebDriver.h"
#include "WebServerFixture.h"

using namespace lucent::test;

namespace {

// A real CT: 28 slices of 512 x 512 (see ../shared/data/README.md).
const QString kSeriesDir = QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";

// A fingerprint of the canvas pixels and how many of them are not black.
constexpr char kCanvasPixels[] = R"(
const c = document.getElementById('view');
const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
let hash = 0, lit = 0;
for (let i = 0; i < d.length; i += 4) {
  hash = (Math.imul(hash, 31) + d[i] * 65536 + d[i + 1] * 256 + d[i + 2]) | 0;
  if (d[i] + d[i + 1] + d[i + 2] > 30) lit++;
}
return {hash, lit, width: c.width, height: c.height};
)";

// True once a still frame of the canvas' size is drawn after `drawn` frames.
QString stillFrameAfter(int drawn) {
    return QString("const s = window.lucent.stats, c = document.getElementById('view');"
                   "return s.framesDrawn > %1 && s.lastHeader && s.lastHeader.quality === "
                   "'still' && s.lastHeader.width === c.width && s.lastHeader.height === "
                   "c.height;")
        .arg(drawn);
}

int framesDrawn(WebDriver& driver) {
    return driver.execute("return window.lucent.stats.framesDrawn;").toInt();
}

} // namespace

class TestWebBrowser : public QObject {
    Q_OBJECT
private slots:
    void dragRotatesTheRemoteView();
    void followsATeachingSession();
    void worksOverTls();

private:
    bool waitForNewStill(WebDriver& driver, int before, QJsonObject* pixels);
    // After a mouse drag (`afterMouse`): a touch drag turns the view again, a pinch
    // zooms, a right drag pans and arrow keys turn it, each with a new frame.
    void verifyTouchPinchPanKeys(WebDriver& driver, const QString& canvas,
                                 const QJsonObject& afterMouse);
    // The server goes away and comes back on the same port: the page reconnects,
    // opens the same series again and shows the same view.
    void verifyReconnect(WebDriver& driver, ServerProcess& server);
};

bool TestWebBrowser::waitForNewStill(WebDriver& driver, int before, QJsonObject* pixels) {
    if (!driver.waitUntil(stillFrameAfter(before), 30000)) {
        return false;
    }
    *pixels = driver.execute(kCanvasPixels).toObject();
    return true;
}

void TestWebBrowser::dragRotatesTheRemoteView() {
    const BrowserTools tools = findBrowserTools();
    if (!tools.missing().isEmpty()) {
        QSKIP(qPrintable(tools.missing()));
    }
    if (!QFileInfo(kSeriesDir).isDir()) {
        QSKIP(qPrintable("real data absent: " + kSeriesDir));
    }
    auto server = std::make_unique<ServerProcess>("cpu", kSeriesDir);
    QVERIFY2(server->started(), qPrintable(server->startError()));
    const quint16 port = server->port();

    WebDriver driver(tools);
    QVERIFY2(driver.start(640, 480), qPrintable(driver.error()));
    QVERIFY2(driver.navigate(QString("http://127.0.0.1:%1/").arg(port)),
             qPrintable(driver.error()));

    // Authenticate with the token typed into the page.
    const QString token = driver.findElement("#token");
    QVERIFY2(!token.isEmpty(), qPrintable(driver.error()));
    QVERIFY(driver.sendKeys(token, kToken));
    QVERIFY(driver.click(driver.findElement("#connect")));
    QVERIFY2(
        driver.waitUntil("return document.getElementById('series-list').options.length > 0;",
                         20000),
        qPrintable(
            "no series list: " +
            driver.execute("return document.getElementById('status').textContent;").toString() +
            "\n" + driver.consoleLog()));
    QVERIFY(!driver.execute("return location.href;").toString().contains(kToken));
    // The page offers lucent.v4 and the server speaks it (hello's version).
    QCOMPARE(driver.execute("return window.lucent.protocolVersion();").toInt(), 4);

    // Open the series: a still frame of the canvas' size arrives and shows something.
    QVERIFY(driver.click(driver.findElement("#open")));
    QJsonObject before;
    QVERIFY2(
        waitForNewStill(driver, 0, &before),
        qPrintable(
            "no frame: " +
            driver.execute("return document.getElementById('status').textContent;").toString() +
            "\n" + driver.consoleLog()));
    QVERIFY2(before["lit"].toInt() > 100, "the first frame is black");

    // A mouse drag on the canvas turns the view: new frames, other pixels.
    const QString canvas = driver.findElement("#view");
    int drawn = framesDrawn(driver);
    QVERIFY2(driver.drag(canvas, "mouse", -40, 0, 120, 30, 6), qPrintable(driver.error()));
    QJsonObject afterMouse;
    QVERIFY2(waitForNewStill(driver, drawn, &afterMouse), "no frame after the mouse drag");
    QVERIFY(afterMouse["lit"].toInt() > 100);
    QVERIFY2(afterMouse["hash"].toInt() != before["hash"].toInt(),
             "the canvas did not change after the drag");
    QVERIFY(driver.execute("return window.lucent.view.azimuth;").toDouble() != 0.0);

    verifyTouchPinchPanKeys(driver, canvas, afterMouse);
    if (QTest::currentTestFailed()) {
        return;
    }

    // Phone size: the canvas still fills the width and gets frames of its new size.
    drawn = framesDrawn(driver);
    QVERIFY(driver.setWindowSize(390, 800));
    QJsonObject phone;
    QVERIFY2(waitForNewStill(driver, drawn, &phone), "no frame at phone size");
    const double cssWidth =
        driver.execute("return document.getElementById('view').getBoundingClientRect().width;")
            .toDouble();
    QVERIFY2(cssWidth > 300 && cssWidth <= 390, qPrintable(QString::number(cssWidth)));

    // No script errors so far (the console holds no SEVERE entries).
    const QString console = driver.consoleLog();
    QVERIFY2(!console.contains("SEVERE"), qPrintable(console));

    verifyReconnect(driver, *server);
}

void TestWebBrowser::verifyTouchPinchPanKeys(WebDriver& driver, const QString& canvas,
                                             const QJsonObject& afterMouse) {
    // A touch drag turns it again.
    int drawn = framesDrawn(driver);
    QVERIFY2(driver.drag(canvas, "touch", 0, -30, -20, 90, 6), qPrintable(driver.error()));
    QJsonObject afterTouch;
    QVERIFY2(waitForNewStill(driver, drawn, &afterTouch), "no frame after the touch drag");
    QVERIFY(afterTouch["hash"].toInt() != afterMouse["hash"].toInt());

    // Two fingers moving apart zoom in.
    const double zoom = driver.execute("return window.lucent.view.zoom;").toDouble();
    drawn = framesDrawn(driver);
    QVERIFY2(driver.pinch(canvas, 30, 110, 5), qPrintable(driver.error()));
    QJsonObject afterPinch;
    QVERIFY2(waitForNewStill(driver, drawn, &afterPinch), "no frame after the pinch");
    QVERIFY(driver.execute("return window.lucent.view.zoom;").toDouble() > zoom * 1.5);
    QVERIFY(afterPinch["hash"].toInt() != afterTouch["hash"].toInt());

    // A right-button drag pans: the camera's pan goes to the server (the image
    // follows the pointer: the point looked at moves left and up).
    drawn = framesDrawn(driver);
    QVERIFY2(driver.drag(canvas, "mouse", 0, 0, 80, 40, 4, 2), qPrintable(driver.error()));
    QJsonObject afterPan;
    QVERIFY2(waitForNewStill(driver, drawn, &afterPan), "no frame after the pan");
    QVERIFY(afterPan["hash"].toInt() != afterPinch["hash"].toInt());
    const double panRight = driver.execute("return window.lucent.view.panRight;").toDouble();
    const double panUp = driver.execute("return window.lucent.view.panUp;").toDouble();
    QVERIFY2(panRight < -1.0 && panUp > 0.5,
             qPrintable(QString("pan %1, %2 mm").arg(panRight).arg(panUp)));

    // Keys on the focused canvas turn the view too.
    const double azimuth = driver.execute("return window.lucent.view.azimuth;").toDouble();
    drawn = framesDrawn(driver);
    QVERIFY2(driver.sendKeys(canvas, QString(QChar(0xE012)) + QChar(0xE012)),
             qPrintable(driver.error())); // two Left arrows
    QJsonObject afterKeys;
    QVERIFY2(waitForNewStill(driver, drawn, &afterKeys), "no frame after the arrow keys");
    QCOMPARE(driver.execute("return window.lucent.view.azimuth;").toDouble(),
             std::fmod(azimuth + 10.0, 360.0));
}

void TestWebBrowser::verifyReconnect(WebDriver& driver, ServerProcess& server) {
    const quint16 port = server.port();
    server.stop();
    QVERIFY(driver.waitUntil(
        "return document.getElementById('status').textContent.includes('reconnecting');", 20000));
    const int drawn = framesDrawn(driver);
    const QString restarted = server.start();
    QVERIFY2(restarted.isEmpty(), qPrintable(restarted));
    QCOMPARE(server.port(), port);
    QJsonObject reconnected;
    QVERIFY2(
        waitForNewStill(driver, drawn, &reconnected),
        qPrintable(
            "no frame after the server came back: " +
            driver.execute("return document.getElementById('status').textContent;").toString()));
    QVERIFY(reconnected["lit"].toInt() > 100);
}

void TestWebBrowser::followsATeachingSession() {
    const BrowserTools tools = findBrowserTools();
    if (!tools.missing().isEmpty()) {
        QSKIP(qPrintable(tools.missing()));
    }
    if (!QFileInfo(kSeriesDir).isDir()) {
        QSKIP(qPrintable("real data absent: " + kSeriesDir));
    }
    ServerProcess server("cpu", kSeriesDir);
    QVERIFY2(server.started(), qPrintable(server.startError()));

    // A presenter (a protocol client) opens the series and starts a session.
    RemoteTestClient presenter(server.port());
    QVERIFY(presenter.waitConnected());
    QVERIFY(presenter.authenticate());
    presenter.send({{"type", "list"}});
    const QJsonArray series = presenter.waitForText("series")["series"].toArray();
    QVERIFY(!series.isEmpty());
    presenter.send({{"type", "open"}, {"series", series[0].toObject()["uid"].toString()}});
    QVERIFY(!presenter.waitForText("opened").isEmpty());
    presenter.send({{"type", "session-create"}});
    const QString sessionId = presenter.waitForText("session-created")["session"].toString();
    QVERIFY(!sessionId.isEmpty());
    presenter.send({{"type", "size"}, {"width", 200}, {"height", 160}});

    // The browser joins as a follower and shows the session's frames.
    WebDriver driver(tools);
    QVERIFY2(driver.start(640, 480), qPrintable(driver.error()));
    QVERIFY(driver.navigate(QString("http://127.0.0.1:%1/").arg(server.port())));
    QVERIFY(driver.sendKeys(driver.findElement("#token"), kTokenNotASubprotocol));
    QVERIFY(driver.click(driver.findElement("#connect")));
    QVERIFY(driver.waitUntil("return !document.getElementById('join-session').disabled;", 20000));
    QVERIFY(driver.sendKeys(driver.findElement("#session-id"), sessionId));
    QVERIFY(driver.click(driver.findElement("#join-session")));
    QVERIFY2(
        driver.waitUntil("const s = window.lucent.session();"
                         "return s !== null && s.role === 'follower' && "
                         "window.lucent.stats.framesDrawn > 0;",
                         30000),
        qPrintable(
            driver.execute("return document.getElementById('status').textContent;").toString()));
    const QJsonObject first = driver.execute(kCanvasPixels).toObject();
    QVERIFY(first["lit"].toInt() > 100);
    // A follower's rendering choices are the presenter's (its drags look around
    // on its own: test_web_freelook).
    QVERIFY(driver.execute("return document.getElementById('preset').disabled;").toBool());
    QVERIFY(driver.execute("return document.getElementById('mode').disabled;").toBool());

    // The presenter turns the view: the follower's canvas follows.
    const int drawn = framesDrawn(driver);
    presenter.send({{"type", "camera"}, {"azimuth", 90}});
    QVERIFY(driver.waitUntil(QString("return window.lucent.stats.framesDrawn > %1;").arg(drawn),
                             30000));
    QVERIFY(QTest::qWaitFor(
        [&] { return driver.execute(kCanvasPixels)["hash"].toInt() != first["hash"].toInt(); },
        10000));
}

void TestWebBrowser::worksOverTls() {
    const BrowserTools tools = findBrowserTools();
    if (!tools.missing().isEmpty()) {
        QSKIP(qPrintable(tools.missing()));
    }
    if (!QFileInfo(kSeriesDir).isDir()) {
        QSKIP(qPrintable("real data absent: " + kSeriesDir));
    }
    QTemporaryDir dir;
    const SelfSigned files = makeSelfSigned(dir.path());
    if (files.certificate.isEmpty()) {
        QSKIP("the openssl command is missing or failed; cannot make a test certificate");
    }
    ServerProcess server("cpu", kSeriesDir,
                         {"--tls-cert", files.certificate, "--tls-key", files.key});
    QVERIFY2(server.started(), qPrintable(server.startError()));
    WebDriver driver(tools);
    QVERIFY2(driver.start(640, 480, true), qPrintable(driver.error()));
    QVERIFY2(driver.navigate(QString("https://127.0.0.1:%1/").arg(server.port())),
             qPrintable(driver.error()));
    QVERIFY(driver.sendKeys(driver.findElement("#token"), kToken));
    QVERIFY(driver.click(driver.findElement("#connect")));
    QVERIFY(driver.waitUntil("return document.getElementById('series-list').options.length > 0;",
                             20000));
    QVERIFY(driver.click(driver.findElement("#open")));
    QJsonObject pixels;
    QVERIFY2(waitForNewStill(driver, 0, &pixels), "no frame over wss://");
    QVERIFY(pixels["lit"].toInt() > 100);
}

QTEST_GUILESS_MAIN(TestWebBrowser)
#include "test_web_browser.moc"
