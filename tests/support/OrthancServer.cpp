#include "OrthancServer.h"

#include <QElapsedTimer>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QStandardPaths>
#include <QTcpServer>
#include <QTcpSocket>
#include <QThread>

#include <random>
#include <set>

namespace lucent::test {

int OrthancServer::freePort() {
    // Below Linux's ephemeral range (32768-60999), never the same twice in a
    // process: a port from bind(0) can go to the next caller (Orthanc's own
    // port on the move destination's) or to an outgoing connection before the
    // test listens on it.
    static std::mt19937 pick(std::random_device{}());
    static std::set<int> handedOut;
    std::uniform_int_distribution<int> below(20000, 32000);
    for (int tries = 0; tries < 500; ++tries) {
        const int port = below(pick);
        QTcpServer probe;
        if (handedOut.count(port) == 0 && probe.listen(QHostAddress::LocalHost, quint16(port))) {
            handedOut.insert(port);
            return port;
        }
    }
    QTcpServer probe;
    probe.listen(QHostAddress::LocalHost, 0);
    return probe.serverPort();
}

OrthancServer::OrthancServer(int moveDestinationPort) {
    binary_ = QStandardPaths::findExecutable("Orthanc", {"/usr/sbin", "/usr/bin"});
    if (binary_.isEmpty()) {
        error_ = "Orthanc is not installed (Debian package orthanc; packaging/install-deps.sh "
                 "installs it)";
        return;
    }
    if (!dir_.isValid()) {
        error_ = "cannot create a temporary folder for Orthanc";
        return;
    }
    dicomPort_ = freePort();
    do {
        httpPort_ = freePort();
    } while (httpPort_ == dicomPort_);
    QJsonObject modalities;
    if (moveDestinationPort != 0) {
        modalities["lucent"] = QJsonArray{"LUCENT", "127.0.0.1", moveDestinationPort};
    }
    const QJsonObject config{
        {"DicomModalities", modalities},
        {"Name", "lucent-test"},
        {"StorageDirectory", dir_.filePath("storage")},
        {"IndexDirectory", dir_.filePath("storage")},
        {"HttpPort", httpPort_},
        {"DicomPort", dicomPort_},
        {"DicomAet", kAeTitle},
        {"RemoteAccessAllowed", false},
        {"AuthenticationEnabled", false},
        {"DicomCheckCalledAet", true},
        {"DicomAlwaysAllowEcho", true},
        {"DicomAlwaysAllowStore", true},
        {"DicomAlwaysAllowFind", true},
        {"DicomAlwaysAllowGet", true},
        {"DicomAlwaysAllowMove", true},
        {"UnknownSopClassAccepted", true},
        {"StorageCompression", false},
        {"LimitFindResults", 0},
        {"LimitFindInstances", 0},
        {"SaveJobs", false},
        {"Plugins", QJsonArray{"/usr/share/orthanc/plugins/libOrthancDicomWeb.so"}},
        {"DicomWeb", QJsonObject{{"Enable", true}, {"Root", "/dicom-web/"}}},
    };
    QFile file(dir_.filePath("orthanc.json"));
    if (!file.open(QIODevice::WriteOnly) || file.write(QJsonDocument(config).toJson()) < 0) {
        error_ = "cannot write the Orthanc configuration";
        return;
    }
    file.close();
    start();
}

bool OrthancServer::start() {
    error_.clear();
    process_ = std::make_unique<QProcess>();
    process_->setStandardOutputFile(dir_.filePath("orthanc.log"));
    process_->setStandardErrorFile(dir_.filePath("orthanc.log"), QIODevice::Append);
    process_->start(binary_, {dir_.filePath("orthanc.json")});
    if (!process_->waitForStarted(10000)) {
        error_ = "Orthanc did not start: " + process_->errorString();
        return false;
    }
    // Ready when the DICOM port takes connections.
    QElapsedTimer timer;
    timer.start();
    while (timer.elapsed() < 30000) {
        if (process_->state() != QProcess::Running) {
            QFile log(dir_.filePath("orthanc.log"));
            log.open(QIODevice::ReadOnly);
            error_ = "Orthanc exited at start: " + QString::fromUtf8(log.readAll().right(2000));
            return false;
        }
        QTcpSocket probe;
        probe.connectToHost(QHostAddress::LocalHost, static_cast<quint16>(dicomPort_));
        if (probe.waitForConnected(200)) {
            probe.disconnectFromHost();
            return true;
        }
        QThread::msleep(100);
    }
    error_ = "Orthanc did not open its DICOM port within 30 s";
    return false;
}

void OrthancServer::kill() {
    if (process_ && process_->state() != QProcess::NotRunning) {
        process_->kill();
        process_->waitForFinished(10000);
    }
}

bool OrthancServer::restart() {
    kill();
    return start();
}

OrthancServer::~OrthancServer() {
    if (process_ && process_->state() != QProcess::NotRunning) {
        process_->terminate();
        if (!process_->waitForFinished(10000)) {
            process_->kill();
            process_->waitForFinished();
        }
    }
}

bool OrthancServer::isRunning() const {
    return error_.isEmpty() && process_ && process_->state() == QProcess::Running;
}

QString OrthancServer::node() const {
    return QString("%1@127.0.0.1:%2").arg(kAeTitle).arg(dicomPort_);
}

QString OrthancServer::dicomWebUrl() const {
    return QString("http://127.0.0.1:%1/dicom-web").arg(httpPort_);
}

bool OrthancServer::store(const QStringList& files) {
    QProcess storescu;
    storescu.start("storescu", QStringList{"-aet", "LUCENTTEST", "-aec", kAeTitle, "127.0.0.1",
                                           QString::number(dicomPort_)} +
                                   files);
    if (!storescu.waitForFinished(120000) || storescu.exitStatus() != QProcess::NormalExit ||
        storescu.exitCode() != 0) {
        error_ =
            "storescu failed: " + QString::fromUtf8(storescu.readAllStandardError().right(2000));
        return false;
    }
    return true;
}

} // namespace lucent::test
