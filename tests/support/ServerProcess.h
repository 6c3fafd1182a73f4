#pragma once
// For every test that talks to a render server: a real lucent-server process
// on a loopback port (a free one, or the one it had, to come back after a
// kill), with its own temporary store and token file, serving a synthetic CT
// volume or the data the test names, with any further options.

#include <QFile>
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>
#include <QUrl>

#include <cmath>
#include <cstdint>

#include "core/formats/MetaImage.h"
#include "core/volume/Volume.h"

namespace lucent::test {

inline constexpr char kToken[] = "s3cret-token-for-tests";
// A second token that cannot ride in a WebSocket subprotocol ('/', '=' are
// separators): the browser client sends it in the first message instead.
inline constexpr char kTokenNotASubprotocol[] = "b64/token+for=tests==";

// Writes a token file as lucent-server wants it: only its owner may read it
// (mode 0600; the server refuses one that its group or others can read).
inline bool writeTokenFile(const QString& path, const QByteArray& contents) {
    QFile file(path);
    return file.open(QIODevice::WriteOnly, QFileDevice::ReadOwner | QFileDevice::WriteOwner) &&
           file.setPermissions(QFileDevice::ReadOwner | QFileDevice::WriteOwner) &&
           file.write(contents) == contents.size();
}

// A 48 x 40 x 36 CT (HU, int16): air, an off-centre bone ball and a soft
// tissue block, so that the camera's turn shows in the image.
inline Volume syntheticCt() {
    VolumeGeometry g;
    g.dims = {48, 40, 36};
    g.spacing = {0.9, 0.9, 1.2};
    Volume v(g, VoxelType::Int16);
    v.modality = "CT";
    v.description = "synthetic";
    auto voxels = v.voxels<std::int16_t>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const double ball = std::hypot(i - 30.0, j - 18.0, k - 20.0);
                const bool block = i > 6 && i < 22 && j > 8 && j < 30 && k > 5 && k < 28;
                const double hu = ball < 9.0 ? 1200.0 - 40.0 * ball
                                  : block    ? 60.0 + 3 * k
                                             : -1000.0;
                voxels[v.linearIndex(i, j, k)] = static_cast<std::int16_t>(hu);
            }
        }
    }
    return v;
}

class ServerProcess {
public:
    enum class Start { Now, Later };

    // Serves `data` (the synthetic CT when empty) with the `backend` and
    // `extraArguments` (a later --store or --listen wins over ours). Started
    // now: a failed start fails the test and startError() says why.
    // `launcher`: the program and arguments that start lucent-server (mpirun
    // -n 2 ... for a distributed server); empty: lucent-server itself.
    explicit ServerProcess(const QString& backend = "cpu", const QString& data = {},
                           const QStringList& extraArguments = {}, Start when = Start::Now,
                           const QStringList& launcher = {})
        : backend_(backend), extraArguments_(extraArguments), launcher_(launcher) {
        if (!dir_.isValid()) {
            error_ = "no temporary directory";
            return;
        }
        volumeFile_ = dir_.filePath("ct.mhd");
        writeMetaImage(syntheticCt(), volumeFile_.toStdString());
        data_ = data.isEmpty() ? volumeFile_ : data;
        if (!writeTokenFile(tokenFile(), QByteArray("# test tokens\n") + kToken + "\n" +
                                             kTokenNotASubprotocol + "\n")) {
            error_ = "cannot write the token file " + tokenFile();
            return;
        }
        if (when == Start::Now && !start().isEmpty()) {
            QTest::qVerify(false, "server.started()", qPrintable(error_), __FILE__, __LINE__);
        }
    }
    ~ServerProcess() { stop(); }
    ServerProcess(const ServerProcess&) = delete;
    ServerProcess& operator=(const ServerProcess&) = delete;

    // Empty when it listens, else why not. After kill() it comes back on the
    // port it had.
    QString start() {
        process_ = std::make_unique<QProcess>();
        process_->setProcessChannelMode(QProcess::SeparateChannels);
        const QString server = QString(LUCENT_BIN_DIR) + "/lucent-server";
        const QStringList arguments =
            QStringList{"--listen",     QString("127.0.0.1:%1").arg(port_),
                        "--store",      storeDir(),
                        "--data",       data_,
                        "--token-file", tokenFile(),
                        "--backend",    backend_} +
            extraArguments_;
        if (launcher_.isEmpty()) {
            process_->start(server, arguments);
        } else {
            process_->start(launcher_.front(), launcher_.mid(1) + QStringList{server} + arguments);
        }
        QString out;
        (void)QTest::qWaitFor(
            [&] {
                out += QString::fromUtf8(process_->readAllStandardOutput());
                return out.contains("listening on") || process_->state() == QProcess::NotRunning;
            },
            60000);
        startupOutput_ = out;
        const qsizetype at = out.indexOf("listening on 127.0.0.1:");
        if (at < 0) {
            error_ = "lucent-server did not start: " + out + log();
            return error_;
        }
        port_ = quint16(out.mid(at + 23).trimmed().toUInt());
        error_.clear();
        return {};
    }
    // SIGTERM, and SIGKILL when it has not ended 10 s later.
    void stop() {
        if (process_ && process_->state() != QProcess::NotRunning) {
            process_->terminate();
            if (!process_->waitForFinished(10000)) {
                process_->kill();
                process_->waitForFinished();
            }
        }
    }
    // SIGKILL: no goodbye to the clients.
    void kill() {
        if (process_ && process_->state() != QProcess::NotRunning) {
            process_->kill();
            process_->waitForFinished(10000);
        }
    }

    bool started() const { return error_.isEmpty() && port_ > 0; }
    // The process id of the running server; 0 when none runs.
    qint64 pid() const { return process_ ? process_->processId() : 0; }
    QString startError() const { return error_; }
    quint16 port() const { return port_; }
    QUrl url() const { return QUrl(QString("ws://127.0.0.1:%1/").arg(port_)); }
    QString dir() const { return dir_.path(); }
    QString storeDir() const { return dir_.filePath("store"); }
    QString volumeFile() const { return volumeFile_; }
    QString tokenFile() const { return dir_.filePath("tokens"); }
    // What the server printed on stdout up to "listening on".
    const QString& startupOutput() const { return startupOutput_; }
    // What the server wrote to stderr so far (its log).
    QString log() {
        if (process_) {
            log_ += QString::fromUtf8(process_->readAllStandardError());
        }
        return log_;
    }

private:
    QTemporaryDir dir_;
    QString backend_;
    QStringList extraArguments_;
    QStringList launcher_;
    QString volumeFile_;
    QString data_;
    std::unique_ptr<QProcess> process_;
    quint16 port_ = 0;
    QString error_;
    QString startupOutput_;
    QString log_;
};

} // namespace lucent::test
