#pragma once
// A small W3C WebDriver client for the web test: starts chromedriver on a free
// loopback port and drives one headless Chromium session over its HTTP API
// (QNetworkAccessManager + JSON). Every call waits for its answer.

#include <QJsonArray>
#include <QJsonObject>
#include <QJsonValue>
#include <QNetworkAccessManager>
#include <QProcess>
#include <QString>
#include <QTemporaryDir>

namespace lucent::test {

// Where chromium and chromedriver are; empty strings when missing.
struct BrowserTools {
    QString chromium;
    QString chromedriver;
    QString missing() const; // why the web test cannot run, or empty
};
BrowserTools findBrowserTools();
// Why a browser test on the real series in seriesDir cannot run (no Chromium or
// chromedriver, no data), or empty.
QString browserTestMissing(const QString& seriesDir);

class WebDriver {
public:
    explicit WebDriver(const BrowserTools& tools);
    ~WebDriver();
    WebDriver(const WebDriver&) = delete;
    WebDriver& operator=(const WebDriver&) = delete;

    // Starts chromedriver and a headless session with this window size (trusting
    // any TLS certificate when asked). False with error() set on failure.
    bool start(int width, int height, bool acceptInsecureCertificates = false);
    QString error() const { return error_; }

    bool navigate(const QString& url);
    // The WebDriver id of the first element matching a CSS selector; empty if none.
    QString findElement(const QString& css);
    bool click(const QString& element);
    bool sendKeys(const QString& element, const QString& text);
    // Runs `script` (a function body; `arguments` holds `args`) and gives its result.
    QJsonValue execute(const QString& script, const QJsonArray& args = {});
    // Polls `script` until it returns true, up to timeoutMs.
    bool waitUntil(const QString& script, int timeoutMs);
    // W3C actions: one pointer ("mouse" or "touch") pressing at (x, y) relative
    // to the centre of `element` and moving by (dx, dy) in `steps` moves, with
    // `button` held (0 left, 2 right).
    bool drag(const QString& element, const QString& pointerType, int x, int y, int dx, int dy,
              int steps, int button = 0);
    // Two touch pointers moving apart (pinch open) about the element's centre.
    bool pinch(const QString& element, int fromHalfGap, int toHalfGap, int steps);
    bool setWindowSize(int width, int height);
    // Log lines the browser wrote to its console (for failure messages).
    QString consoleLog();

private:
    QJsonValue call(const QByteArray& verb, const QString& path, const QJsonObject& body = {});
    bool performActions(const QJsonArray& sources);

    BrowserTools tools_;
    QTemporaryDir profile_;
    QProcess driver_;
    QNetworkAccessManager network_;
    quint16 port_ = 0;
    QString session_;
    QString error_;
};

} // namespace lucent::test
