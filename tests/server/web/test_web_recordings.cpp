// Recording and replay in the browser client, end to end with headless
// Chromium: the presenter's page records (Record, a preset, a drag, Stop), the
// recording shows in its list, Step replays it one recorded view a click with
// a frame drawn for each, and Play replays it at the original pace to its end.
// Skips when chromium, chromedriver or the real data are missing.
#include <QFileInfo>
#include <QTest>

#include <cmath>

#include "WebDriver.h"
#include "WebServerFixture.h"

using namespace lucent::test;

namespace {

const QString kSeriesDir = QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";

QString statusOf(WebDriver& driver) {
    return driver
               .execute("return document.getElementById('status').textContent + ' / ' + "
                        "document.getElementById('recording-info').textContent;")
               .toString() +
           "\n" + driver.consoleLog();
}

int framesDrawn(WebDriver& driver) {
    return driver.execute("return window.lucent.stats.framesDrawn;").toInt();
}

// Clicks a control of the panel, scrolled into view first as a user would.
bool press(WebDriver& driver, const QString& id) {
    driver.execute(QString("document.getElementById('%1').scrollIntoView();").arg(id));
    return driver.click(driver.findElement("#" + id));
}

bool waitForFrameAfter(WebDriver& driver, int drawn) {
    return driver.waitUntil(QString("return window.lucent.stats.framesDrawn > %1;").arg(drawn),
                            30000);
}

} // namespace

class TestWebRecordings : public QObject {
    Q_OBJECT
private slots:
    void init() {
        if (const QString missing = browserTestMissing(kSeriesDir); !missing.isEmpty()) {
            QSKIP(qPrintable(missing));
        }
    }

    void recordStepAndPlay() {
        ServerProcess server("cpu", kSeriesDir);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        WebDriver driver(findBrowserTools());
        QVERIFY2(driver.start(1000, 900), qPrintable(driver.error())); // the panel beside the view
        QVERIFY(driver.navigate(QString("http://127.0.0.1:%1/").arg(server.port())));
        QVERIFY(driver.execute("return document.getElementById('recording-group').hidden;")
                    .toBool()); // before a token: nothing to record or list
        QVERIFY(driver.sendKeys(driver.findElement("#token"), kToken));
        QVERIFY(driver.click(driver.findElement("#connect")));
        QVERIFY2(driver.waitUntil(
                     "return document.getElementById('series-list').options.length > 0;", 20000),
                 qPrintable(statusOf(driver)));
        QVERIFY2(press(driver, "open"), qPrintable(driver.error() + statusOf(driver)));
        QVERIFY2(driver.waitUntil("return !document.getElementById('record').disabled;", 30000),
                 qPrintable(statusOf(driver)));
        QVERIFY2(waitForFrameAfter(driver, 0), qPrintable(statusOf(driver)));

        // Record: a preset and a drag.
        QVERIFY2(press(driver, "record"), qPrintable(driver.error() + statusOf(driver)));
        QVERIFY2(driver.waitUntil("return window.lucent.recordings().recording !== null;", 20000),
                 qPrintable(statusOf(driver)));
        int drawn = framesDrawn(driver);
        driver.execute("const p = document.getElementById('preset'); p.value = 'ct-soft-tissue';"
                       "p.dispatchEvent(new Event('change'));");
        QVERIFY2(waitForFrameAfter(driver, drawn), qPrintable(statusOf(driver)));
        drawn = framesDrawn(driver);
        QVERIFY2(driver.drag(driver.findElement("#view"), "mouse", -40, 0, 120, 30, 6),
                 qPrintable(driver.error()));
        QVERIFY2(waitForFrameAfter(driver, drawn), qPrintable(statusOf(driver)));
        QTest::qWait(500); // the drag's last frame
        QVERIFY2(press(driver, "record"), qPrintable(driver.error() + statusOf(driver)));
        QVERIFY2(
            driver.waitUntil(
                "return document.getElementById('recording-list').options.length === 1;", 20000),
            qPrintable(statusOf(driver)));
        QVERIFY(driver.execute("return window.lucent.recordings().recording === null;").toBool());
        const QString info =
            driver.execute("return document.getElementById('recording-info').textContent;")
                .toString();
        QVERIFY2(info.startsWith("recorded "), qPrintable(info));
        const int views = info.section(' ', 1, 1).toInt();
        QVERIFY2(views >= 3, qPrintable(info)); // the start, the preset, the drag's cameras

        // Step: one recorded view a click, each drawn.
        driver.execute("const l = document.getElementById('recording-list'); l.selectedIndex = 0;"
                       "l.dispatchEvent(new Event('change'));");
        for (int view = 0; view < views; ++view) {
            drawn = framesDrawn(driver);
            QVERIFY2(press(driver, "step-recording"),
                     qPrintable(driver.error() + statusOf(driver)));
            if (view == views - 1) {
                QVERIFY2(
                    driver.waitUntil("return window.lucent.recordings().replay === null;", 20000),
                    qPrintable(statusOf(driver)));
            } else {
                QVERIFY2(driver.waitUntil(
                             QString("const r = window.lucent.recordings().replay;"
                                     "return r !== null && r.pace === 'step' && r.view === %1;")
                                 .arg(view),
                             20000),
                         qPrintable(statusOf(driver)));
            }
            QVERIFY2(waitForFrameAfter(driver, drawn),
                     qPrintable(QString("view %1: ").arg(view) + statusOf(driver)));
        }
        QVERIFY2(driver.waitUntil("return document.getElementById('recording-info').textContent"
                                  " === 'replay finished';",
                                  20000),
                 qPrintable(statusOf(driver)));

        // Play: the original pace, to its end, after the page turned away from the
        // recorded camera; it goes on from the recording's last camera.
        const double recordedAzimuth =
            driver.execute("return window.lucent.view.azimuth;").toDouble();
        drawn = framesDrawn(driver);
        QVERIFY2(driver.drag(driver.findElement("#view"), "mouse", 40, 0, 300, 30, 6),
                 qPrintable(driver.error()));
        QVERIFY2(waitForFrameAfter(driver, drawn), qPrintable(statusOf(driver)));
        QTest::qWait(500);
        QVERIFY(std::abs(driver.execute("return window.lucent.view.azimuth;").toDouble() -
                         recordedAzimuth) > 1.0);
        drawn = framesDrawn(driver);
        QVERIFY2(press(driver, "play-recording"), qPrintable(driver.error() + statusOf(driver)));
        QVERIFY2(driver.waitUntil("return window.lucent.recordings().replay !== null;", 20000),
                 qPrintable(statusOf(driver)));
        QVERIFY2(driver.waitUntil("return document.getElementById('recording-info').textContent"
                                  " === 'replay finished';",
                                  60000),
                 qPrintable(statusOf(driver)));
        QVERIFY2(waitForFrameAfter(driver, drawn), qPrintable(statusOf(driver)));
        QVERIFY2(std::abs(driver.execute("return window.lucent.view.azimuth;").toDouble() -
                          recordedAzimuth) < 1e-6,
                 qPrintable(statusOf(driver)));
    }
};

QTEST_GUILESS_MAIN(TestWebRecordings)
#include "test_web_recordings.moc"
