// The presenter's pointer and marks in the browser client, end to end with
// headless Chromium on the demo head CT: a presenter (a C++ client) marks the
// skull; a browser follower (joined by an invite link) draws the mark where the
// frame's projection puts its anchor, and after a 90 degree turn at the
// projection of the 3D anchor (computed here with ViewFrame) within 2 pixels, in
// the mark's colour; the pointer reaches the browser and a second follower; a
// presenter's page marks with its toolbar instead of turning the view.
// Skips when chromium, chromedriver or the demo head CT are missing.
#include <QFileInfo>
#include <QJsonArray>
#include <QTest>

#include "WebDriver.h"
#include "WebServerFixture.h"
#include "core/formats/InVesaliusProject.h"
#include "core/scene/ImageProjection.h"
#include "core/scene/ViewFrame.h"
#include "tests/server/DemoHead.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSide = 256;
const QStringList kV4 = {"lucent.v4"};

QString statusOf(WebDriver& driver) {
    return driver.execute("return document.getElementById('status').textContent;").toString() +
           "\n" + driver.consoleLog();
}

glm::dvec3 anchorAt(const QJsonObject& mark, int n) {
    const QJsonArray a = mark["anchors"].toArray()[n].toArray();
    return {a[0].toDouble(), a[1].toDouble(), a[2].toDouble()};
}

// The drawn mark's n-th point: image fraction and canvas pixel.
struct DrawnPoint {
    glm::dvec2 fraction{-1.0};
    glm::dvec2 pixel{-1.0};
};
DrawnPoint drawnPoint(WebDriver& driver, int n) {
    const QJsonObject m = driver.execute("return window.lucent.marks().marks[0];").toObject();
    const QJsonArray f = m["fractions"].toArray()[n].toArray();
    const QJsonArray p = m["pixels"].toArray()[n].toArray();
    return {{f[0].toDouble(), f[1].toDouble()}, {p[0].toDouble(), p[1].toDouble()}};
}

// The canvas pixel (r, g, b) at a canvas position.
QJsonArray canvasPixel(WebDriver& driver, glm::dvec2 at) {
    return driver
        .execute("const c = document.getElementById('view').getContext('2d');"
                 "return Array.from(c.getImageData(arguments[0], arguments[1], 1, 1).data);",
                 {std::floor(at.x), std::floor(at.y)})
        .toArray();
}

bool isMarkColour(const QJsonArray& rgba) { // #ff2bd6
    return rgba.size() == 4 && rgba[0].toInt() > 200 && rgba[1].toInt() < 110 &&
           rgba[2].toInt() > 160;
}

} // namespace

class TestWebMarks : public QObject {
    Q_OBJECT
    std::unique_ptr<Volume> head_;

private slots:
    void initTestCase() {
        const BrowserTools tools = findBrowserTools();
        if (!tools.missing().isEmpty()) {
            QSKIP(qPrintable(tools.missing()));
        }
        if (!QFileInfo::exists(kDemoHead)) {
            QSKIP(kDemoHeadMissing);
        }
        head_ = std::make_unique<Volume>(readInVesalius(kDemoHead.toStdString()));
    }

