#include "core/pacs/DimseQuery.h"

#include <algorithm>
#include <cctype>
#include <map>

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>

#include "core/pacs/DimseAssociation_p.h"

namespace lucent {
namespace {

constexpr Uint16 kPending = 0xFF00;
constexpr Uint16 kPendingWarning = 0xFF01;

std::string text(DcmDataset& d, const DcmTagKey& tag) {
    OFString value;
    d.findAndGetOFStringArray(tag, value);
    return value.c_str();
}

int number(DcmDataset& d, const DcmTagKey& tag) {
    const std::string v = text(d, tag);
    try {
        return v.empty() ? 0 : std::stoi(v);
    } catch (const std::exception&) {
        return 0;
    }
}

std::vector<QueryMatch> findOnce(DimseAssociation& a, QueryLevel level, const QueryFilter& f,
                                 const std::string& modality) {
    const bool patientRoot = level == QueryLevel::Patient;
    const char* model = patientRoot ? UID_FINDPatientRootQueryRetrieveInformationModel
                                    : UID_FINDStudyRootQueryRetrieveInformationModel;
    const T_ASC_PresentationContextID pc = a.context(model, "C-FIND queries");
    DcmDataset q;
    q.putAndInsertString(DCM_QueryRetrieveLevel, queryLevelName(level));
    q.putAndInsertString(DCM_PatientName, f.patientName.c_str());
    q.putAndInsertString(DCM_PatientID, f.patientId.c_str());
    if (level == QueryLevel::Patient) {
        q.putAndInsertString(DCM_PatientBirthDate, "");
    } else {
        q.putAndInsertString(DCM_StudyInstanceUID, f.studyUid.c_str());
        q.putAndInsertString(DCM_StudyDate, f.dateRange.c_str());
        q.putAndInsertString(DCM_StudyTime, "");
        q.putAndInsertString(DCM_StudyDescription, "");
        q.putAndInsertString(DCM_AccessionNumber, f.accessionNumber.c_str());
    }
    if (level == QueryLevel::Study) {
        q.putAndInsertString(DCM_ModalitiesInStudy, modality.c_str());
        q.putAndInsertString(DCM_NumberOfStudyRelatedInstances, "");
    }
    if (level == QueryLevel::Series) {
        q.putAndInsertString(DCM_SeriesInstanceUID, "");
        q.putAndInsertString(DCM_Modality, modality.c_str());
        q.putAndInsertString(DCM_SeriesNumber, "");
        q.putAndInsertString(DCM_SeriesDescription, "");
        q.putAndInsertString(DCM_BodyPartExamined, "");
        q.putAndInsertString(DCM_NumberOfSeriesRelatedInstances, "");
    }
    OwnedResponses<QRResponse> r;
    if (const OFCondition c = a.scu().sendFINDRequest(pc, &q, &r.list); c.bad()) {
        a.fail("C-FIND failed", c);
    }
    std::vector<QueryMatch> out;
    for (QRResponse* resp : r.list) {
        if (resp->m_status == kPending || resp->m_status == kPendingWarning) {
            if (resp->m_dataset == nullptr) {
                continue;
            }
            DcmDataset& d = *resp->m_dataset;
            QueryMatch m;
            m.level = level;
            m.patientName = text(d, DCM_PatientName);
            m.patientId = text(d, DCM_PatientID);
            m.patientBirthDate = text(d, DCM_PatientBirthDate);
            m.studyUid = text(d, DCM_StudyInstanceUID);
            m.studyDate = text(d, DCM_StudyDate);
            m.studyTime = text(d, DCM_StudyTime);
            m.studyDescription = text(d, DCM_StudyDescription);
            m.accessionNumber = text(d, DCM_AccessionNumber);
            m.modalitiesInStudy = text(d, DCM_ModalitiesInStudy);
            m.seriesUid = text(d, DCM_SeriesInstanceUID);
            m.seriesDescription = text(d, DCM_SeriesDescription);
            m.modality = text(d, DCM_Modality);
            m.bodyPart = text(d, DCM_BodyPartExamined);
            m.seriesNumber = number(d, DCM_SeriesNumber);
            m.instances =
                number(d, level == QueryLevel::Series ? DCM_NumberOfSeriesRelatedInstances
                                                      : DCM_NumberOfStudyRelatedInstances);
            out.push_back(std::move(m));
        } else if (resp->m_status != 0x0000) {
            char status[8];
            std::snprintf(status, sizeof status, "%04X", resp->m_status);
            throw PacsError("C-FIND refused by the PACS with status 0x" + std::string(status));
        }
    }
    return out;
}

std::string keyOf(const QueryMatch& m) {
    switch (m.level) {
    case QueryLevel::Patient:
        return m.patientId + "|" + m.patientName;
    case QueryLevel::Study:
        return m.studyUid;
    case QueryLevel::Series:
        return m.seriesUid;
    }
    return {};
}

bool isDate(std::string_view s) {
    return s.size() == 8 && std::all_of(s.begin(), s.end(), [](char c) {
               return std::isdigit(static_cast<unsigned char>(c));
           });
}

} // namespace

const char* queryLevelName(QueryLevel level) {
    switch (level) {
    case QueryLevel::Patient:
        return "PATIENT";
    case QueryLevel::Study:
        return "STUDY";
    case QueryLevel::Series:
        return "SERIES";
    }
    return "?";
}

QueryLevel parseQueryLevel(std::string_view name) {
    if (name == "patient") {
        return QueryLevel::Patient;
    }
    if (name == "study") {
        return QueryLevel::Study;
    }
    if (name == "series") {
        return QueryLevel::Series;
    }
    throw PacsError("query level '" + std::string(name) + "' is not one of patient, study, series");
}

void QueryFilter::validate() const {
    if (!dateRange.empty()) {
        const std::size_t dash = dateRange.find('-');
        const std::string_view d(dateRange);
        const bool ok = dash == std::string::npos
                            ? isDate(d)
                            : (dash == 0 || isDate(d.substr(0, dash))) &&
                                  (dash + 1 == d.size() || isDate(d.substr(dash + 1))) &&
                                  d.size() > 1;
        if (!ok) {
            throw PacsError("date range '" + dateRange +
                            "' is not YYYYMMDD, YYYYMMDD-YYYYMMDD, YYYYMMDD- or -YYYYMMDD");
        }
    }
    for (const std::string& m : modalities) {
        if (m.empty() || m.size() > 16 || m.find('\\') != std::string::npos) {
            throw PacsError("modality '" + m + "' is not a DICOM modality code");
        }
    }
}

void echo(const PacsNode& node, const PacsSettings& settings) {
    DimseAssociation a(node, settings, {UID_VerificationSOPClass});
    const T_ASC_PresentationContextID pc = a.context(UID_VerificationSOPClass, "C-ECHO");
    if (const OFCondition c = a.scu().sendECHORequest(pc); c.bad()) {
        a.fail("C-ECHO failed", c);
    }
}

std::vector<QueryMatch> find(const PacsNode& node, const PacsSettings& settings, QueryLevel level,
                             const QueryFilter& filter) {
    filter.validate();
    DimseAssociation a(node, settings,
                       {UID_FINDPatientRootQueryRetrieveInformationModel,
                        UID_FINDStudyRootQueryRetrieveInformationModel});
    // One query per modality (C-FIND matches one value); patients have no modality.
    const std::vector<std::string> modalities =
        filter.modalities.empty() || level == QueryLevel::Patient ? std::vector<std::string>{""}
                                                                  : filter.modalities;
    std::map<std::string, QueryMatch> unique;
    auto add = [&](std::vector<QueryMatch> matches) {
        for (QueryMatch& m : matches) {
            unique.try_emplace(keyOf(m), std::move(m));
        }
    };
    if (level == QueryLevel::Series && filter.studyUid.empty()) {
        // Series live under studies: find the studies, then list their series.
        std::vector<std::string> studies;
        for (const std::string& m : modalities) {
            for (const QueryMatch& s : findOnce(a, QueryLevel::Study, filter, m)) {
                studies.push_back(s.studyUid);
            }
        }
        std::sort(studies.begin(), studies.end());
        studies.erase(std::unique(studies.begin(), studies.end()), studies.end());
        for (const std::string& uid : studies) {
            QueryFilter inStudy = filter;
            inStudy.studyUid = uid;
            for (const std::string& m : modalities) {
                add(findOnce(a, QueryLevel::Series, inStudy, m));
            }
        }
    } else {
        for (const std::string& m : modalities) {
            add(findOnce(a, level, filter, m));
        }
    }
    return orderedMatches(std::move(unique));
}

std::vector<QueryMatch> orderedMatches(std::map<std::string, QueryMatch> unique) {
    std::vector<QueryMatch> out;
    for (auto& [key, m] : unique) {
        out.push_back(std::move(m));
    }
    std::stable_sort(out.begin(), out.end(), [](const QueryMatch& x, const QueryMatch& y) {
        return std::tie(x.studyDate, x.studyUid, x.seriesNumber) <
               std::tie(y.studyDate, y.studyUid, y.seriesNumber);
    });
    return out;
}

} // namespace lucent
