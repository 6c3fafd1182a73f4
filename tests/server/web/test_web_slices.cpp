// MPR slices in the browser client (protocol version 4) end to end: headless
// Chromium opens the page of a real lucent-server on loopback, opens a real CT,
// switches the layout to the slices, scrolls with the wheel, picks a window
// preset with a key and moves the crosshair with a click; each slice canvas
// (its pixels read back) equals the workstation's SliceView (the widget itself,
// offscreen) of the same plane and window at 45 dB or more. A follower's page
// shows the presenter's slices and window. Skips when chromium, chromedriver or
// the real data are missing; both images are saved on a failed comparison.
#include <QApplication>
#include <QDir>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QTest>

#include <memory>

#include "WebDriver.h"
#include "WebServerFixture.h"
#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SliceView.h"

using namespace lucent;
using namespace lucent::test;

namespace {

// A real CT: 28 slices of 512 x 512, 5 mm apart (see ../shared/data/README.md).
const QString kSeriesDir = QString(LUCENT_TEST_DATA_DIR) + "/dcm_qa_ct/Philips_S21570/S2010";
const char* const kViews[] = {"axial", "coronal", "sagittal"};

// A slice canvas's pixels (as PNG) and the header of the frame drawn on it.
constexpr char kReadSlice[] = R"(
const c = document.querySelector('#slice-' + arguments[0] + ' .slice-image');
return {png: c.toDataURL('image/png'),
        header: window.lucent.slices.stats.lastHeader[arguments[0]] || null};
)";

ImageRGBA8 toImage(const QImage& image) {
    const QImage q = image.convertToFormat(QImage::Format_RGBA8888);
    ImageRGBA8 out = ImageRGBA8::filled(q.width(), q.height());
    for (int y = 0; y < q.height(); ++y) {
        std::copy_n(q.constScanLine(y), 4 * q.width(), out.at(0, y));
    }
    return out;
}

glm::dvec3 vec3(const QJsonValue& v) {
    const QJsonArray a = v.toArray();
    return {a[0].toDouble(), a[1].toDouble(), a[2].toDouble()};
}

// The workstation's MPR views on the same volume, offscreen.
class DesktopMpr {
public:
    explicit DesktopMpr(std::shared_ptr<const Volume> volume) {
        for (const Orientation o :
             {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
            views_[static_cast<int>(o)] = std::make_unique<SliceView>(o, &cursor_);
            views_[static_cast<int>(o)]->setVolume(volume);
        }
    }
    // What the SliceView of this header's view shows for its crosshair and window
    // at its size.
    QImage image(const QJsonObject& header) {
        SliceView& view = *views_[static_cast<int>(
            *remote::sliceViewNamed(header["view"].toString().toStdString()))];
        view.resize(header["width"].toInt(), header["height"].toInt());
        cursor_.setPoint(vec3(header["crosshair"]));
        const QJsonObject window = header["window"].toObject();
        cursor_.setWindow(window["center"].toDouble(), window["width"].toDouble());
        return view.image();
    }

private:
    MprCursor cursor_;
    std::unique_ptr<SliceView> views_[3];
};

} // namespace

class TestWebSlices : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void slicesEqualTheDesktopsMpr();
    void followerSeesThePresentersSlices();

private:
    // Compares a view's canvas with the desktop's image (>= 45 dB); its header.
    QJsonObject compareWithDesktop(WebDriver& driver, const QString& view, const QString& step);
    // compareWithDesktop for each of the three views; false at the first that differs.
    bool allLikeDesktop(WebDriver& driver, const QString& step);
    // Phone width: the slices stack, each as wide as the page, sized anew.
    void verifyPhoneWidth(WebDriver& driver);
    // The server goes away and comes back: the page restores the slices' crosshair and window.
    void verifyReconnect(WebDriver& driver, ServerProcess& server);
    bool waitForSlices(WebDriver& driver, const QString& condition, int timeoutMs = 30000);

    BrowserTools tools_;
    std::shared_ptr<const Volume> volume_;
    std::unique_ptr<DesktopMpr> desktop_;
};

