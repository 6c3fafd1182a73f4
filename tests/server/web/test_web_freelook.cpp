// Free look in the browser: headless Chromium (chromedriver) follows a teaching
// session on a real lucent-server (real CT); a drag on the canvas starts free
// look (the canvas changes, the presenter's frames do not), "Back to teacher"
// snaps back and the canvas then equals the presenter's frame (>= 50 dB). The
// presenter's page shows how many look on their own and brings everyone back.
// Skips when chromium, chromedriver or the real data are missing.
#include <QDir>
#include <QFileInfo>
#include <QJsonArray>
#include <QTest>

#include "WebDriver.h"
#include "WebServerFixture.h"
#include "core/image/ImageMetrics.h"

using namespace lucent;
using namespace lucent::test;

namespace {

const QString kSeriesDir = QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";

// The canvas as the page drew it.
ImageRGBA8 canvasImage(WebDriver& driver) {
    const QString url =
        driver.execute("return document.getElementById('view').toDataURL('image/png');").toString();
    const QImage q = QImage::fromData(QByteArray::fromBase64(url.section(',', 1).toLatin1()))
                         .convertToFormat(QImage::Format_RGBA8888);
    ImageRGBA8 out = ImageRGBA8::filled(q.width(), q.height());
    for (int y = 0; y < q.height(); ++y) {
        std::copy_n(q.constScanLine(y), 4 * q.width(), out.at(0, y));
    }
    return out;
}

void saveOnFailure(const ImageRGBA8& image, const QString& name, bool failed) {
    if (failed) {
        QImage(image.pixels.data(), image.width, image.height, QImage::Format_RGBA8888)
            .save(QDir::temp().filePath(name));
        qWarning() << "saved" << QDir::temp().filePath(name);
    }
}

int framesDrawn(WebDriver& driver) {
    return driver.execute("return window.lucent.stats.framesDrawn;").toInt();
}

// Waits until the presenter's newest free-look-state says `looking`.
bool presenterSees(RemoteTestClient& presenter, int looking) {
    return QTest::qWaitFor(
        [&] {
            for (qsizetype n = presenter.texts.size() - 1; n >= 0; --n) {
                if (presenter.texts[n]["type"].toString() == "free-look-state") {
                    return presenter.texts[n]["looking"].toInt() == looking;
                }
            }
            return false;
        },
        20000);
}

QString status(WebDriver& driver) {
    return driver.execute("return document.getElementById('status').textContent;").toString() +
           "\n" + driver.consoleLog();
}

} // namespace

class TestWebFreeLook : public QObject {
    Q_OBJECT
private slots:
    void aFollowerLooksAroundAndGoesBackToTheTeacher() {
        const BrowserTools tools = findBrowserTools();
        if (!tools.missing().isEmpty()) {
            QSKIP(qPrintable(tools.missing()));
        }
        if (!QFileInfo(kSeriesDir).isDir()) {
            QSKIP(qPrintable("real data absent: " + kSeriesDir));
        }
        ServerProcess server("cpu", kSeriesDir);
        QVERIFY2(server.started(), qPrintable(server.startError()));

        // A presenter (a protocol client, version 4) shows the series in a session.
        RemoteTestClient presenter(server.port(), {"lucent.v4"});
        QVERIFY(presenter.waitConnected());
        QVERIFY(presenter.authenticate());
        presenter.send({{"type", "session-create"}});
        const QString sessionId = presenter.waitForText("session-created")["session"].toString();
        QVERIFY(!sessionId.isEmpty());
        QVERIFY(!openOnlySeries(presenter, 200).isEmpty());
        QVERIFY(!presenter.waitForText("opened").isEmpty());

        // The browser joins as a follower.
        WebDriver driver(tools);
        QVERIFY2(driver.start(640, 480), qPrintable(driver.error()));
        QVERIFY(driver.navigate(QString("http://127.0.0.1:%1/").arg(server.port())));
        QVERIFY(driver.sendKeys(driver.findElement("#token"), kToken));
        QVERIFY(driver.click(driver.findElement("#connect")));
        QVERIFY(
            driver.waitUntil("return !document.getElementById('join-session').disabled;", 20000));
        QVERIFY(driver.sendKeys(driver.findElement("#session-id"), sessionId));
        QVERIFY(driver.click(driver.findElement("#join-session")));
        QVERIFY2(driver.waitUntil("const s = window.lucent.session();"
                                  "return s !== null && s.role === 'follower' && "
                                  "window.lucent.stats.framesDrawn > 0;",
                                  30000),
                 qPrintable(status(driver)));
        // The presenter's frames at the canvas' size: drawn one to one.
        const QJsonObject canvas = driver
                                       .execute("const c = document.getElementById('view');"
                                                "return {width: c.width, height: c.height};")
                                       .toObject();
        const int width = canvas["width"].toInt(), height = canvas["height"].toInt();
        presenter.change({{"type", "size"}, {"width", width}, {"height", height}});
        QVERIFY(presenter.waitForCurrentFrame());
        QVERIFY2(driver.waitUntil(QString("const h = window.lucent.stats.lastHeader;"
                                          "return h && h.seq === %1;")
                                      .arg(presenter.seq),
                                  30000),
                 qPrintable(status(driver)));
        QVERIFY(
            driver.execute("return document.getElementById('back-to-teacher').hidden;").toBool());
        const ImageRGBA8 before = canvasImage(driver);

        // A drag: free look on, the canvas turns, the presenter's frames do not change.
        const qsizetype presenterFrames = presenter.frames.size();
        const int drawn = framesDrawn(driver);
        QVERIFY(driver.drag(driver.findElement("#view"), "mouse", 0, 0, 150, 0, 6));
        QVERIFY2(driver.waitUntil("return window.lucent.freeLook();", 20000),
                 qPrintable(status(driver)));
        QVERIFY(
            !driver.execute("return document.getElementById('back-to-teacher').hidden;").toBool());
        QVERIFY2(driver.waitUntil(QString("const s = window.lucent.stats;"
                                          "return s.framesDrawn > %1 && s.lastHeader.quality === "
                                          "'still' && window.lucent.view.azimuth !== 0;")
                                      .arg(drawn),
                                  30000),
                 qPrintable(status(driver)));
        const ImageRGBA8 own = canvasImage(driver);
        const double turned = psnr(before, own);
        qInfo("free look in the browser: %.1f dB against the presenter's view (lower: turned)",
              turned);
        QVERIFY2(turned < 35.0, qPrintable(QString("%1 dB").arg(turned)));
        QCOMPARE(presenter.frames.size(), presenterFrames);
        QVERIFY(presenterSees(presenter, 1));

        // Back to teacher: the canvas is the presenter's frame again.
        const int drawnBefore = framesDrawn(driver);
        QVERIFY(driver.click(driver.findElement("#back-to-teacher")));
        QVERIFY2(driver.waitUntil(QString("return !window.lucent.freeLook() && "
                                          "window.lucent.stats.framesDrawn > %1 && "
                                          "window.lucent.stats.lastHeader.seq === %2;")
                                      .arg(drawnBefore)
                                      .arg(presenter.seq),
                                  30000),
                 qPrintable(status(driver)));
        const ImageRGBA8 back = canvasImage(driver);
        const double db = psnr(presenter.frames.back().decoded(), back);
        qInfo("back to teacher: %.1f dB against the presenter's frame", db);
        saveOnFailure(back, "web_freelook_back.png", !(db >= 50.0));
        QVERIFY2(db >= 50.0, qPrintable(QString("%1 dB").arg(db)));
        QVERIFY(
            driver.execute("return document.getElementById('back-to-teacher').hidden;").toBool());

        // Again, and this time the presenter brings everyone back.
        QVERIFY(driver.drag(driver.findElement("#view"), "mouse", 0, 0, -120, 40, 6));
        QVERIFY(driver.waitUntil("return window.lucent.freeLook();", 20000));
        QVERIFY(presenterSees(presenter, 1));
        presenter.send({{"type", "free-look-recall"}});
        QVERIFY2(driver.waitUntil(QString("return !window.lucent.freeLook() && "
                                          "window.lucent.stats.lastHeader.seq === %1;")
                                      .arg(presenter.seq),
                                  30000),
                 qPrintable(status(driver)));
        QVERIFY(driver.waitUntil("return document.getElementById('status').textContent"
                                 ".includes('called everyone back');",
                                 10000));
        QVERIFY(presenterSees(presenter, 0));
        const double recalled = psnr(presenter.frames.back().decoded(), canvasImage(driver));
        QVERIFY2(recalled >= 50.0, qPrintable(QString("%1 dB").arg(recalled)));
    }

