// C-STORE SCU: each instance in its own transfer syntax on one association.
#include <map>
#include <set>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmnet/diutil.h>

#include "core/pacs/DimseAssociation_p.h"
#include "core/pacs/InstanceSender.h"

namespace lucent {
namespace {

// The largest number of presentation contexts one association can propose.
constexpr std::size_t kMaxContexts = 128;

std::vector<ProposedContext> contextsFor(const std::vector<InstanceHeader>& instances) {
    std::map<std::string, std::set<std::string>> syntaxesOf;
    for (const InstanceHeader& h : instances) {
        syntaxesOf[h.sopClassUid].insert(h.transferSyntaxUid);
    }
    std::vector<ProposedContext> out;
    for (const auto& [sop, syntaxes] : syntaxesOf) {
        for (const std::string& ts : syntaxes) {
            out.push_back({sop, {ts}});
        }
        // Uncompressed as a fallback when the PACS takes none of the files' own.
        out.push_back(
            {sop,
             {UID_LittleEndianExplicitTransferSyntax, UID_LittleEndianImplicitTransferSyntax}});
    }
    if (out.size() > kMaxContexts) {
        throw PacsError("cannot send " + std::to_string(instances.size()) +
                        " instances on one association: they need " + std::to_string(out.size()) +
                        " presentation contexts (at most " + std::to_string(kMaxContexts) +
                        "); send fewer SOP classes at once");
    }
    return out;
}

bool isWarning(Uint16 status) {
    return status == STATUS_STORE_Warning_CoercionOfDataElements ||
           status == STATUS_STORE_Warning_DataSetDoesNotMatchSOPClass ||
           status == STATUS_STORE_Warning_ElementsDiscarded;
}

std::string statusText(Uint16 status) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%04X", status);
    return std::string("status ") + hex + " (" + DU_cstoreStatusString(status) + ")";
}

} // namespace

SendResult sendByCStore(const PacsNode& node, const PacsSettings& settings,
                        const std::vector<InstanceHeader>& instances, const SendControl& control) {
    SendResult result;
    for (const InstanceHeader& h : instances) {
        result.instances.push_back({h.file, h.sopInstanceUid, SentInstance::Outcome::NotSent, ""});
    }
    if (instances.empty()) {
        return result;
    }
    std::vector<ProposedContext> contexts;
    try {
        contexts = contextsFor(instances);
    } catch (const PacsError& e) {
        throw PacsError(node.describe() + ": " + e.what());
    }
    DimseAssociation association(node, settings, {}, nullptr, {}, contexts);
    DcmSCU& scu = association.scu();
    const int total = static_cast<int>(instances.size());
    for (int k = 0; k < total; ++k) {
        SentInstance& out = result.instances[k];
        const InstanceHeader& h = instances[k];
        if (control.stop.stop_requested()) {
            result.cancelled = true;
            out.message = "cancelled";
            continue;
        }
        if (!scu.isConnected()) {
            out.outcome = SentInstance::Outcome::Failed;
            out.message = node.describe() + ": the association ended before this instance";
            continue;
        }
        T_ASC_PresentationContextID pc =
            scu.findPresentationContextID(h.sopClassUid.c_str(), h.transferSyntaxUid.c_str());
        if (pc == 0) {
            pc = scu.findPresentationContextID(h.sopClassUid.c_str(), "");
        }
        if (pc == 0) {
            out.outcome = SentInstance::Outcome::Failed;
            out.message = node.describe() + " accepts no " +
                          dcmFindNameOfUID(h.sopClassUid.c_str(), h.sopClassUid.c_str()) +
                          " (SOP class " + h.sopClassUid + ")";
        } else {
            Uint16 status = 0;
            const OFCondition c = scu.sendSTORERequest(pc, h.file.c_str(), nullptr, status);
            if (c.bad()) {
                out.outcome = SentInstance::Outcome::Failed;
                out.message = node.describe() + ": C-STORE failed: " + c.text();
            } else if (status == STATUS_Success) {
                out.outcome = SentInstance::Outcome::Stored;
            } else if (isWarning(status)) {
                out.outcome = SentInstance::Outcome::StoredWithWarning;
                out.message = statusText(status);
            } else {
                out.outcome = SentInstance::Outcome::Failed;
                out.message = node.describe() + " refused it: " + statusText(status);
            }
        }
        if (control.onProgress) {
            control.onProgress(k + 1, total);
        }
    }
    return result;
}

} // namespace lucent