void TestWebSlices::initTestCase() {
    tools_ = findBrowserTools();
    if (!tools_.missing().isEmpty()) {
        QSKIP(qPrintable(tools_.missing()));
    }
    if (!QFileInfo(kSeriesDir).isDir()) {
        QSKIP(qPrintable("real data absent: " + kSeriesDir));
    }
    const Catalog catalog = scanPath(kSeriesDir.toStdString());
    QCOMPARE(catalog.series.size(), std::size_t(1));
    volume_ = std::make_shared<const Volume>(loadSeries(catalog.series[0]));
    desktop_ = std::make_unique<DesktopMpr>(volume_);
}

bool TestWebSlices::waitForSlices(WebDriver& driver, const QString& condition, int timeoutMs) {
    // `condition` sees h, the last header of a view; true for all three.
    return driver.waitUntil(QString("const all = window.lucent.slices.stats.lastHeader;"
                                    "return ['axial', 'coronal', 'sagittal'].every((v) => {"
                                    "  const h = all[v]; return !!h && (%1); });")
                                .arg(condition),
                            timeoutMs);
}

QJsonObject TestWebSlices::compareWithDesktop(WebDriver& driver, const QString& view,
                                              const QString& step) {
    const QJsonObject read = driver.execute(kReadSlice, {view}).toObject();
    const QJsonObject header = read["header"].toObject();
    const QByteArray png =
        QByteArray::fromBase64(read["png"].toString().section(',', 1).toLatin1());
    const QImage canvas = QImage::fromData(png, "PNG");
    const QImage desktop = desktop_->image(header);
    if (canvas.size() != desktop.size() || canvas.isNull()) {
        qWarning() << "sizes differ:" << canvas.size() << desktop.size();
        return {};
    }
    const double db = psnr(toImage(canvas), toImage(desktop));
    qInfo("%s after %s: %.1f dB against the desktop's SliceView (%dx%d, window %g/%g)",
          qPrintable(view), qPrintable(step), db, canvas.width(), canvas.height(),
          header["window"].toObject()["center"].toDouble(),
          header["window"].toObject()["width"].toDouble());
    if (db < 45.0) {
        const QString stem = QDir::temp().filePath("web-slice-" + view + "-" + step);
        canvas.save(stem + "-browser.png");
        desktop.save(stem + "-desktop.png");
        qWarning() << "saved" << stem + "-browser.png" << stem + "-desktop.png";
        return {};
    }
    return header;
}

