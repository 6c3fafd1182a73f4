#include "core/pacs/StorageScp.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmnet/scp.h>

#include "core/pacs/IncomingInstance_p.h"
#include "core/pacs/PacsNode.h"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace lucent {
namespace {

constexpr Uint16 kSuccess = 0x0000;
constexpr Uint16 kOutOfResources = 0xA700;

// A free TCP port for port 0: bound and released (DcmSCP needs a number).
int anyFreePort() {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_ANY);
    socklen_t len = sizeof a;
    int port = 0;
    if (fd >= 0 && ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0) {
        port = ntohs(a.sin_port);
    }
    if (fd >= 0) {
        ::close(fd);
    }
    return port;
}

} // namespace

struct StorageScp::Scp : DcmSCP {
    std::atomic<bool> stop{false};
    std::unique_ptr<StudyStore>
        store; // opened on the SCP's thread (Qt SQL connections are per thread)
    std::filesystem::path root;
    std::atomic<int>* received = nullptr;
    std::atomic<int>* failed = nullptr;

    OFCondition handleIncomingCommand(T_DIMSE_Message* msg,
                                      const DcmPresentationContextInfo& info) override {
        if (msg->CommandField != DIMSE_C_STORE_RQ) {
            return DcmSCP::handleIncomingCommand(msg, info); // C-ECHO and refusals
        }
        T_DIMSE_C_StoreRQ& request = msg->msg.CStoreRQ;
        DcmDataset* raw = nullptr;
        const OFCondition c = receiveSTORERequest(request, info.presentationContextID, raw);
        const std::unique_ptr<DcmDataset> dataset(raw);
        Uint16 status = kSuccess;
        if (!store) { // the store could not be opened before: try again
            try {
                store = std::make_unique<StudyStore>(root);
            } catch (const std::exception&) {
                store.reset();
            }
        }
        if (c.bad() || !dataset || !store) {
            status = kOutOfResources;
            ++*failed;
        } else {
            try {
                storeIncoming(*dataset, *store);
                ++*received;
            } catch (const std::exception&) {
                status = kOutOfResources;
                ++*failed;
            }
        }
        return c.bad() ? c : sendSTOREResponse(info.presentationContextID, request, status);
    }
    OFBool stopAfterConnectionTimeout() override { return stop.load(); }
    OFBool stopAfterCurrentAssociation() override { return stop.load(); }
};

StorageScp::StorageScp(const std::filesystem::path& storeRoot, const StorageScpSettings& settings)
    : scp_(std::make_unique<Scp>()), aeTitle_(settings.aeTitle) {
    checkAeTitle(settings.aeTitle, "storage SCP AE title");
    port_ = settings.port == 0 ? anyFreePort() : settings.port;
    if (port_ < 1 || port_ > 65535) {
        throw PacsError("storage SCP port " + std::to_string(settings.port) + " is not usable");
    }
    Scp& scp = *scp_;
    scp.root = storeRoot;
    scp.received = &received_;
    scp.failed = &failed_;
    scp.setAETitle(settings.aeTitle.c_str());
    scp.setPort(static_cast<Uint16>(port_));
    scp.setHostLookupEnabled(OFFalse);
    scp.setConnectionBlockingMode(DUL_NOBLOCK);
    scp.setConnectionTimeout(1); // how soon a stop request is noticed
    OFList<OFString> syntaxes;
    for (const char* uid :
         {UID_LittleEndianExplicitTransferSyntax, UID_LittleEndianImplicitTransferSyntax,
          UID_BigEndianExplicitTransferSyntax, UID_DeflatedExplicitVRLittleEndianTransferSyntax,
          UID_JPEGProcess14SV1TransferSyntax, UID_JPEGProcess14TransferSyntax,
          UID_JPEGProcess1TransferSyntax, UID_JPEGProcess2_4TransferSyntax,
          UID_JPEGLSLosslessTransferSyntax, UID_JPEGLSLossyTransferSyntax,
          UID_JPEG2000LosslessOnlyTransferSyntax, UID_JPEG2000TransferSyntax,
          UID_RLELosslessTransferSyntax}) {
        syntaxes.push_back(uid);
    }
    scp.addPresentationContext(UID_VerificationSOPClass, syntaxes);
    for (int i = 0; i < numberOfDcmAllStorageSOPClassUIDs; ++i) {
        scp.addPresentationContext(dcmAllStorageSOPClassUIDs[i], syntaxes);
    }
    if (const OFCondition c = scp.openListenPort(); c.bad()) {
        throw PacsError("storage SCP " + settings.aeTitle + " cannot listen on port " +
                        std::to_string(port_) + ": " + c.text());
    }
    // The store is opened on the SCP thread; a failure there shows as failed instances.
    thread_ = std::jthread([this, root = storeRoot] {
        try {
            scp_->store = std::make_unique<StudyStore>(root);
        } catch (const std::exception&) {
            scp_->store.reset();
        }
        scp_->acceptAssociations();
        scp_->store.reset();
    });
}

StorageScp::~StorageScp() {
    scp_->stop = true;
    if (thread_.joinable()) {
        thread_.join();
    }
}

} // namespace lucent