    void aMarkOnTheSkullStaysOnItWhenTheViewTurns() {
        ServerProcess server("cpu", kDemoHead);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        RemoteTestClient presenter(server.port(), kV4);
        QVERIFY(presenter.waitConnected() && presenter.authenticate());
        presenter.send({{"type", "session-create"}});
        const QString session = presenter.waitForText("session-created")["session"].toString();
        QVERIFY(!openOnlySeries(presenter, kSide).isEmpty());
        QVERIFY(!presenter.waitForText("opened").isEmpty());
        presenter.send({{"type", "invite-create"}});
        const QString link = presenter.waitForText("invite-created")["link"].toString();
        QVERIFY(!link.isEmpty());

        // Two followers: the browser (by the join link) and a C++ client.
        WebDriver driver(findBrowserTools());
        QVERIFY2(driver.start(520, 560), qPrintable(driver.error()));
        QVERIFY2(driver.navigate(link), qPrintable(driver.error()));
        QVERIFY2(driver.waitUntil("const s = window.lucent.session();"
                                  "return s !== null && s.role === 'follower' && "
                                  "window.lucent.stats.framesDrawn > 0;",
                                  30000),
                 qPrintable(statusOf(driver)));
        QCOMPARE(driver.execute("return window.lucent.protocolVersion();").toInt(), 4);
        RemoteTestClient other(server.port(), kV4);
        QVERIFY(other.waitConnected() && other.authenticate());
        other.send({{"type", "session-join"}, {"session", session}});
        QVERIFY(!other.waitForText("opened").isEmpty());

        // The pointer reaches both followers; the browser draws it where it was sent.
        presenter.send({{"type", "pointer"}, {"x", 0.3}, {"y", 0.62}});
        QCOMPARE(other.waitForText("pointer")["x"].toDouble(), 0.3);
        QVERIFY2(driver.waitUntil("return window.lucent.marks().pointer !== null;", 20000),
                 qPrintable(statusOf(driver)));
        const QJsonObject shown = driver.execute("return window.lucent.marks();").toObject();
        const QJsonObject rect = shown["rect"].toObject();
        const QJsonArray dot = shown["pointer"].toArray();
        QVERIFY(std::abs(dot[0].toDouble() - (rect["x"].toDouble() + 0.3 * rect["w"].toDouble())) <
                0.01);
        QVERIFY(std::abs(dot[1].toDouble() - (rect["y"].toDouble() + 0.62 * rect["h"].toDouble())) <
                0.01);

        // An arrow whose tip is on the forehead.
        presenter.send({{"type", "mark"},
                        {"kind", "arrow"},
                        {"points", QJsonArray{QJsonArray{0.5, 0.4}, QJsonArray{0.7, 0.25}}}});
        const QJsonObject mark = other.waitForText("mark");
        QCOMPARE(mark["anchors"].toArray().size(), 2);
        const glm::dvec3 tip = anchorAt(mark, 0);
        QVERIFY2(maxValueNear(*head_, tip, 2.0) > 300.0, "the arrow's tip is not on bone");
        QVERIFY2(driver.waitUntil("const m = window.lucent.marks().marks;"
                                  "return m.length === 1 && m[0].pixels !== null;",
                                  20000),
                 qPrintable(statusOf(driver)));
        const DrawnPoint before = drawnPoint(driver, 0);
        QVERIFY2(
            glm::length(before.fraction - glm::dvec2(0.5, 0.4)) * kSide < 2.0,
            qPrintable(QString("drawn at %1,%2").arg(before.fraction.x).arg(before.fraction.y)));

        // The presenter turns the view by 90 degrees: the browser draws the tip where the
        // new view projects its anchor.
        presenter.change({{"type", "camera"}, {"azimuth", 90}});
        QVERIFY2(driver.waitUntil(QString("const h = window.lucent.stats.lastHeader;"
                                          "return h !== null && h.seq >= %1 && "
                                          "window.lucent.marks().marks[0].pixels !== null;")
                                      .arg(presenter.seq),
                                  60000),
                 qPrintable(statusOf(driver)));
        Camera turned;
        turned.azimuth = 90.0;
        const auto expected = projectToImage(
            imageProjection(makeViewFrame(head_->geometry(), turned, kSide, kSide)), tip);
        QVERIFY(expected);
        const DrawnPoint after = drawnPoint(driver, 0);
        const double errorPixels = glm::length(after.fraction - *expected) * kSide;
        qInfo("after the turn the tip is drawn %.3f pixels (of %d) from its anchor's projection",
              errorPixels, kSide);
        QVERIFY2(errorPixels < 2.0,
                 qPrintable(QString("the tip is drawn %1 pixels from its anchor's projection")
                                .arg(errorPixels)));
        QVERIFY2(glm::length(after.fraction - before.fraction) * kSide > 20.0,
                 "the mark did not move with the anatomy");
        // And it is drawn there, in the mark's colour, on the canvas.
        const QJsonArray rgba = canvasPixel(driver, after.pixel);
        QVERIFY2(isMarkColour(rgba),
                 qPrintable("the canvas at the tip is " +
                            QString::fromUtf8(QJsonDocument(rgba).toJson(QJsonDocument::Compact))));

        // The other kinds are drawn too, each at its first anchor.
        QJsonArray freehand;
        for (int n = 0; n <= 20; ++n) {
            freehand.append(QJsonArray{0.4 + 0.01 * n, 0.55 + 0.002 * n * n / 4.0});
        }
        presenter.send({{"type", "mark"},
                        {"kind", "circle"},
                        {"points", QJsonArray{QJsonArray{0.45, 0.45}, QJsonArray{0.5, 0.45}}}});
        presenter.send({{"type", "mark"}, {"kind", "freehand"}, {"points", freehand}});
        presenter.send({{"type", "mark"},
                        {"kind", "text"},
                        {"points", QJsonArray{QJsonArray{0.42, 0.6}}},
                        {"text", "Zygoma <b>&amp;</b>"}});
        QVERIFY2(driver.waitUntil("const m = window.lucent.marks().marks;"
                                  "return m.length === 4 && m.every((k) => k.pixels !== null);",
                                  20000),
                 qPrintable(statusOf(driver)));
        const QJsonArray all = driver.execute("return window.lucent.marks().marks;").toArray();
        for (const QJsonValue& m : all) {
            const QJsonArray first = m.toObject()["pixels"].toArray()[0].toArray();
            const QJsonArray colour =
                canvasPixel(driver, {first[0].toDouble(), first[1].toDouble()});
            QVERIFY2(isMarkColour(colour),
                     qPrintable(
                         m.toObject()["kind"].toString() + " is " +
                         QString::fromUtf8(QJsonDocument(colour).toJson(QJsonDocument::Compact))));
        }
        QCOMPARE(all[3].toObject()["text"].toString(), "Zygoma <b>&amp;</b>"); // text, not markup

        presenter.send({{"type", "marks-clear"}});
        QVERIFY2(driver.waitUntil("return window.lucent.marks().marks.length === 0;", 20000),
                 qPrintable(statusOf(driver)));
    }