void TestWebSlices::slicesEqualTheDesktopsMpr() {
    ServerProcess server("cpu", kSeriesDir);
    QVERIFY2(server.started(), qPrintable(server.startError()));
    WebDriver driver(tools_);
    QVERIFY2(driver.start(900, 700), qPrintable(driver.error()));
    QVERIFY(driver.navigate(QString("http://127.0.0.1:%1/").arg(server.port())));
    QVERIFY(driver.sendKeys(driver.findElement("#token"), kToken));
    QVERIFY(driver.click(driver.findElement("#connect")));
    QVERIFY(driver.waitUntil("return document.getElementById('series-list').options.length > 0;",
                             20000));
    QVERIFY(driver.click(driver.findElement("#open")));
    QVERIFY(driver.waitUntil("return window.lucent.stats.framesDrawn > 0;", 30000));
    // Eight presets from hello in the picker (and "custom").
    QCOMPARE(
        driver.execute("return document.getElementById('window-preset').options.length;").toInt(),
        9);

    // The layout switch: the three slices, at the volume's centre and default window.
    QVERIFY(driver
                .execute("const l = document.getElementById('layout'); l.value = 'mpr';"
                         "l.dispatchEvent(new Event('change')); return true;")
                .toBool());
    QVERIFY2(waitForSlices(driver, "h.window.width === 400"), qPrintable(driver.consoleLog()));
    QJsonObject axial;
    for (const char* view : kViews) {
        const QJsonObject header = compareWithDesktop(driver, view, "open");
        QVERIFY2(!header.isEmpty(), view);
        if (QString(view) == "axial") {
            axial = header;
        }
    }
    const QJsonObject cell =
        driver
            .execute("const r = document.getElementById('slice-axial').getBoundingClientRect();"
                     "return {w: r.width, h: r.height};")
            .toObject();
    QCOMPARE(axial["width"].toInt(), qRound(cell["w"].toDouble())); // the cell's pixels

    // Two wheel notches forward on the axial view: two voxels (5 mm each) deeper.
    const double z0 = vec3(axial["crosshair"]).z;
    const double step = axial["plane"].toObject()["step_mm"].toDouble();
    QVERIFY(std::abs(step - 5.0) < 0.01);
    QVERIFY(driver
                .execute("const o = document.querySelector('#slice-axial .slice-overlay');"
                         "for (let i = 0; i < 2; ++i) o.dispatchEvent(new WheelEvent('wheel', "
                         "{deltaY: -100, bubbles: true, cancelable: true}));"
                         "return true;")
                .toBool());
    // Axial is seen from the feet: its normal (u x v = L x P) points to the head (+z).
    QVERIFY2(waitForSlices(
                 driver,
                 QString("Math.abs(h.crosshair[2] - (%1)) < 1e-6").arg(z0 + 2 * step, 0, 'g', 17)),
             "the crosshair did not move two voxels towards the head");
    QVERIFY(allLikeDesktop(driver, "wheel"));

    // Key 8 on the focused axial slice: the bone window (400/1800), as the desktop's.
    QVERIFY(driver.sendKeys(driver.findElement("#slice-axial .slice-overlay"), "8"));
    QVERIFY(waitForSlices(driver, "h.window.center === 400 && h.window.width === 1800"));
    QCOMPARE(driver.execute("return document.getElementById('window-preset').value;").toString(),
             QString("Bone"));
    QVERIFY(allLikeDesktop(driver, "preset"));

    // A click on the coronal view moves the crosshair there: all three follow.
    const QJsonObject before = driver.execute(kReadSlice, {"sagittal"})["header"].toObject();
    QVERIFY2(
        driver.drag(driver.findElement("#slice-coronal .slice-overlay"), "mouse", 60, -40, 0, 0, 1),
        qPrintable(driver.error()));
    QVERIFY(waitForSlices(driver, QString("Math.abs(h.crosshair[0] - (%1)) > 1")
                                      .arg(vec3(before["crosshair"]).x, 0, 'g', 17)));
    QVERIFY(allLikeDesktop(driver, "click"));

    // A right drag: right widens the window, down raises the level, one unit a pixel.
    QVERIFY2(
        driver.drag(driver.findElement("#slice-axial .slice-overlay"), "mouse", 0, 0, 40, 20, 4, 2),
        qPrintable(driver.error()));
    QVERIFY2(waitForSlices(driver, "h.window.center === 420 && h.window.width === 1840"),
             qPrintable(QJsonDocument(driver.execute(kReadSlice, {"axial"})["header"].toObject())
                            .toJson(QJsonDocument::Compact)));
    QVERIFY(allLikeDesktop(driver, "right-drag"));

    verifyPhoneWidth(driver);
    if (QTest::currentTestFailed()) {
        return;
    }
    verifyReconnect(driver, server);
}

bool TestWebSlices::allLikeDesktop(WebDriver& driver, const QString& step) {
    for (const char* view : kViews) {
        if (compareWithDesktop(driver, view, step).isEmpty()) {
            qWarning() << "the" << view << "slice differs from the desktop's after" << step;
            return false;
        }
    }
    return true;
}

void TestWebSlices::verifyPhoneWidth(WebDriver& driver) {
    const int wide = driver.execute(kReadSlice, {"axial"})["header"].toObject()["width"].toInt();
    QVERIFY(driver.setWindowSize(390, 800));
    QVERIFY2(
        waitForSlices(driver, QString("h.width !== %1 && h.width === Math.round(document."
                                      "getElementById('slice-' + h.view).getBoundingClientRect()."
                                      "width)")
                                  .arg(wide)),
        qPrintable(driver.consoleLog()));
    QVERIFY(allLikeDesktop(driver, "phone"));
    const QString console = driver.consoleLog();
    QVERIFY2(!console.contains("SEVERE"), qPrintable(console));
}

