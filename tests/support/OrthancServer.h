#pragma once
// A real Orthanc PACS for tests: started on loopback on free ports, in its own
// temporary folder, with C-ECHO/C-FIND/C-GET/C-MOVE open; stopped on destruction.

#include <QProcess>
#include <QStringList>
#include <QTemporaryDir>

#include <memory>

namespace lucent::test {

class OrthancServer {
public:
    static constexpr const char* kAeTitle = "ORTHANC";

    // Starts Orthanc and waits until it accepts associations. isRunning() says
    // whether that worked; error() says why not (e.g. Orthanc not installed).
    // moveDestinationPort: when not 0, the AE title LUCENT at 127.0.0.1 on that
    // port is registered as a modality (the destination of C-MOVE requests).
    explicit OrthancServer(int moveDestinationPort = 0);
    ~OrthancServer();
    OrthancServer(const OrthancServer&) = delete;
    OrthancServer& operator=(const OrthancServer&) = delete;

    bool isRunning() const;
    const QString& error() const { return error_; }
    int dicomPort() const { return dicomPort_; }
    int httpPort() const { return httpPort_; }
    QString node() const;        // ORTHANC@127.0.0.1:PORT
    QString dicomWebUrl() const; // http://127.0.0.1:PORT/dicom-web

    // Sends files with DCMTK's storescu (C-STORE); false with error() set on failure.
    bool store(const QStringList& files);

    // Kills Orthanc at once (SIGKILL), as a crash would.
    void kill();
    // Starts it again on the same ports and storage; false with error() set on failure.
    bool restart();

    // A loopback port nobody listens on right now, below the ephemeral range and
    // never handed out before in this process.
    static int freePort();

private:
    bool start();

    QString binary_;
    QTemporaryDir dir_;
    std::unique_ptr<QProcess> process_;
    int dicomPort_ = 0;
    int httpPort_ = 0;
    QString error_;
};

} // namespace lucent::test
