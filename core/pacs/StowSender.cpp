// STOW-RS: instances POSTed in batches as multipart/related, each one's
// status read from the response (PS3.18 10.5.3: Referenced SOP Sequence for
// the stored, Failed SOP Sequence with a Failure Reason for the others).
#include <QEventLoop>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QNetworkAccessManager>
#include <QNetworkReply>
#include <QTimer>
#include <QUuid>

#include <map>

#include "core/pacs/DicomWebHttp.h"
#include "core/pacs/InstanceSender.h"

namespace lucent {
namespace {

// A batch ends at this many bytes or instances, whichever comes first: the
// request body is held in memory, and progress moves once per batch.
constexpr qint64 kBatchBytes = 32 << 20;
constexpr std::size_t kBatchInstances = 64;

QByteArray multipartBody(const std::vector<const InstanceHeader*>& batch,
                         const QByteArray& boundary) {
    QByteArray body;
    for (const InstanceHeader* h : batch) {
        QFile f(QString::fromStdString(h->file.string()));
        if (!f.open(QIODevice::ReadOnly)) {
            throw PacsError(h->file.string() + ": cannot read (" + f.errorString().toStdString() +
                            ")");
        }
        body += "--" + boundary + "\r\nContent-Type: application/dicom\r\n\r\n";
        body += f.readAll();
        body += "\r\n";
    }
    body += "--" + boundary + "--\r\n";
    return body;
}

// FailureReason codes of PS3.18 Table 10.5.3-2 and the storage statuses.
std::string failureText(int code) {
    switch (code) {
    case 0xA700:
        return "out of resources";
    case 0xA900:
        return "data set does not match SOP class";
    case 0xC000:
        return "cannot understand";
    case 0xC122:
        return "referenced transfer syntax not supported";
    case 0x0110:
        return "processing failure";
    case 0x0122:
        return "referenced SOP class not supported";
    default:
        return "failure reason " + std::to_string(code);
    }
}

// Instance UID -> (outcome, message) from a STOW-RS response body.
std::map<std::string, std::pair<SentInstance::Outcome, std::string>>
statusesOf(const QByteArray& body) {
    std::map<std::string, std::pair<SentInstance::Outcome, std::string>> out;
    const QJsonObject root = QJsonDocument::fromJson(body).object();
    const auto items = [&](const char* tag) {
        return root.value(tag).toObject().value("Value").toArray();
    };
    for (const QJsonValue& v : items("00081199")) {
        const QJsonObject item = v.toObject();
        const QString warning = dicomweb::value(item, "00081196");
        out[dicomweb::value(item, "00081155").toStdString()] =
            warning.isEmpty() ? std::pair{SentInstance::Outcome::Stored, std::string()}
                              : std::pair{SentInstance::Outcome::StoredWithWarning,
                                          "warning reason " + warning.toStdString()};
    }
    for (const QJsonValue& v : items("00081198")) {
        const QJsonObject item = v.toObject();
        out[dicomweb::value(item, "00081155").toStdString()] = {
            SentInstance::Outcome::Failed,
            "refused: " + failureText(dicomweb::value(item, "00081197").toInt())};
    }
    return out;
}

// POSTs one batch; returns the response body. Throws PacsError naming the URL.
QByteArray post(const DicomWebService& s, const QUrl& url, const QByteArray& body,
                const QByteArray& boundary, const std::stop_token& stop, bool& cancelled) {
    QNetworkAccessManager manager;
    QNetworkRequest request = dicomweb::request(s, url, "application/dicom+json");
    request.setHeader(QNetworkRequest::ContentTypeHeader,
                      "multipart/related; type=\"application/dicom\"; boundary=" + boundary);
    QNetworkReply* reply = manager.post(request, body); // owned by the manager
    QEventLoop loop;
    QTimer timeout, poll;
    timeout.setSingleShot(true);
    QObject::connect(reply, &QNetworkReply::finished, &loop, &QEventLoop::quit);
    QObject::connect(&timeout, &QTimer::timeout, &loop, &QEventLoop::quit);
    // The timeout counts from the last bytes that moved, not from the start.
    QObject::connect(reply, &QNetworkReply::uploadProgress, &timeout,
                     [&] { timeout.start(s.timeoutSeconds * 1000); });
    QObject::connect(&poll, &QTimer::timeout, &loop, [&] {
        if (stop.stop_requested()) {
            cancelled = true;
            loop.quit();
        }
    });
    timeout.start(s.timeoutSeconds * 1000);
    poll.start(50);
    loop.exec();
    const std::string where = url.toString().toStdString();
    if (!reply->isFinished()) {
        reply->abort();
        if (cancelled) {
            return {};
        }
        throw PacsError(where + ": no answer within " + std::to_string(s.timeoutSeconds) +
                        " s (timeout)");
    }
    const int status = reply->attribute(QNetworkRequest::HttpStatusCodeAttribute).toInt();
    if (status != 409) { // 409: every instance failed; the body says why
        dicomweb::checkReply(*reply, where);
    }
    return reply->readAll();
}

} // namespace

SendResult sendByStow(const DicomWebService& service, const std::vector<InstanceHeader>& instances,
                      const SendControl& control) {
    SendResult result;
    for (const InstanceHeader& h : instances) {
        result.instances.push_back({h.file, h.sopInstanceUid, SentInstance::Outcome::NotSent, ""});
    }
    const QUrl url(QString::fromStdString(service.baseUrl) + "/studies");
    const QByteArray boundary = "lucent-" + QUuid::createUuid().toByteArray(QUuid::WithoutBraces);
    const int total = static_cast<int>(instances.size());
    std::size_t next = 0;
    while (next < instances.size()) {
        if (control.stop.stop_requested()) {
            result.cancelled = true;
            break;
        }
        std::vector<const InstanceHeader*> batch;
        qint64 bytes = 0;
        const std::size_t first = next;
        while (next < instances.size() && batch.size() < kBatchInstances &&
               (batch.empty() || bytes < kBatchBytes)) {
            std::error_code ec;
            bytes += static_cast<qint64>(std::filesystem::file_size(instances[next].file, ec));
            batch.push_back(&instances[next++]);
        }
        bool cancelled = false;
        const QByteArray response =
            post(service, url, multipartBody(batch, boundary), boundary, control.stop, cancelled);
        if (cancelled) {
            result.cancelled = true;
            next = first; // the interrupted batch counts as not sent
            break;
        }
        const auto statuses = statusesOf(response);
        for (std::size_t k = first; k < next; ++k) {
            SentInstance& out = result.instances[k];
            const auto found = statuses.find(out.sopInstanceUid);
            if (found == statuses.end()) {
                out.outcome = SentInstance::Outcome::Failed;
                out.message = url.toString().toStdString() + ": not in the STOW-RS response";
            } else {
                out.outcome = found->second.first;
                out.message = found->second.second;
            }
        }
        if (control.onProgress) {
            control.onProgress(static_cast<int>(next), total);
        }
    }
    for (std::size_t k = next; k < instances.size() && result.cancelled; ++k) {
        result.instances[k].message = "cancelled";
    }
    return result;
}

} // namespace lucent
