#pragma once
// lucent-server's DICOM door: Lucent's storage SCP (C-STORE into the server's
// store, C-ECHO) and the rule that says when pushed series have arrived: when
// no new instance has come for `quietMs`, the store is scanned again and what
// it holds becomes listable and openable. A series pushed in pieces (more
// than `quietMs` apart) shows after each piece and is loaded anew, whole, by
// the next client that opens it.

#include <QElapsedTimer>
#include <QObject>
#include <QTimer>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

namespace lucent {
class StorageScp;
}

namespace lucent::remote {

class DicomIntake : public QObject {
    Q_OBJECT
public:
    // Listens at once (port 0: any free port); throws PacsError when it cannot.
    // `arrived` runs on this thread when instances have come and gone quiet.
    DicomIntake(const std::filesystem::path& storeRoot, const std::string& aeTitle, int port,
                int quietMs, std::function<void()> arrived, QObject* parent = nullptr);
    ~DicomIntake() override;

    int port() const;
    const std::string& aeTitle() const;

private:
    void poll();

    std::unique_ptr<StorageScp> scp_;
    std::function<void()> arrived_;
    QTimer pollTimer_;
    QElapsedTimer clock_;
    int quietMs_;
    int seen_ = 0;          // instances received (and failed) when last polled
    qint64 quietSince_ = 0; // clock_ ms of the last new instance
    bool waiting_ = false;
};

} // namespace lucent::remote
