#include "core/pacs/DicomWebHttp.h"

#include <QEventLoop>
#include <QJsonDocument>
#include <QNetworkAccessManager>
#include <QNetworkReply>
#include <QStringList>
#include <QTimer>

namespace lucent::dicomweb {

QNetworkRequest request(const DicomWebService& s, const QUrl& url, const QByteArray& accept) {
    QNetworkRequest r(url);
    r.setRawHeader("Accept", accept);
    if (!s.bearerToken.empty()) {
        r.setRawHeader("Authorization", "Bearer " + QByteArray::fromStdString(s.bearerToken));
    }
    return r;
}

int checkReply(QNetworkReply& reply, const std::string& where) {
    const int status = reply.attribute(QNetworkRequest::HttpStatusCodeAttribute).toInt();
    if (reply.error() != QNetworkReply::NoError && status == 0) {
        const bool refused = reply.error() == QNetworkReply::ConnectionRefusedError;
        throw PacsError(where + ": " +
                        (refused
                             ? std::string("connection refused (is the DICOMweb server running?)")
                             : reply.errorString().toStdString()));
    }
    if (status != 204 && (status < 200 || status >= 300)) {
        throw PacsError(
            where + ": HTTP " + std::to_string(status) + " " +
            reply.attribute(QNetworkRequest::HttpReasonPhraseAttribute).toString().toStdString());
    }
    return status;
}

QByteArray get(const DicomWebService& s, const QUrl& url, const QByteArray& accept) {
    QNetworkAccessManager manager;
    QNetworkReply* reply = manager.get(request(s, url, accept)); // owned by the manager
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
    if (checkReply(*reply, where) == 204) {
        return {}; // no content: nothing matched
    }
    return reply->readAll();
}

QJsonArray searchJson(const DicomWebService& s, const QString& path, const QUrlQuery& query) {
    QUrl url(QString::fromStdString(s.baseUrl) + path);
    url.setQuery(query);
    const QByteArray body = get(s, url, "application/dicom+json");
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
    m.studyTime = value(o, "00080030").toStdString();
    m.studyDescription = value(o, "00081030").toStdString();
    m.accessionNumber = value(o, "00080050").toStdString();
    m.modalitiesInStudy = value(o, "00080061").toStdString();
    m.seriesUid = value(o, "0020000E").toStdString();
    m.seriesDescription = value(o, "0008103E").toStdString();
    m.modality = value(o, "00080060").toStdString();
    m.bodyPart = value(o, "00180015").toStdString();
    m.seriesNumber = value(o, "00200011").toInt();
    m.instances = value(o, level == QueryLevel::Series ? "00201209" : "00201208").toInt();
    return m;
}

} // namespace lucent::dicomweb
