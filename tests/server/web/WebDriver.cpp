#include "WebDriver.h"

#include <QFileInfo>

#include <QEventLoop>
#include <QJsonDocument>
#include <QNetworkReply>
#include <QStandardPaths>
#include <QTcpServer>
#include <QTest>
#include <QTimer>

namespace lucent::test {
namespace {

// The key under which WebDriver answers carry an element's id.
constexpr char kElementKey[] = "element-6066-11e4-a52e-4f735466cecf";
constexpr int kCallTimeoutMs = 60000;

quint16 freeLoopbackPort() {
    QTcpServer probe;
    return probe.listen(QHostAddress::LocalHost, 0) ? probe.serverPort() : 0;
}

QJsonObject pointerMove(int x, int y, const QJsonValue& origin, int durationMs) {
    return {
        {"type", "pointerMove"}, {"x", x}, {"y", y}, {"origin", origin}, {"duration", durationMs}};
}

} // namespace

QString BrowserTools::missing() const {
    if (chromium.isEmpty()) {
        return "chromium is not installed (Debian package chromium)";
    }
    if (chromedriver.isEmpty()) {
        return "chromedriver is not installed (Debian package chromium-driver)";
    }
    return {};
}

QString browserTestMissing(const QString& seriesDir) {
    const BrowserTools tools = findBrowserTools();
    if (!tools.missing().isEmpty()) {
        return tools.missing();
    }
    return QFileInfo(seriesDir).isDir() ? QString() : "real data absent: " + seriesDir;
}

BrowserTools findBrowserTools() {
    BrowserTools tools;
    for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
        if (tools.chromium.isEmpty()) {
            tools.chromium = QStandardPaths::findExecutable(name);
        }
    }
    tools.chromedriver = QStandardPaths::findExecutable("chromedriver");
    return tools;
}

WebDriver::WebDriver(const BrowserTools& tools) : tools_(tools) {}

WebDriver::~WebDriver() {
    if (!session_.isEmpty()) {
        (void)call("DELETE", "/session/" + session_);
    }
    if (driver_.state() != QProcess::NotRunning) {
        driver_.terminate();
        if (!driver_.waitForFinished(5000)) {
            driver_.kill();
            driver_.waitForFinished();
        }
    }
}

QJsonValue WebDriver::call(const QByteArray& verb, const QString& path, const QJsonObject& body) {
    QNetworkRequest request(QUrl(QString("http://127.0.0.1:%1%2").arg(port_).arg(path)));
    request.setHeader(QNetworkRequest::ContentTypeHeader, "application/json; charset=utf-8");
    const QByteArray payload =
        verb == "GET" || verb == "DELETE" ? QByteArray() : QJsonDocument(body).toJson();
    QNetworkReply* reply = network_.sendCustomRequest(request, verb, payload);
    QEventLoop loop;
    QObject::connect(reply, &QNetworkReply::finished, &loop, &QEventLoop::quit);
    QTimer::singleShot(kCallTimeoutMs, &loop, &QEventLoop::quit);
    if (!reply->isFinished()) {
        loop.exec();
    }
    const QJsonObject answer = QJsonDocument::fromJson(reply->readAll()).object();
    const bool finished = reply->isFinished();
    const QString networkError = reply->errorString();
    reply->abort();
    reply->deleteLater();
    if (!finished) {
        error_ = verb + " " + path + ": no answer within the time allowed";
        return QJsonValue::Undefined;
    }
    const QJsonValue value = answer["value"];
    if (value.isObject() && value.toObject().contains("error")) {
        error_ = verb + " " + path + ": " + value["error"].toString() + ": " +
                 value["message"].toString().left(400);
        return QJsonValue::Undefined;
    }
    if (!answer.contains("value")) {
        error_ = verb + " " + path + ": " + networkError;
        return QJsonValue::Undefined;
    }
    return value;
}

