#pragma once
// One DICOM association with a PACS, opened in the constructor and released
// in the destructor. Private to lucent_pacs: DCMTK stays out of public headers.

#include <memory>
#include <string>
#include <vector>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmnet/scu.h>

#include "core/pacs/PacsNode.h"

namespace lucent {

// Owns the responses DcmSCU hands back as raw pointers.
template <class Response> struct OwnedResponses {
    OFList<Response*> list;
    OwnedResponses() = default;
    OwnedResponses(const OwnedResponses&) = delete;
    OwnedResponses& operator=(const OwnedResponses&) = delete;
    ~OwnedResponses() {
        for (Response* r : list) {
            delete r;
        }
    }
};

// A presentation context proposed as it is (the sender's: a SOP class with
// the transfer syntaxes its files are in).
struct ProposedContext {
    std::string abstractSyntax;
    std::vector<std::string> transferSyntaxes;
};

class DimseAssociation {
public:
    // Proposes the abstract syntaxes (SOP class UIDs) with the uncompressed
    // little-endian transfer syntaxes, and the storage classes in the SCP role
    // (C-GET sends the instances back on this association). scu may be a
    // subclass that handles incoming instances; `contexts` are proposed as
    // they are. Throws PacsError naming the node.
    DimseAssociation(const PacsNode& node, const PacsSettings& settings,
                     const std::vector<std::string>& abstractSyntaxes,
                     std::unique_ptr<DcmSCU> scu = nullptr,
                     const std::vector<std::string>& storageClasses = {},
                     const std::vector<ProposedContext>& contexts = {});
    ~DimseAssociation();
    DimseAssociation(const DimseAssociation&) = delete;
    DimseAssociation& operator=(const DimseAssociation&) = delete;

    DcmSCU& scu() { return *scu_; }
    // The accepted presentation context for a SOP class; PacsError when the PACS refused it.
    T_ASC_PresentationContextID context(const std::string& abstractSyntax, const std::string& what);
    const PacsNode& node() const { return node_; }
    // A PacsError for a failed operation on this association: the node, the
    // operation, why, and (when given) what it means for the user.
    [[noreturn]] void fail(const std::string& operation, const OFCondition& condition,
                           const std::string& consequence = {}) const;

private:
    PacsNode node_;
    PacsSettings settings_;
    std::unique_ptr<DcmSCU> scu_;
    bool open_ = false;
};

} // namespace lucent
