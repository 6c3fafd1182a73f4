#include "core/pacs/DicomWebClient.h"

#include <map>

#include "core/pacs/DicomWebHttp.h"

namespace lucent {

using dicomweb::searchJson;
using dicomweb::toMatch;

std::vector<QueryMatch> qidoSearch(const DicomWebService& s, QueryLevel level,
                                   const QueryFilter& f) {
    f.validate();
    QUrlQuery q;
    auto add = [&](const char* key, const std::string& v) {
        if (!v.empty()) {
            q.addQueryItem(key, QString::fromStdString(v));
        }
    };
    add("PatientName", f.patientName);
    add("PatientID", f.patientId);
    add("AccessionNumber", f.accessionNumber);
    add("StudyDate", f.dateRange);
    const std::vector<std::string> modalities =
        f.modalities.empty() ? std::vector<std::string>{""} : f.modalities;
    std::map<std::string, QueryMatch> unique;
    for (const std::string& modality : modalities) {
        QUrlQuery query = q;
        QString path = "/studies";
        if (level == QueryLevel::Series) {
            path = f.studyUid.empty()
                       ? "/series"
                       : "/studies/" + QString::fromStdString(f.studyUid) + "/series";
            if (!modality.empty()) {
                query.addQueryItem("Modality", QString::fromStdString(modality));
            }
        } else {
            if (!f.studyUid.empty()) {
                query.addQueryItem("StudyInstanceUID", QString::fromStdString(f.studyUid));
            }
            if (!modality.empty() && level == QueryLevel::Study) {
                query.addQueryItem("ModalitiesInStudy", QString::fromStdString(modality));
            }
        }
        for (const char* field : {"00081030", "00080061", "00201208", "00201209", "0008103E",
                                  "00200011", "00080030", "00180015"}) {
            query.addQueryItem("includefield", field);
        }
        for (const QJsonValue& v : searchJson(s, path, query)) {
            QueryMatch m =
                toMatch(v.toObject(), level == QueryLevel::Patient ? QueryLevel::Study : level);
            if (level == QueryLevel::Patient) {
                m.level = QueryLevel::Patient;
                unique.try_emplace(m.patientId + "|" + m.patientName, std::move(m));
            } else {
                unique.try_emplace(level == QueryLevel::Series ? m.seriesUid : m.studyUid,
                                   std::move(m));
            }
        }
    }
    return orderedMatches(std::move(unique));
}

} // namespace lucent
