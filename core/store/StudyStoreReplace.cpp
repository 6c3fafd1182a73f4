// StudyStore: instances replaced in one index transaction, and the files of a series.
#include "core/store/StudyStore.h"

#include <system_error>

#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QString>
#include <QVariant>

namespace lucent {

namespace fs = std::filesystem;

namespace {

QString q(const std::string& s) {
    return QString::fromStdString(s);
}

QSqlQuery boundQuery(const std::string& connection, const fs::path& root, const char* sql,
                     const std::string& value) {
    QSqlQuery query(QSqlDatabase::database(q(connection)));
    if (!query.prepare(sql)) {
        throw StoreError(root.string() +
                         "/index.sqlite: " + query.lastError().text().toStdString());
    }
    query.addBindValue(q(value));
    if (!query.exec()) {
        throw StoreError(root.string() +
                         "/index.sqlite: " + query.lastError().text().toStdString());
    }
    return query;
}

} // namespace

void StudyStore::replace(const std::vector<std::string>& replaced, const fs::path& completeFile,
                         const InstanceRecord& record) {
    // A savepoint, not a Batch: a batch commits what it holds even on an exception,
    // and dropped rows without the new one would lose the old instances.
    exec("SAVEPOINT lucent_replace");
    std::vector<fs::path> oldFiles;
    try {
        for (const std::string& sop : replaced) {
            QSqlQuery path =
                boundQuery(connection_, root_, "SELECT path FROM instances WHERE sop_uid = ?", sop);
            if (path.next()) {
                oldFiles.push_back(root_ / path.value(0).toString().toStdString());
            }
            path.finish();
            QSqlQuery del =
                boundQuery(connection_, root_, "DELETE FROM instances WHERE sop_uid = ?", sop);
        }
        if (!add(completeFile, record)) {
            throw StoreError(record.sopInstanceUid + ": already stored, nothing replaced");
        }
        exec("RELEASE lucent_replace");
    } catch (const StoreError&) {
        std::error_code ec;
        fs::remove(completeFile, ec);
        try {
            exec("ROLLBACK TO lucent_replace");
            exec("RELEASE lucent_replace");
        } catch (const StoreError&) {
            // SQLite rolled back on its own (a full disk); the first error is the one to report.
        }
        throw;
    }
    for (const fs::path& file : oldFiles) {
        std::error_code ec;
        fs::remove(file, ec);
    }
}

std::vector<std::pair<std::string, fs::path>>
StudyStore::instanceFiles(const std::string& seriesUid) const {
    QSqlQuery query = boundQuery(connection_, root_,
                                 "SELECT sop_uid, path FROM instances WHERE series_uid = ? "
                                 "ORDER BY path",
                                 seriesUid);
    std::vector<std::pair<std::string, fs::path>> out;
    while (query.next()) {
        out.emplace_back(query.value(0).toString().toStdString(),
                         root_ / query.value(1).toString().toStdString());
    }
    return out;
}

std::string StudyStore::studyOf(const std::string& seriesUid) const {
    QSqlQuery query = boundQuery(connection_, root_,
                                 "SELECT study_uid FROM series WHERE series_uid = ?", seriesUid);
    return query.next() ? query.value(0).toString().toStdString() : std::string();
}

} // namespace lucent