void TestWebSlices::verifyReconnect(WebDriver& driver, ServerProcess& server) {
    const QJsonObject last = driver.execute(kReadSlice, {"axial"})["header"].toObject();
    const int drawn = driver.execute("return window.lucent.slices.stats.framesDrawn;").toInt();
    server.stop();
    QVERIFY(driver.waitUntil(
        "return document.getElementById('status').textContent.includes('reconnecting');", 20000));
    const QString restarted = server.start();
    QVERIFY2(restarted.isEmpty(), qPrintable(restarted));
    const glm::dvec3 at = vec3(last["crosshair"]);
    QVERIFY2(waitForSlices(driver,
                           QString("window.lucent.slices.stats.framesDrawn > %1 && "
                                   "h.window.width === 1840 && h.window.center === 420 && "
                                   "Math.abs(h.crosshair[0] - (%2)) < 1e-6 && "
                                   "Math.abs(h.crosshair[2] - (%3)) < 1e-6")
                               .arg(drawn + 2)
                               .arg(at.x, 0, 'g', 17)
                               .arg(at.z, 0, 'g', 17),
                           60000),
             qPrintable(driver.consoleLog()));
    QVERIFY(allLikeDesktop(driver, "reconnect"));
}

void TestWebSlices::followerSeesThePresentersSlices() {
    ServerProcess server("cpu", kSeriesDir);
    QVERIFY2(server.started(), qPrintable(server.startError()));
    // The presenter: a version 4 protocol client with a session and the bone window.
    RemoteTestClient presenter(server.port(), {"lucent.v4"});
    QVERIFY(presenter.waitConnected() && presenter.authenticate());
    presenter.send({{"type", "list"}});
    const QJsonArray series = presenter.waitForText("series")["series"].toArray();
    QVERIFY(!series.isEmpty());
    presenter.send({{"type", "open"}, {"series", series[0].toObject()["uid"].toString()}});
    presenter.send({{"type", "session-create"}});
    const QString sessionId = presenter.waitForText("session-created")["session"].toString();
    QVERIFY(!sessionId.isEmpty());
    QVERIFY(!presenter.waitForText("opened", 60000).isEmpty());
    presenter.send({{"type", "slices"}, {"size", QJsonArray{160, 128}}, {"window", "Bone"}});

    WebDriver driver(tools_);
    QVERIFY2(driver.start(900, 700), qPrintable(driver.error()));
    QVERIFY(driver.navigate(QString("http://127.0.0.1:%1/").arg(server.port())));
    QVERIFY(driver.sendKeys(driver.findElement("#token"), kToken));
    QVERIFY(driver.click(driver.findElement("#connect")));
    QVERIFY(driver.waitUntil("return !document.getElementById('join-session').disabled;", 20000));
    QVERIFY(driver.sendKeys(driver.findElement("#session-id"), sessionId));
    QVERIFY(driver.click(driver.findElement("#join-session")));
    // The page shows the slices by itself, with the presenter's window.
    QVERIFY2(waitForSlices(driver, "h.window.width === 1800 && h.width === 160"),
             qPrintable(driver.consoleLog()));
    QCOMPARE(driver.execute("return document.getElementById('layout').value;").toString(),
             QString("both"));
    QVERIFY(allLikeDesktop(driver, "joined"));
    // A follower's gestures change nothing: the presenter holds the slices.
    QVERIFY(driver.sendKeys(driver.findElement("#slice-axial .slice-overlay"), "1"));
    QTest::qWait(500);
    QVERIFY(waitForSlices(driver, "h.window.width === 1800", 1000));

    // The presenter scrolls and picks the brain window: the follower's slices follow.
    const QJsonArray centre = presenter.waitForText("opened")["centre"].toArray();
    presenter.send({{"type", "slices"},
                    {"crosshair", QJsonArray{centre[0].toDouble(), centre[1].toDouble(),
                                             centre[2].toDouble() - 20.0}},
                    {"window", "Brain"}});
    QVERIFY(waitForSlices(driver, QString("h.window.width === 80 && "
                                          "Math.abs(h.crosshair[2] - (%1)) < 1e-6")
                                      .arg(centre[2].toDouble() - 20.0, 0, 'g', 17)));
    QVERIFY(allLikeDesktop(driver, "followed"));
}

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestWebSlices test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_web_slices.moc"
