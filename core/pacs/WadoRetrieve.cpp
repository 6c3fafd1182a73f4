// WADO-RS retrieval of a series into the study store: the multipart answer is
// parsed as it arrives and each instance written straight to a temporary file,
// then moved in and indexed (one transaction per retrieval). Only the instances
// the store lacks are asked for; when it has none of the series, the instance
// listing (slow on some servers) is skipped and the series fetched at once.
#include "core/pacs/DicomWebClient.h"

#include <cerrno>
#include <cstring>
#include <exception>
#include <memory>
#include <optional>

#include <QEventLoop>
#include <QNetworkAccessManager>
#include <QNetworkReply>
#include <QTimer>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include <fcntl.h>
#include <unistd.h>

#include "core/pacs/DicomWebHttp.h"
#include "core/pacs/MultipartStream.h"

namespace lucent {
namespace {

using dicomweb::value;

// Writes the parts of a multipart answer into the store, one instance each.
class PartWriter {
public:
    PartWriter(StudyStore& store, const InstanceRecord& facts, RetrieveResult& result,
               const RetrieveControl& control, int toFetch)
        : store_(store), facts_(facts), result_(result), control_(control), toFetch_(toFetch) {}
    ~PartWriter() { discard(); }
    PartWriter(const PartWriter&) = delete;
    PartWriter& operator=(const PartWriter&) = delete;

    void begin() {
        discard();
        store_.requireSpace(0);
        temp_ = store_.temporaryFile();
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (fd_ < 0) {
            throw store_.writeError(temp_, temp_.string() +
                                               ": cannot create a file for a received instance (" +
                                               std::strerror(errno) + ")");
        }
    }
    void data(const char* p, qsizetype n) {
        // The part's size is not known ahead: the reserve is checked as it grows.
        store_.requireSpace(static_cast<std::uintmax_t>(n));
        while (n > 0) {
            const ssize_t w = ::write(fd_, p, static_cast<std::size_t>(n));
            if (w <= 0) {
                throw store_.writeError(temp_, temp_.string() +
                                                   ": cannot write a received instance (" +
                                                   std::strerror(errno) + ")");
            }
            p += w;
            n -= w;
        }
    }
    void end() {
        const bool closed = ::close(fd_) == 0;
        fd_ = -1;
        if (!closed) {
            throw store_.writeError(temp_, temp_.string() + ": cannot write a received instance (" +
                                               std::strerror(errno) + ")");
        }
        // Only the header is parsed, up to the pixel data.
        DcmFileFormat file;
        InstanceRecord r = facts_;
        OFString sop;
        if (file.loadFileUntilTag(temp_.c_str(), EXS_Unknown, EGL_noChange, 4096, ERM_autoDetect,
                                  DCM_PixelData)
                .bad() ||
            file.getDataset()->findAndGetOFString(DCM_SOPInstanceUID, sop).bad() || sop.empty()) {
            discard();
            ++result_.failed;
        } else {
            r.sopInstanceUid = sop.c_str();
            (store_.add(temp_, r) ? result_.received : result_.alreadyStored) += 1;
            temp_.clear();
        }
        if (control_.onProgress) {
            control_.onProgress(++done_, toFetch_);
        }
    }

    // "k of n instance(s)" handled so far.
    std::string progress() const {
        return std::to_string(done_) + " of " + std::to_string(toFetch_) + " instance(s)";
    }

private:
    void discard() {
        if (fd_ >= 0) {
            ::close(fd_);
            fd_ = -1;
        }
        if (!temp_.empty()) {
            std::error_code ec;
            std::filesystem::remove(temp_, ec);
            temp_.clear();
        }
    }

