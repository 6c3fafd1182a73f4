#include "core/pacs/DimseAssociation_p.h"

#include <algorithm>
#include <cstdlib>
#include <mutex>

#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmnet/diutil.h>
#include <dcmtk/oflog/oflog.h>

namespace lucent {
namespace {

bool mentions(const OFCondition& c, const char* text) {
    return std::string(c.text()).find(text) != std::string::npos;
}

// What went wrong, in words a user can act on.
std::string reason(const OFCondition& c, const PacsSettings& s, const PacsNode& node) {
    if (c == DUL_ASSOCIATIONREJECTED) {
        return "association rejected (calling AE title '" + s.callingAeTitle + "', called '" +
               node.aeTitle + "': is Lucent registered with this PACS, and is its AE title right?)";
    }
    if (c == NET_EC_NoAcceptablePresentationContexts) {
        return "the PACS accepts none of the proposed services";
    }
    if (c == DUL_READTIMEOUT || c == DIMSE_NODATAAVAILABLE || mentions(c, "imeout") ||
        mentions(c, "timed out")) {
        return "no answer within the timeout (" + std::to_string(s.connectTimeoutSeconds) +
               " s to connect, " + std::to_string(s.responseTimeoutSeconds) + " s per response)";
    }
    if (mentions(c, "Connection refused")) {
        return "connection refused (is the PACS running and listening on that port?)";
    }
    if (mentions(c, "Name or service not known") || mentions(c, "unknown host") ||
        mentions(c, "No address")) {
        return "unknown host";
    }
    if (c == DUL_PEERABORTEDASSOCIATION || c == DUL_NETWORKCLOSED) {
        return "the PACS closed the connection";
    }
    if (mentions(c, "Broken pipe") || mentions(c, "Connection reset") ||
        mentions(c, "TCP I/O Error")) {
        return "the connection to the PACS was lost (it closed or stopped)";
    }
    std::string text = c.text(); // DCMTK's, on one line
    std::replace(text.begin(), text.end(), '\n', ' ');
    return text;
}

void prepareDcmtk() {
    static std::once_flag once;
    std::call_once(once, [] {
        // Lucent reports PACS problems itself, once, with the node's name.
        OFLog::configure(OFLogger::FATAL_LOG_LEVEL);
        // DCMTK leaves Nagle's algorithm on unless this is set: every instance
        // of a retrieval then waits for a delayed ACK (8x slower on loopback).
        ::setenv("TCP_NODELAY", "1", 0);
    });
}

} // namespace

DimseAssociation::DimseAssociation(const PacsNode& node, const PacsSettings& settings,
                                   const std::vector<std::string>& abstractSyntaxes,
                                   std::unique_ptr<DcmSCU> customScu,
                                   const std::vector<std::string>& storageClasses,
                                   const std::vector<ProposedContext>& contexts)
    : node_(node), settings_(settings),
      scu_(customScu ? std::move(customScu) : std::make_unique<DcmSCU>()) {
    prepareDcmtk();
    checkAeTitle(settings.callingAeTitle, "our AE title");
    DcmSCU& scu = *scu_;
    scu.setAETitle(settings.callingAeTitle.c_str());
    scu.setPeerAETitle(node.aeTitle.c_str());
    scu.setPeerHostName(node.host.c_str());
    scu.setPeerPort(static_cast<Uint16>(node.port));
    scu.setConnectionTimeout(settings.connectTimeoutSeconds);
    scu.setACSETimeout(static_cast<Uint32>(settings.connectTimeoutSeconds));
    scu.setDIMSEBlockingMode(DIMSE_NONBLOCKING);
    scu.setDIMSETimeout(static_cast<Uint32>(settings.responseTimeoutSeconds));
    OFList<OFString> syntaxes;
    syntaxes.push_back(UID_LittleEndianExplicitTransferSyntax);
    syntaxes.push_back(UID_LittleEndianImplicitTransferSyntax);
    for (const std::string& sop : abstractSyntaxes) {
        scu.addPresentationContext(sop.c_str(), syntaxes);
    }
    for (const std::string& sop : storageClasses) {
        scu.addPresentationContext(sop.c_str(), syntaxes, ASC_SC_ROLE_SCP);
    }
    for (const ProposedContext& pc : contexts) {
        OFList<OFString> own;
        for (const std::string& ts : pc.transferSyntaxes) {
            own.push_back(ts.c_str());
        }
        scu.addPresentationContext(pc.abstractSyntax.c_str(), own);
    }
    if (const OFCondition c = scu.initNetwork(); c.bad()) {
        fail("cannot start networking", c);
    }
    if (const OFCondition c = scu.negotiateAssociation(); c.bad()) {
        fail("cannot open an association", c);
    }
    open_ = true;
}

DimseAssociation::~DimseAssociation() {
    if (open_ && scu_->isConnected()) {
        scu_->releaseAssociation();
    }
}

T_ASC_PresentationContextID DimseAssociation::context(const std::string& abstractSyntax,
                                                      const std::string& what) {
    const T_ASC_PresentationContextID id =
        scu_->findPresentationContextID(abstractSyntax.c_str(), "");
    if (id == 0) {
        throw PacsError(node_.describe() + ": the PACS does not accept " + what);
    }
    return id;
}

void DimseAssociation::fail(const std::string& operation, const OFCondition& condition,
                            const std::string& consequence) const {
    throw PacsError(node_.describe() + ": " + operation + ": " +
                    reason(condition, settings_, node_) +
                    (consequence.empty() ? std::string() : "; " + consequence));
}

} // namespace lucent
