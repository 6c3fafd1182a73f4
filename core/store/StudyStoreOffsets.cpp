// StudyStore: the "link here" offsets between series of different Frames of Reference.
#include "core/store/StudyStore.h"

#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QString>
#include <QVariant>

namespace lucent {

namespace {

QSqlQuery offsetQuery(const std::string& connection, const std::filesystem::path& root,
                      const char* sql) {
    QSqlQuery query(QSqlDatabase::database(QString::fromStdString(connection)));
    if (!query.prepare(sql)) {
        throw StoreError(root.string() +
                         "/index.sqlite: " + query.lastError().text().toStdString());
    }
    return query;
}

void execOrThrow(QSqlQuery& query, const std::filesystem::path& root) {
    if (!query.exec()) {
        throw StoreError(root.string() +
                         "/index.sqlite: " + query.lastError().text().toStdString());
    }
}

} // namespace

void StudyStore::setSeriesOffset(const std::string& seriesA, const std::string& seriesB,
                                 const glm::dvec3& offset) {
    if (seriesA.empty() || seriesB.empty() || seriesA == seriesB) {
        throw StoreError("series offset: two different series UIDs are needed");
    }
    // One row per pair, in UID order, so that either order finds it.
    const bool inOrder = seriesA < seriesB;
    const glm::dvec3 stored = inOrder ? offset : -offset;
    QSqlQuery query = offsetQuery(connection_, root_,
                                  "INSERT OR REPLACE INTO series_offsets (series_a, series_b, dx, "
                                  "dy, dz) VALUES (?,?,?,?,?)");
    query.addBindValue(QString::fromStdString(inOrder ? seriesA : seriesB));
    query.addBindValue(QString::fromStdString(inOrder ? seriesB : seriesA));
    query.addBindValue(stored.x);
    query.addBindValue(stored.y);
    query.addBindValue(stored.z);
    execOrThrow(query, root_);
}

std::optional<glm::dvec3> StudyStore::seriesOffset(const std::string& seriesA,
                                                   const std::string& seriesB) const {
    const bool inOrder = seriesA < seriesB;
    QSqlQuery query =
        offsetQuery(connection_, root_,
                    "SELECT dx, dy, dz FROM series_offsets WHERE series_a = ? AND series_b = ?");
    query.addBindValue(QString::fromStdString(inOrder ? seriesA : seriesB));
    query.addBindValue(QString::fromStdString(inOrder ? seriesB : seriesA));
    execOrThrow(query, root_);
    if (!query.next()) {
        return std::nullopt;
    }
    const glm::dvec3 stored(query.value(0).toDouble(), query.value(1).toDouble(),
                            query.value(2).toDouble());
    return inOrder ? stored : -stored;
}

} // namespace lucent
