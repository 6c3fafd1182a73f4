#pragma once
// Sending DICOM instances to a PACS: C-STORE over DIMSE (DCMTK) and STOW-RS
// over DICOMweb (Qt Network; needs a QCoreApplication). Files go as they are,
// in their own transfer syntax, so the PACS stores the same bytes.

#include <filesystem>
#include <functional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/exchange/InstanceFiles.h"
#include "core/pacs/DicomWebClient.h"
#include "core/pacs/PacsNode.h"

namespace lucent {

struct SentInstance {
    enum class Outcome { Stored, StoredWithWarning, Failed, NotSent };
    std::filesystem::path file;
    std::string sopInstanceUid;
    Outcome outcome = Outcome::NotSent;
    std::string message; // why it failed, what the warning said, or why it was not sent
};

struct SendResult {
    std::vector<SentInstance> instances; // in the order given
    bool cancelled = false;
    int count(SentInstance::Outcome o) const;
    bool allStored() const; // every instance stored, with or without a warning
};

struct SendControl {
    std::function<void(int done, int total)> onProgress; // after each instance (or batch)
    std::stop_token stop; // cancel between instances: the rest are NotSent
};

// C-STORE of each instance on one association. Throws PacsError naming the
// node when the association cannot be opened; a PACS that refuses an
// instance, or drops the association midway, shows as Failed instances.
SendResult sendByCStore(const PacsNode& node, const PacsSettings& settings,
                        const std::vector<InstanceHeader>& instances,
                        const SendControl& control = {});

// STOW-RS to BASE/studies in batches (multipart/related, application/dicom),
// with each instance's status from the response's Referenced and Failed SOP
// sequences. Throws PacsError naming the URL when the service cannot be reached.
SendResult sendByStow(const DicomWebService& service, const std::vector<InstanceHeader>& instances,
                      const SendControl& control = {});

const char* outcomeName(SentInstance::Outcome o);

} // namespace lucent
