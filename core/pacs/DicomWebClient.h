#pragma once
// DICOMweb over Qt Network: QIDO-RS search and WADO-RS retrieval of a series
// into the study store. Needs a QCoreApplication (it runs a local event loop).

#include <string>
#include <vector>

#include "core/pacs/DimseQuery.h"
#include "core/pacs/SeriesRetriever.h"

namespace lucent {

struct DicomWebService {
    std::string baseUrl;     // e.g. http://host:8042/dicom-web
    int timeoutSeconds = 30; // per request
    std::string bearerToken; // sent as Authorization: Bearer when not empty
};

// QIDO-RS at a level with the same filters as C-FIND. Throws PacsError
// naming the URL and the cause (refused, HTTP status, timeout, bad JSON).
std::vector<QueryMatch> qidoSearch(const DicomWebService& service, QueryLevel level,
                                   const QueryFilter& filter);

// WADO-RS of a series into the store, asking only for instances the store lacks.
RetrieveResult wadoRetrieveSeries(const DicomWebService& service, const std::string& studyUid,
                                  const std::string& seriesUid, StudyStore& store,
                                  const RetrieveControl& control = {});

} // namespace lucent
