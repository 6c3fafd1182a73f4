#pragma once
// HTTP and DICOM JSON helpers shared by QIDO-RS and WADO-RS. Private to lucent_pacs.

#include <string>

#include <QByteArray>
#include <QJsonArray>
#include <QJsonObject>
#include <QString>
#include <QUrl>
#include <QUrlQuery>

#include "core/pacs/DicomWebClient.h"

class QNetworkReply;
class QNetworkRequest;

namespace lucent::dicomweb {

// A request with the service's Accept and Authorization headers.
QNetworkRequest request(const DicomWebService& s, const QUrl& url, const QByteArray& accept);

// Throws PacsError naming `where` when the finished reply failed (refused,
// network error, HTTP status outside 2xx). Returns the HTTP status.
int checkReply(QNetworkReply& reply, const std::string& where);

// One GET, synchronously, with the service's timeout. Throws PacsError naming the URL.
QByteArray get(const DicomWebService& s, const QUrl& url, const QByteArray& accept);

// A DICOM JSON search (QIDO-RS) below the base URL; an empty array when nothing matched.
QJsonArray searchJson(const DicomWebService& s, const QString& path, const QUrlQuery& query);

// The value of a tag ("00100010") of a DICOM JSON object, multiple values joined by '\'.
QString value(const QJsonObject& item, const char* tag);
QueryMatch toMatch(const QJsonObject& o, QueryLevel level);

} // namespace lucent::dicomweb
