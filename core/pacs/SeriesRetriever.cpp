#include "core/pacs/SeriesRetriever.h"

#include <optional>

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>

#include "core/pacs/DimseAssociation_p.h"
#include "core/pacs/IncomingInstance_p.h"

namespace lucent {
namespace {

constexpr Uint16 kSuccess = 0x0000;
constexpr Uint16 kPending = 0xFF00;
constexpr Uint16 kPendingWarning = 0xFF01;
constexpr Uint16 kOutOfResources = 0xA700;

std::string text(DcmItem& d, const DcmTagKey& tag) {
    OFString value;
    d.findAndGetOFStringArray(tag, value);
    return value.c_str();
}

// Receives the instances a C-GET sends back: each is written whole to a
// temporary name in the store and then moved in.
class StoringScu : public DcmSCU {
public:
    StoringScu(StudyStore& store, const RetrieveControl& control, int toFetch)
        : store_(store), control_(control), toFetch_(toFetch) {}

    int received = 0;
    int duplicates = 0;
    int failed = 0;
    std::string storeError;

protected:
    OFCondition handleSTORERequest(const T_ASC_PresentationContextID, DcmDataset* incoming,
                                   OFBool& continueSession, Uint16& status) override {
        const std::unique_ptr<DcmDataset> dataset(incoming); // ours to delete
        continueSession = OFTrue;
        status = kSuccess;
        if (control_.stop.stop_requested()) {
            continueSession = OFFalse;
            status = kOutOfResources;
            return EC_Normal;
        }
        try {
            (storeIncoming(*dataset, store_) ? received : duplicates) += 1;
        } catch (const StoreError& e) {
            ++failed;
            storeError = e.what();
            status = kOutOfResources;
        }
        if (control_.onProgress) {
            control_.onProgress(received + duplicates + failed, toFetch_);
        }
        return EC_Normal;
    }

private:
    StudyStore& store_;
    const RetrieveControl& control_;
    int toFetch_;
};

// Follows a C-MOVE's pending responses: reports progress and, on cancel,
// sends C-CANCEL and stops waiting (the association is then aborted, so the
// PACS stops the sub-operations whether or not it honours C-CANCEL).
class MovingScu : public DcmSCU {
public:
    explicit MovingScu(const RetrieveControl& control) : control_(control) {}
    bool cancelled = false;

protected:
    OFCondition handleMOVEResponse(const T_ASC_PresentationContextID presID,
                                   RetrieveResponse* response,
                                   OFBool& waitForNextResponse) override {
        const OFCondition c = DcmSCU::handleMOVEResponse(presID, response, waitForNextResponse);
        if (waitForNextResponse && control_.onProgress) {
            const int done = response->m_numberOfCompletedSubops +
                             response->m_numberOfFailedSubops + response->m_numberOfWarningSubops;
            control_.onProgress(done, done + response->m_numberOfRemainingSubops);
        }
        if (waitForNextResponse && control_.stop.stop_requested()) {
            cancelled = true;
            sendCANCELRequest(presID);
            waitForNextResponse = OFFalse;
        }
        return c;
    }

private:
    const RetrieveControl& control_;
};

struct SeriesListing {
    SeriesInfo info;
    int seriesNumber = 0;
    std::vector<std::string> instances;
};

SeriesListing listInstances(const PacsNode& node, const PacsSettings& settings,
                            const std::string& studyUid, const std::string& seriesUid) {
    DimseAssociation a(node, settings, {UID_FINDStudyRootQueryRetrieveInformationModel});
    const T_ASC_PresentationContextID pc =
        a.context(UID_FINDStudyRootQueryRetrieveInformationModel, "C-FIND queries");
    DcmDataset q;
    q.putAndInsertString(DCM_QueryRetrieveLevel, "IMAGE");
    q.putAndInsertString(DCM_StudyInstanceUID, studyUid.c_str());
    q.putAndInsertString(DCM_SeriesInstanceUID, seriesUid.c_str());
    q.putAndInsertString(DCM_SOPInstanceUID, "");
    for (const DcmTagKey& key : {DCM_PatientName, DCM_PatientID, DCM_StudyDate, DCM_Modality,
                                 DCM_SeriesDescription, DCM_SeriesNumber}) {
        q.putAndInsertString(key, "");
    }
    OwnedResponses<QRResponse> r;
    if (const OFCondition c = a.scu().sendFINDRequest(pc, &q, &r.list); c.bad()) {
        a.fail("C-FIND of the series' instances failed", c);
    }
    SeriesListing out;
    out.info.studyUid = studyUid;
    out.info.seriesUid = seriesUid;
    for (QRResponse* resp : r.list) {
        if ((resp->m_status == kPending || resp->m_status == kPendingWarning) &&
            resp->m_dataset != nullptr) {
            DcmDataset& d = *resp->m_dataset;
            out.instances.push_back(text(d, DCM_SOPInstanceUID));
            out.info.patientName = text(d, DCM_PatientName);
            out.info.patientId = text(d, DCM_PatientID);
            out.info.studyDate = text(d, DCM_StudyDate);
            out.info.modality = text(d, DCM_Modality);
            out.info.description = text(d, DCM_SeriesDescription);
            out.seriesNumber = std::atoi(text(d, DCM_SeriesNumber).c_str());
        }
    }
    return out;
}

// The C-GET/C-MOVE query for what is missing: the series, or a UID list.
void missingQuery(DcmDataset& q, const std::string& studyUid, const std::string& seriesUid,
                  const std::vector<std::string>& missing, std::size_t all) {
    q.putAndInsertString(DCM_StudyInstanceUID, studyUid.c_str());
    q.putAndInsertString(DCM_SeriesInstanceUID, seriesUid.c_str());
    if (missing.size() == all) {
        q.putAndInsertString(DCM_QueryRetrieveLevel, "SERIES");
        return;
    }
    std::string list;
    for (const std::string& sop : missing) {
        list += (list.empty() ? "" : "\\") + sop;
    }
    q.putAndInsertString(DCM_QueryRetrieveLevel, "IMAGE");
    q.putAndInsertString(DCM_SOPInstanceUID, list.c_str());
}

// What the PACS has of a series, what the store lacks, and the result so far.
struct RetrievalPlan {
    SeriesListing listing;
    std::vector<std::string> missing;
    RetrieveResult result;
};

RetrievalPlan planRetrieval(const PacsNode& node, const PacsSettings& settings,
                            const std::string& studyUid, const std::string& seriesUid,
                            StudyStore& store) {
    RetrievalPlan plan;
    plan.listing = listInstances(node, settings, studyUid, seriesUid);
    if (plan.listing.instances.empty()) {
        throw PacsError(node.describe() + ": series " + seriesUid + " of study " + studyUid +
                        " has no instances there");
    }
    RetrieveResult& r = plan.result;
    r.seriesUid = seriesUid;
    r.expected = static_cast<int>(plan.listing.instances.size());
    r.folder = store.seriesFolder(studyUid, seriesUid);
    store.setExpected(plan.listing.info, plan.listing.seriesNumber, r.expected);
    const std::set<std::string> stored = store.instancesOf(seriesUid);
    for (const std::string& sop : plan.listing.instances) {
        if (stored.count(sop) == 0) {
            plan.missing.push_back(sop);
        }
    }
    r.alreadyStored = r.expected - static_cast<int>(plan.missing.size());
    return plan;
}

} // namespace

RetrieveResult retrieveSeries(const PacsNode& node, const PacsSettings& settings,
                              const std::string& studyUid, const std::string& seriesUid,
                              StudyStore& store, const RetrieveControl& control) {
    const RetrievalPlan plan = planRetrieval(node, settings, studyUid, seriesUid, store);
    const SeriesListing& listing = plan.listing;
    const std::vector<std::string>& missing = plan.missing;
    RetrieveResult result = plan.result;

    if (!missing.empty()) {
        std::vector<std::string> storage;
        for (int i = 0; i < numberOfDcmLongSCUStorageSOPClassUIDs; ++i) {
            storage.emplace_back(dcmLongSCUStorageSOPClassUIDs[i]);
        }
        auto scu = std::make_unique<StoringScu>(store, control, static_cast<int>(missing.size()));
        StoringScu* receiver = scu.get();
        DimseAssociation a(node, settings, {UID_GETStudyRootQueryRetrieveInformationModel},
                           std::move(scu), storage);
        const T_ASC_PresentationContextID pc =
            a.context(UID_GETStudyRootQueryRetrieveInformationModel, "C-GET");
        DcmDataset q;
        missingQuery(q, studyUid, seriesUid, missing, listing.instances.size());
        OwnedResponses<RetrieveResponse> responses;
        std::optional<StudyStore::Batch> batch(std::in_place, store);
        const OFCondition c = a.scu().sendCGETRequest(pc, &q, &responses.list);
        batch.reset();
        result.received = receiver->received;
        result.alreadyStored += receiver->duplicates;
        result.failed = receiver->failed;
        if (control.stop.stop_requested()) {
            a.scu().abortAssociation();
            throw PacsError(node.describe() + ": retrieval of series " + seriesUid +
                            " cancelled after " + std::to_string(result.received) + " instance(s)");
        }
        if (!receiver->storeError.empty()) {
            throw StoreError(receiver->storeError);
        }
        if (c.bad()) {
            a.fail("C-GET of series " + seriesUid + " interrupted after " +
                       std::to_string(result.received) + " of " + std::to_string(missing.size()) +
                       " instance(s)",
                   c,
                   "what arrived whole is stored, the series stays incomplete: retrieve it "
                   "again for the rest");
        }
    }
    result.complete = store.isComplete(seriesUid);
    return result;
}

RetrieveResult moveSeries(const PacsNode& node, const PacsSettings& settings,
                          const std::string& destinationAe, const std::string& studyUid,
                          const std::string& seriesUid, StudyStore& store,
                          const RetrieveControl& control) {
    checkAeTitle(destinationAe, "move destination");
    const RetrievalPlan plan = planRetrieval(node, settings, studyUid, seriesUid, store);
    const SeriesListing& listing = plan.listing;
    const std::vector<std::string>& missing = plan.missing;
    RetrieveResult result = plan.result;
    const std::size_t before = store.instancesOf(seriesUid).size();
    if (!missing.empty()) {
        auto scu = std::make_unique<MovingScu>(control);
        const MovingScu& mover = *scu;
        DimseAssociation a(node, settings, {UID_MOVEStudyRootQueryRetrieveInformationModel},
                           std::move(scu));
        const T_ASC_PresentationContextID pc =
            a.context(UID_MOVEStudyRootQueryRetrieveInformationModel, "C-MOVE");
        DcmDataset q;
        missingQuery(q, studyUid, seriesUid, missing, listing.instances.size());
        OwnedResponses<RetrieveResponse> responses;
        const OFCondition c =
            a.scu().sendMOVERequest(pc, destinationAe.c_str(), &q, &responses.list);
        if (mover.cancelled || control.stop.stop_requested()) {
            a.scu().abortAssociation();
            throw PacsError(
                node.describe() + ": retrieval of series " + seriesUid + " cancelled after " +
                std::to_string(store.instancesOf(seriesUid).size() - before) + " instance(s)");
        }
        if (c.bad()) {
            a.fail("C-MOVE failed", c);
        }
        const Uint16 status = responses.list.empty() ? 0xC000 : responses.list.back()->m_status;
        std::string comment;
        if (!responses.list.empty() && responses.list.back()->m_statusDetail != nullptr) {
            comment = text(*responses.list.back()->m_statusDetail, DCM_ErrorComment);
        }
        if (status == 0xA801) {
            throw PacsError(node.describe() + ": the PACS does not know the move destination '" +
                            destinationAe +
                            "' (register Lucent's AE title, host and storage port with the PACS)");
        }
        if (status != kSuccess &&
            status != 0xB000) { // 0xB000: finished with failures, counted below
            char hex[8];
            std::snprintf(hex, sizeof hex, "%04X", status);
            const bool nothingSent =
                responses.list.empty() || responses.list.back()->m_numberOfCompletedSubops == 0;
            // Some PACS (Orthanc) answer an unknown destination with a generic failure.
            throw PacsError(
                node.describe() + ": the PACS refused to send to '" + destinationAe +
                "' (C-MOVE status 0x" + hex + (comment.empty() ? std::string() : ", " + comment) +
                ")" +
                (nothingSent
                     ? std::string(": is '") + destinationAe +
                           "' registered with the PACS as a move destination, with Lucent's "
                           "host and storage port?"
                     : std::string()));
        }
        if (!responses.list.empty()) {
            result.failed = responses.list.back()->m_numberOfFailedSubops;
        }
    }
    result.received = static_cast<int>(store.instancesOf(seriesUid).size() - before);
    result.complete = store.isComplete(seriesUid);
    return result;
}

} // namespace lucent
