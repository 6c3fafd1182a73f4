#pragma once
// Sending DICOM instances to a PACS: C-STORE over DIMSE (DCMTK) and STOW-RS
// over DICOMweb (Qt Network; needs a QCoreApplication). Files go as they are,
// in their own transfer syntax, so the PACS stores the same bytes.

#include <filesystem>
#include <functional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/pacs/DicomWebClient.h"
#include "core/pacs/PacsNode.h"

namespace lucent {

// What a sender needs of a file: read from its meta header and dataset.
struct InstanceHeader {
    std::filesystem::path file;
    std::string sopClassUid;
    std::string sopInstanceUid;
    std::string transferSyntaxUid;
    std::string studyUid;
    std::string seriesUid;
};

// Reads the header of a DICOM file (not its pixels). Throws PacsError naming
// the file when it is not DICOM or lacks a SOP class, SOP instance or
// transfer syntax UID.
InstanceHeader readInstanceHeader(const std::filesystem::path& file);

// The instances under `path` (a file, or a folder searched recursively) in
// file name order, only those of the series `seriesUid` when it is not empty.
// Files that are not DICOM instances (DICOMDIRs among them) are passed over:
// each is named in `passedOver` with the reason. Throws PacsError when `path`
// does not exist.
std::vector<InstanceHeader> collectInstances(const std::filesystem::path& path,
                                             const std::string& seriesUid,
                                             std::vector<std::string>& passedOver);

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