    void thePresentersPageMarksWithItsToolbar() {
        ServerProcess server("cpu", kDemoHead);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        WebDriver driver(findBrowserTools());
        QVERIFY2(driver.start(960, 640), qPrintable(driver.error())); // the panel beside the view
        QVERIFY(driver.navigate(QString("http://127.0.0.1:%1/").arg(server.port())));
        QVERIFY(driver.sendKeys(driver.findElement("#token"), kToken));
        QVERIFY(driver.click(driver.findElement("#connect")));
        QVERIFY(driver.waitUntil(
            "return document.getElementById('series-list').options.length > 0;", 20000));
        QVERIFY(driver
                    .execute("document.getElementById('series-list').selectedIndex = 0;"
                             "document.getElementById('series-list')"
                             ".dispatchEvent(new Event('change')); return true;")
                    .toBool());
        QVERIFY(driver.click(driver.findElement("#open")));
        QVERIFY2(driver.waitUntil("return window.lucent.stats.framesDrawn > 0;", 30000),
                 qPrintable(statusOf(driver)));
        QVERIFY2(driver.click(driver.findElement("#start-session")), qPrintable(driver.error()));
        QVERIFY2(driver.waitUntil("const s = window.lucent.session();"
                                  "return s !== null && s.role === 'presenter' && "
                                  "!document.getElementById('mark-tools').hidden;",
                                  20000),
                 qPrintable(statusOf(driver)));
        const QString session = driver.execute("return window.lucent.session().id;").toString();
        RemoteTestClient follower(server.port(), kV4);
        QVERIFY(follower.waitConnected() && follower.authenticate());
        follower.send({{"type", "session-join"}, {"session", session}});
        QVERIFY(!follower.waitForText("opened").isEmpty());
        QVERIFY2(driver.waitUntil("return window.lucent.stats.framesDrawn > 1;", 30000),
                 qPrintable(statusOf(driver)));
        const double azimuth = driver.execute("return window.lucent.view.azimuth;").toDouble();

        // The arrow tool: a drag sends an arrow (tip where it ends), the view does not turn.
        QVERIFY(driver.click(driver.findElement("#mark-tools [data-tool=arrow]")));
        QVERIFY(driver.drag(driver.findElement("#view"), "mouse", -60, 42, 60, -42, 6));
        const QJsonObject mark = follower.waitForText("mark");
        QCOMPARE(mark["kind"].toString(), "arrow");
        QCOMPARE(mark["anchors"].toArray().size(), 2);
        QCOMPARE(driver.execute("return window.lucent.view.azimuth;").toDouble(), azimuth);
        QVERIFY2(driver.waitUntil("return window.lucent.marks().marks.length === 1;", 20000),
                 qPrintable(statusOf(driver)));
        // The drawn tip lies where the drag ended: the element's centre.
        const QJsonObject drawn = driver.execute("return window.lucent.marks();").toObject();
        const QJsonArray tipPixel =
            drawn["marks"].toArray()[0].toObject()["pixels"].toArray()[0].toArray();
        const double width =
            driver.execute("return document.getElementById('view').width;").toDouble();
        const double height =
            driver.execute("return document.getElementById('view').height;").toDouble();
        QVERIFY2(std::abs(tipPixel[0].toDouble() - width / 2) < 3 &&
                     std::abs(tipPixel[1].toDouble() - height / 2) < 3,
                 qPrintable(QString("tip at %1,%2 of %3 x %4")
                                .arg(tipPixel[0].toDouble())
                                .arg(tipPixel[1].toDouble())
                                .arg(width)
                                .arg(height)));

        // The pointer tool: moving over the view points for every follower.
        QVERIFY(driver.click(driver.findElement("#mark-tools [data-tool=pointer]")));
        QVERIFY(driver.drag(driver.findElement("#view"), "mouse", 0, 0, 30, 20, 3));
        QVERIFY(!follower.waitForText("pointer").isEmpty());
        QVERIFY(driver.click(driver.findElement("#mark-tools [data-action=clear]")));
        QVERIFY(!follower.waitForText("marks-cleared").isEmpty());
    }
};

QTEST_GUILESS_MAIN(TestWebMarks)
#include "test_web_marks.moc"
