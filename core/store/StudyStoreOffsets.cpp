// StudyStore: how series of different Frames of Reference are related: the "link here"
// offsets and the registrations' transforms, one per series pair.
#include "core/store/StudyStore.h"

#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QString>
#include <QStringList>
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

// Row-major text: 16 numbers with all their digits.
QString matrixText(const glm::dmat4& m) {
    QStringList numbers;
    for (int row = 0; row < 4; ++row) {
        for (int column = 0; column < 4; ++column) {
            numbers << QString::number(m[column][row], 'g', 17);
        }
    }
    return numbers.join(' ');
}

std::optional<glm::dmat4> matrixFrom(const QString& text) {
    const QStringList numbers = text.split(' ', Qt::SkipEmptyParts);
    if (numbers.size() != 16) {
        return std::nullopt;
    }
    glm::dmat4 m(1.0);
    for (int n = 0; n < 16; ++n) {
        bool ok = false;
        m[n % 4][n / 4] = numbers[n].toDouble(&ok);
        if (!ok) {
            return std::nullopt;
        }
    }
    return m;
}

void requirePair(const std::string& a, const std::string& b, const char* what) {
    if (a.empty() || b.empty() || a == b) {
        throw StoreError(std::string(what) + ": two different series UIDs are needed");
    }
}

} // namespace

void StudyStore::setSeriesTransform(const std::string& seriesA, const std::string& seriesB,
                                    const glm::dmat4& aToB) {
    requirePair(seriesA, seriesB, "series transform");
    const bool inOrder = seriesA < seriesB;
    QSqlQuery query = offsetQuery(
        connection_, root_,
        "INSERT OR REPLACE INTO series_transforms (series_a, series_b, matrix) VALUES (?,?,?)");
    query.addBindValue(QString::fromStdString(inOrder ? seriesA : seriesB));
    query.addBindValue(QString::fromStdString(inOrder ? seriesB : seriesA));
    query.addBindValue(matrixText(inOrder ? aToB : glm::inverse(aToB)));
    execOrThrow(query, root_);
}

std::optional<glm::dmat4> StudyStore::seriesTransform(const std::string& seriesA,
                                                      const std::string& seriesB) const {
    const bool inOrder = seriesA < seriesB;
    QSqlQuery query =
        offsetQuery(connection_, root_,
                    "SELECT matrix FROM series_transforms WHERE series_a = ? AND series_b = ?");
    query.addBindValue(QString::fromStdString(inOrder ? seriesA : seriesB));
    query.addBindValue(QString::fromStdString(inOrder ? seriesB : seriesA));
    execOrThrow(query, root_);
    if (!query.next()) {
        return std::nullopt;
    }
    const std::optional<glm::dmat4> stored = matrixFrom(query.value(0).toString());
    if (!stored) {
        throw StoreError(root_.string() + "/index.sqlite: series_transforms: the matrix of " +
                         seriesA + " and " + seriesB + " is not 16 numbers");
    }
    return inOrder ? *stored : glm::inverse(*stored);
}

void StudyStore::setSeriesOffset(const std::string& seriesA, const std::string& seriesB,
                                 const glm::dvec3& offset) {
    requirePair(seriesA, seriesB, "series offset");
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