    StudyStore& store_;
    const InstanceRecord& facts_;
    RetrieveResult& result_;
    const RetrieveControl& control_;
    int toFetch_;
    int done_ = 0;
    std::filesystem::path temp_;
    int fd_ = -1;
};

// One WADO-RS GET, streamed into the writer. Throws PacsError (network, HTTP,
// timeout without data, cancel) or StoreError.
void fetch(const DicomWebService& s, const QUrl& url, PartWriter& writer,
           const RetrieveControl& control, const std::string& seriesUid) {
    const std::string where = url.toString().toStdString();
    QNetworkAccessManager manager;
    QNetworkReply* reply = manager.get(dicomweb::request(
        s, url, "multipart/related; type=\"application/dicom\"; transfer-syntax=*"));
    std::optional<MultipartStream> parts;
    std::exception_ptr failure;
    QEventLoop loop;
    QTimer idle; // no data for the timeout: give up
    idle.setSingleShot(true);
    QTimer poll; // cancel requests
    auto stopWith = [&](std::exception_ptr e) {
        if (!failure) {
            failure = std::move(e);
        }
        reply->abort();
        loop.quit();
    };
    QObject::connect(&idle, &QTimer::timeout, &loop, [&] {
        stopWith(std::make_exception_ptr(PacsError(
            where + ": no data within " + std::to_string(s.timeoutSeconds) + " s (timeout)")));
    });
    auto checkStop = [&] {
        if (control.stop.stop_requested()) {
            stopWith(std::make_exception_ptr(
                PacsError(s.baseUrl + ": retrieval of series " + seriesUid + " cancelled")));
            return true;
        }
        return false;
    };
    QObject::connect(&poll, &QTimer::timeout, &loop, checkStop);
    QObject::connect(reply, &QNetworkReply::readyRead, &loop, [&] {
        idle.start();
        if (failure || checkStop()) {
            return;
        }
        const int status = reply->attribute(QNetworkRequest::HttpStatusCodeAttribute).toInt();
        if (status < 200 || status >= 300) {
            return; // the error is reported when the reply finishes
        }
        try {
            if (!parts) {
                parts.emplace(reply->header(QNetworkRequest::ContentTypeHeader).toByteArray(),
                              where);
                parts->onPartBegin = [&] { writer.begin(); };
                parts->onPartData = [&](const char* p, qsizetype n) { writer.data(p, n); };
                parts->onPartEnd = [&] {
                    writer.end();
                    if (control.stop.stop_requested()) { // between instances, even in one read
                        throw PacsError(s.baseUrl + ": retrieval of series " + seriesUid +
                                        " cancelled");
                    }
                };
            }
            char buffer[1 << 16];
            for (qint64 n; (n = reply->read(buffer, sizeof buffer)) > 0;) {
                parts->feed(buffer, n);
            }
        } catch (...) {
            stopWith(std::current_exception());
        }
    });
    QObject::connect(reply, &QNetworkReply::finished, &loop, &QEventLoop::quit);
    idle.start(s.timeoutSeconds * 1000);
    poll.start(50);
    if (!reply->isFinished()) {
        loop.exec();
    }
    if (failure) {
        std::rethrow_exception(failure);
    }
    // The answer had begun: the server went away in the middle of it (a
    // connection lost, or closed before the last part ended).
    const auto interrupted = [&](const std::string& cause) {
        return PacsError(s.baseUrl + ": WADO-RS retrieval of series " + seriesUid +
                         " interrupted after " + writer.progress() + " (" + cause +
                         "); what arrived whole is stored, the series stays incomplete: "
                         "retrieve it again for the rest");
    };
    if (parts && reply->error() != QNetworkReply::NoError) {
        throw interrupted(reply->errorString().toStdString());
    }
    if (dicomweb::checkReply(*reply, where) == 204) {
        return;
    }
    if (!parts) {
        throw PacsError(where + ": the answer has no instances");
    }
    try {
        parts->finish();
    } catch (const PacsError& e) {
        throw interrupted(e.what());
    }
}

} // namespace

RetrieveResult wadoRetrieveSeries(const DicomWebService& s, const std::string& studyUid,
                                  const std::string& seriesUid, StudyStore& store,
                                  const RetrieveControl& control) {
    const QString studyPath = "/studies/" + QString::fromStdString(studyUid);
    const QString seriesPath = studyPath + "/series/" + QString::fromStdString(seriesUid);
    QUrlQuery query;
    query.addQueryItem("SeriesInstanceUID", QString::fromStdString(seriesUid));
    for (const char* field : {"00201209", "0008103E", "00200011", "00081030", "00100030"}) {
        query.addQueryItem("includefield", field);
    }
    const QJsonArray found = dicomweb::searchJson(s, studyPath + "/series", query);
    if (found.isEmpty()) {
        throw PacsError(s.baseUrl + ": series " + seriesUid + " of study " + studyUid +
                        " has no instances there");
    }
    const QJsonObject series = found.first().toObject();
    const QueryMatch m = dicomweb::toMatch(series, QueryLevel::Series);
    InstanceRecord facts;
    facts.series.seriesUid = seriesUid;
    facts.series.studyUid = studyUid;
    facts.series.modality = m.modality;
    facts.series.description = m.seriesDescription;
    facts.series.patientName = m.patientName;
    facts.series.patientId = m.patientId;
    facts.series.studyDate = m.studyDate;
    facts.seriesNumber = m.seriesNumber;
    facts.studyDescription = m.studyDescription;
    facts.accessionNumber = m.accessionNumber;
    facts.patientBirthDate = m.patientBirthDate;

    RetrieveResult result;
    result.seriesUid = seriesUid;
    result.expected = m.instances;
    result.folder = store.seriesFolder(studyUid, seriesUid);
    const std::set<std::string> stored = store.instancesOf(seriesUid);
    std::vector<QString> paths;
    int toFetch = result.expected;
    if (stored.empty() && result.expected > 0) {
        paths.push_back(seriesPath); // nothing stored: the whole series, no listing
    } else if (result.expected == 0 || static_cast<int>(stored.size()) < result.expected) {
        const QJsonArray listing = dicomweb::searchJson(s, seriesPath + "/instances", {});
        result.expected = listing.size();
        std::vector<QString> missing;
        for (const QJsonValue& v : listing) {
            const QString sop = value(v.toObject(), "00080018");
            if (stored.count(sop.toStdString()) == 0) {
                missing.push_back(seriesPath + "/instances/" + sop);
            }
        }
        toFetch = static_cast<int>(missing.size());
        paths = toFetch == result.expected ? std::vector<QString>{seriesPath} : missing;
    } else {
        toFetch = 0;
    }
    if (result.expected == 0) {
        throw PacsError(s.baseUrl + ": series " + seriesUid + " of study " + studyUid +
                        " has no instances there");
    }
    result.alreadyStored = result.expected - toFetch;
    store.setExpected(facts, result.expected);
    {
        StudyStore::Batch batch(store);
        PartWriter writer(store, facts, result, control, toFetch);
        for (const QString& path : paths) {
            fetch(s, QUrl(QString::fromStdString(s.baseUrl) + path), writer, control, seriesUid);
        }
    }
    result.complete = store.isComplete(seriesUid);
    return result;
}

} // namespace lucent
