#include "server/DicomIntake.h"

#include <QLoggingCategory>

#include "core/pacs/StorageScp.h"

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcIntake, "lucent.server.dicom")

constexpr int kPollMs = 200;

} // namespace

DicomIntake::DicomIntake(const std::filesystem::path& storeRoot, const std::string& aeTitle,
                         int port, int quietMs, std::function<void()> arrived, QObject* parent)
    : QObject(parent),
      scp_(std::make_unique<StorageScp>(storeRoot, StorageScpSettings{aeTitle, port})),
      arrived_(std::move(arrived)), quietMs_(quietMs) {
    clock_.start();
    connect(&pollTimer_, &QTimer::timeout, this, &DicomIntake::poll);
    pollTimer_.start(kPollMs);
}

DicomIntake::~DicomIntake() = default;

int DicomIntake::port() const {
    return scp_->port();
}

const std::string& DicomIntake::aeTitle() const {
    return scp_->aeTitle();
}

void DicomIntake::poll() {
    const int failed = scp_->failed();
    const int count = scp_->received() + failed;
    const qint64 now = clock_.elapsed();
    if (count != seen_) {
        seen_ = count;
        quietSince_ = now;
        waiting_ = true;
        return;
    }
    if (waiting_ && now - quietSince_ >= quietMs_) {
        waiting_ = false;
        // Counts only: what arrived may identify a patient.
        qCInfo(lcIntake) << scp_->received() << "instance(s) received by C-STORE so far," << failed
                         << "failed";
        arrived_();
    }
}

} // namespace lucent::remote