    // The presenter's page: how many look on their own, and "Bring everyone back".
    void thePresenterBringsEveryoneBack() {
        const BrowserTools tools = findBrowserTools();
        if (!tools.missing().isEmpty()) {
            QSKIP(qPrintable(tools.missing()));
        }
        if (!QFileInfo(kSeriesDir).isDir()) {
            QSKIP(qPrintable("real data absent: " + kSeriesDir));
        }
        ServerProcess server("cpu", kSeriesDir);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        WebDriver driver(tools);
        QVERIFY2(driver.start(1000, 700), qPrintable(driver.error())); // wide: the panel stays
        QVERIFY(driver.navigate(QString("http://127.0.0.1:%1/").arg(server.port())));
        QVERIFY(driver.sendKeys(driver.findElement("#token"), kToken));
        QVERIFY(driver.click(driver.findElement("#connect")));
        QVERIFY(driver.waitUntil(
            "return document.getElementById('series-list').options.length > 0;", 20000));
        QVERIFY(driver.click(driver.findElement("#open")));
        QVERIFY(driver.waitUntil("return window.lucent.stats.framesDrawn > 0;", 30000));
        QVERIFY2(driver.click(driver.findElement("#start-session")), qPrintable(driver.error()));
        QVERIFY2(driver.waitUntil("const s = window.lucent.session();"
                                  "return s !== null && s.role === 'presenter';",
                                  20000),
                 qPrintable(status(driver)));
        const QString sessionId = driver.execute("return window.lucent.session().id;").toString();
        QVERIFY(driver.execute("return document.getElementById('recall-free-look').disabled;")
                    .toBool());

        // A student looks on their own: the page says so and may bring them back.
        RemoteTestClient student(server.port(), {"lucent.v4"});
        QVERIFY(student.waitConnected() && student.authenticate());
        student.send({{"type", "session-join"}, {"session", sessionId}});
        QVERIFY(!student.waitForText("opened").isEmpty());
        student.send({{"type", "free-look"}, {"state", "start"}});
        QVERIFY(!student.waitForText("free-look-started").isEmpty());
        QVERIFY2(driver.waitUntil("const b = document.getElementById('recall-free-look');"
                                  "return !b.hidden && !b.disabled && document.getElementById("
                                  "'free-look-info').textContent.startsWith('1 follower');",
                                  20000),
                 qPrintable(status(driver)));
        QVERIFY(driver.click(driver.findElement("#recall-free-look")));
        QCOMPARE(student.waitForText("free-look-ended")["reason"].toString(), "recalled");
        QVERIFY(driver.waitUntil("return document.getElementById('recall-free-look').disabled;",
                                 20000));
    }
};

QTEST_GUILESS_MAIN(TestWebFreeLook)
#include "test_web_freelook.moc"
