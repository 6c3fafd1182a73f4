#include "core/pacs/DicomWebClient.h"

#include <fstream>

#include <QEventLoop>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QNetworkAccessManager>
#include <QNetworkReply>
#include <QTimer>
#include <QUrlQuery>

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

namespace lucent {
namespace {

// One GET, synchronously, with a timeout. Throws PacsError naming the URL.
QByteArray get(const DicomWebService& s, const QUrl& url, const QByteArray& accept,
               QByteArray* contentType) {
    QNetworkAccessManager manager;
    QNetworkRequest request(url);
    request.setRawHeader("Accept", accept);
    if (!s.bearerToken.empty()) {
        request.setRawHeader("Authorization", "Bearer " + QByteArray::fromStdString(s.bearerToken));
    }
    QNetworkReply* reply = manager.get(request); // owned by the manager
    QEventLoop loop;
    QTimer timer;
    timer.setSingleShot(true);
    QObject::connect(reply, &QNetworkReply::finished, &loop, &QEventLoop::quit);
    QObject::connect(&timer, &QTimer::timeout, &loop, &QEventLoop::quit);
    timer.start(s.timeoutSeconds * 1000);
    loop.exec();
    const std::string where = url.toString(QUrl::RemoveQuery).toStdString();
    if (!reply->isFinished()) {
        reply->abort();
        throw PacsError(where + ": no answer within " + std::to_string(s.timeoutSeconds) +
                        " s (timeout)");
    }
    const int status = reply->attribute(QNetworkRequest::HttpStatusCodeAttribute).toInt();
    if (reply->error() != QNetworkReply::NoError && status == 0) {
        const bool refused = reply->error() == QNetworkReply::ConnectionRefusedError;
        throw PacsError(where + ": " +
                        (refused
                             ? std::string("connection refused (is the DICOMweb server running?)")
                             : reply->errorString().toStdString()));
    }
    if (status == 204) {
        return {}; // no content: nothing matched
    }
    if (status < 200 || status >= 300) {
        throw PacsError(
            where + ": HTTP " + std::to_string(status) + " " +
            reply->attribute(QNetworkRequest::HttpReasonPhraseAttribute).toString().toStdString());
    }
    if (contentType != nullptr) {
        *contentType = reply->header(QNetworkRequest::ContentTypeHeader).toByteArray();
    }
    return reply->readAll();
}

QString value(const QJsonObject& item, const char* tag) {
    const QJsonArray values = item.value(tag).toObject().value("Value").toArray();
    QStringList parts;
    for (const QJsonValue& v : values) {
        parts << (v.isObject()   ? v.toObject().value("Alphabetic").toString()
                  : v.isDouble() ? QString::number(v.toDouble())
                                 : v.toString());
    }
    return parts.join('\\');
}

QueryMatch toMatch(const QJsonObject& o, QueryLevel level) {
    QueryMatch m;
    m.level = level;
    m.patientName = value(o, "00100010").toStdString();
    m.patientId = value(o, "00100020").toStdString();
    m.patientBirthDate = value(o, "00100030").toStdString();
    m.studyUid = value(o, "0020000D").toStdString();
    m.studyDate = value(o, "00080020").toStdString();
    m.studyDescription = value(o, "00081030").toStdString();
    m.accessionNumber = value(o, "00080050").toStdString();
    m.modalitiesInStudy = value(o, "00080061").toStdString();
    m.seriesUid = value(o, "0020000E").toStdString();
    m.seriesDescription = value(o, "0008103E").toStdString();
    m.modality = value(o, "00080060").toStdString();
    m.seriesNumber = value(o, "00200011").toInt();
    m.instances = value(o, level == QueryLevel::Series ? "00201209" : "00201208").toInt();
    return m;
}

QJsonArray searchJson(const DicomWebService& s, const QString& path, const QUrlQuery& query) {
    QUrl url(QString::fromStdString(s.baseUrl) + path);
    url.setQuery(query);
    const QByteArray body = get(s, url, "application/dicom+json", nullptr);
    if (body.isEmpty()) {
        return {};
    }
    QJsonParseError error{};
    const QJsonDocument doc = QJsonDocument::fromJson(body, &error);
    if (!doc.isArray()) {
        throw PacsError(url.toString(QUrl::RemoveQuery).toStdString() +
                        ": the answer is not a DICOM JSON array (" +
                        error.errorString().toStdString() + ")");
    }
    return doc.array();
}

// The parts of a multipart/related body.
std::vector<QByteArray> multipartParts(const QByteArray& body, const QByteArray& contentType,
                                       const std::string& where) {
    const int b = contentType.indexOf("boundary=");
    if (b < 0) {
        throw PacsError(where + ": the answer is not multipart/related (" +
                        contentType.toStdString() + ")");
    }
    QByteArray boundary = contentType.mid(b + 9);
    const int semicolon = boundary.indexOf(';');
    if (semicolon >= 0) {
        boundary = boundary.left(semicolon);
    }
    boundary = boundary.trimmed();
    if (boundary.startsWith('"')) {
        boundary = boundary.mid(1, boundary.size() - 2);
    }
    const QByteArray delimiter = "--" + boundary;
    std::vector<QByteArray> parts;
    int pos = body.indexOf(delimiter);
    while (pos >= 0) {
        pos += delimiter.size();
        if (body.mid(pos, 2) == "--") {
            break; // closing delimiter
        }
        const int headersEnd = body.indexOf("\r\n\r\n", pos);
        const int next = body.indexOf("\r\n" + delimiter, headersEnd);
        if (headersEnd < 0 || next < 0) {
            throw PacsError(where + ": a part of the multipart answer is cut short");
        }
        parts.push_back(body.mid(headersEnd + 4, next - headersEnd - 4));
        pos = next + 2;
    }
    return parts;
}

std::string tagText(DcmDataset& d, const DcmTagKey& tag) {
    OFString v;
    d.findAndGetOFStringArray(tag, v);
    return v.c_str();
}

} // namespace

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
        for (const char* field :
             {"00081030", "00080061", "00201208", "00201209", "0008103E", "00200011"}) {
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

RetrieveResult wadoRetrieveSeries(const DicomWebService& s, const std::string& studyUid,
                                  const std::string& seriesUid, StudyStore& store,
                                  const RetrieveControl& control) {
    const QString seriesPath = "/studies/" + QString::fromStdString(studyUid) + "/series/" +
                               QString::fromStdString(seriesUid);
    const QJsonArray listing = searchJson(s, seriesPath + "/instances", QUrlQuery());
    if (listing.isEmpty()) {
        throw PacsError(s.baseUrl + ": series " + seriesUid + " of study " + studyUid +
                        " has no instances there");
    }
    RetrieveResult result;
    result.seriesUid = seriesUid;
    result.expected = listing.size();
    result.folder = store.seriesFolder(studyUid, seriesUid);
    const QueryMatch first = toMatch(listing.first().toObject(), QueryLevel::Series);
    SeriesInfo info;
    info.studyUid = studyUid;
    info.seriesUid = seriesUid;
    info.patientName = first.patientName;
    info.patientId = first.patientId;
    info.studyDate = first.studyDate;
    info.modality = first.modality;
    store.setExpected(info, first.seriesNumber, result.expected);
    const std::set<std::string> stored = store.instancesOf(seriesUid);
    std::vector<std::string> missing;
    for (const QJsonValue& v : listing) {
        const std::string sop = value(v.toObject(), "00080018").toStdString();
        if (stored.count(sop) == 0) {
            missing.push_back(sop);
        }
    }
    result.alreadyStored = result.expected - static_cast<int>(missing.size());
    // The whole series in one request when all is missing, else instance by instance.
    std::vector<QString> paths;
    if (static_cast<int>(missing.size()) == result.expected) {
        paths.push_back(seriesPath);
    } else {
        for (const std::string& sop : missing) {
            paths.push_back(seriesPath + "/instances/" + QString::fromStdString(sop));
        }
    }
    int done = 0;
    for (const QString& path : paths) {
        if (control.stop.stop_requested()) {
            throw PacsError(s.baseUrl + ": retrieval of series " + seriesUid + " cancelled");
        }
        QByteArray contentType;
        const QUrl url(QString::fromStdString(s.baseUrl) + path);
        const QByteArray body =
            get(s, url, "multipart/related; type=\"application/dicom\"", &contentType);
        for (const QByteArray& part :
             multipartParts(body, contentType, url.toString().toStdString())) {
            const std::filesystem::path temp = store.temporaryFile();
            {
                std::ofstream out(temp, std::ios::binary);
                out.write(part.constData(), part.size());
                if (!out) {
                    throw StoreError(temp.string() + ": cannot write a received instance");
                }
            }
            DcmFileFormat file;
            if (file.loadFile(temp.c_str(), EXS_Unknown, EGL_noChange, 4096).bad()) {
                std::error_code ec;
                std::filesystem::remove(temp, ec);
                ++result.failed;
                continue;
            }
            DcmDataset& d = *file.getDataset();
            InstanceRecord r;
            r.series = info;
            r.series.description = tagText(d, DCM_SeriesDescription);
            r.sopInstanceUid = tagText(d, DCM_SOPInstanceUID);
            r.seriesNumber = first.seriesNumber;
            (store.add(temp, r) ? result.received : result.alreadyStored) += 1;
            if (control.onProgress) {
                control.onProgress(++done, static_cast<int>(missing.size()));
            }
        }
    }
    result.complete = store.isComplete(seriesUid);
    return result;
}

} // namespace lucent