bool WebDriver::start(int width, int height, bool acceptInsecureCertificates) {
    if (!tools_.missing().isEmpty()) {
        error_ = tools_.missing();
        return false;
    }
    port_ = freeLoopbackPort();
    driver_.setProcessChannelMode(QProcess::MergedChannels);
    driver_.start(tools_.chromedriver, {QString("--port=%1").arg(port_)});
    if (!driver_.waitForStarted(10000)) {
        error_ = "chromedriver did not start: " + driver_.errorString();
        return false;
    }
    const bool ready = QTest::qWaitFor(
        [this] {
            const QJsonValue status = call("GET", "/status");
            return status.isObject() && status["ready"].toBool();
        },
        20000);
    if (!ready) {
        error_ = "chromedriver is not ready: " + QString::fromUtf8(driver_.readAll());
        return false;
    }
    const QJsonArray args{"--headless=new",
                          "--no-sandbox",
                          "--disable-gpu",
                          "--disable-dev-shm-usage",
                          "--no-first-run",
                          "--no-default-browser-check",
                          "--disable-extensions",
                          "--user-data-dir=" + profile_.path(),
                          QString("--window-size=%1,%2").arg(width).arg(height)};
    const QJsonObject capabilities{
        {"alwaysMatch", QJsonObject{{"browserName", "chrome"},
                                    {"acceptInsecureCerts", acceptInsecureCertificates},
                                    {"goog:chromeOptions",
                                     QJsonObject{{"binary", tools_.chromium}, {"args", args}}},
                                    {"goog:loggingPrefs", QJsonObject{{"browser", "ALL"}}}}}};
    const QJsonValue created = call("POST", "/session", {{"capabilities", capabilities}});
    session_ = created["sessionId"].toString();
    return !session_.isEmpty();
}

bool WebDriver::navigate(const QString& url) {
    return !call("POST", "/session/" + session_ + "/url", {{"url", url}}).isUndefined();
}

QString WebDriver::findElement(const QString& css) {
    const QJsonValue found = call("POST", "/session/" + session_ + "/element",
                                  {{"using", "css selector"}, {"value", css}});
    return found[kElementKey].toString();
}

bool WebDriver::click(const QString& element) {
    return !call("POST", "/session/" + session_ + "/element/" + element + "/click").isUndefined();
}

bool WebDriver::sendKeys(const QString& element, const QString& text) {
    return !call("POST", "/session/" + session_ + "/element/" + element + "/value",
                 {{"text", text}})
                .isUndefined();
}

QJsonValue WebDriver::execute(const QString& script, const QJsonArray& args) {
    return call("POST", "/session/" + session_ + "/execute/sync",
                {{"script", script}, {"args", args}});
}

bool WebDriver::waitUntil(const QString& script, int timeoutMs) {
    return QTest::qWaitFor([&] { return execute(script).toBool(); }, timeoutMs);
}

bool WebDriver::performActions(const QJsonArray& sources) {
    const bool done =
        !call("POST", "/session/" + session_ + "/actions", {{"actions", sources}}).isUndefined();
    (void)call("DELETE", "/session/" + session_ + "/actions");
    return done;
}

bool WebDriver::drag(const QString& element, const QString& pointerType, int x, int y, int dx,
                     int dy, int steps, int button) {
    QJsonArray actions{pointerMove(x, y, QJsonObject{{kElementKey, element}}, 0),
                       QJsonObject{{"type", "pointerDown"}, {"button", button}}};
    for (int n = 1; n <= steps; ++n) {
        actions.append(pointerMove(dx / steps, dy / steps, "pointer", 40));
    }
    actions.append(QJsonObject{{"type", "pointerUp"}, {"button", button}});
    return performActions({QJsonObject{{"type", "pointer"},
                                       {"id", pointerType + "1"},
                                       {"parameters", QJsonObject{{"pointerType", pointerType}}},
                                       {"actions", actions}}});
}

bool WebDriver::pinch(const QString& element, int fromHalfGap, int toHalfGap, int steps) {
    QJsonArray sources;
    for (const int side : {-1, 1}) {
        QJsonArray actions{
            pointerMove(side * fromHalfGap, 0, QJsonObject{{kElementKey, element}}, 0),
            QJsonObject{{"type", "pointerDown"}, {"button", 0}}};
        for (int n = 1; n <= steps; ++n) {
            const int gap = fromHalfGap + (toHalfGap - fromHalfGap) * n / steps;
            actions.append(pointerMove(side * gap, 0, QJsonObject{{kElementKey, element}}, 40));
        }
        actions.append(QJsonObject{{"type", "pointerUp"}, {"button", 0}});
        sources.append(QJsonObject{{"type", "pointer"},
                                   {"id", QString("finger%1").arg(side + 1)},
                                   {"parameters", QJsonObject{{"pointerType", "touch"}}},
                                   {"actions", actions}});
    }
    return performActions(sources);
}

bool WebDriver::setWindowSize(int width, int height) {
    return !call("POST", "/session/" + session_ + "/window/rect",
                 {{"width", width}, {"height", height}})
                .isUndefined();
}

QString WebDriver::consoleLog() {
    const QJsonValue entries =
        call("POST", "/session/" + session_ + "/se/log", {{"type", "browser"}});
    QString log;
    for (const QJsonValue& entry : entries.toArray()) {
        log += entry["level"].toString() + ": " + entry["message"].toString() + "\n";
    }
    return log;
}

} // namespace lucent::test
