// lucent-cli info and convert, run as a user runs them: JSON fields, exit
// status, messages, and a convert round trip through MetaImage.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include "tests/support/CliRunner.h"

#include <filesystem>
#include <fstream>

#include "core/formats/MetaImage.h"
#include "core/io/Catalog.h"
#include "tests/support/SyntheticDicom.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

test::SyntheticSeries obliqueSeries() {
    test::SyntheticSeries s;
    const double a = glm::radians(20.0);
    s.rowDir = {std::cos(a), 0.0, std::sin(a)};
    s.colDir = {0.0, 1.0, 0.0};
    s.columns = 9;
    s.rows = 7;
    return s;
}

std::vector<glm::dvec3> stackPositions(const test::SyntheticSeries& s, int n, double step) {
    const glm::dvec3 normal = glm::normalize(glm::cross(s.rowDir, s.colDir));
    std::vector<glm::dvec3> p;
    for (int k = n - 1; k >= 0; --k) { // written in descending order on purpose
        p.push_back(glm::dvec3(-20, 15, 100) + normal * (step * k));
    }
    return p;
}

bool nearArray(const QJsonArray& a, const glm::dvec3& v, double tol = 1e-6) {
    return a.size() == 3 && std::abs(a[0].toDouble() - v.x) < tol &&
           std::abs(a[1].toDouble() - v.y) < tol && std::abs(a[2].toDouble() - v.z) < tol;
}

} // namespace

class TestCli : public QObject {
    Q_OBJECT
private slots:
    void infoJsonFollowsTheContract() {
        QTemporaryDir dir;
        const test::SyntheticSeries s = obliqueSeries();
        test::writeSeries(dir.path().toStdString(), s, stackPositions(s, 4, 2.0));
        const test::CliRun r = test::runCli({"info", dir.path(), "--json"});
        QCOMPARE(r.exitCode, 0);
        const QJsonObject doc = QJsonDocument::fromJson(r.out.toUtf8()).object();
        const QJsonArray series = doc["series"].toArray();
        QCOMPARE(series.size(), 1);
        const QJsonObject e = series[0].toObject();
        QCOMPARE(e["uid"].toString(), QString::fromStdString(s.seriesUid));
        QCOMPARE(e["modality"].toString(), QString("CT"));
        QCOMPARE(e["description"].toString(), QString("synthetic"));
        QCOMPARE(e["kind"].toString(), QString("volume"));
        QCOMPARE(e["dims"].toArray(), (QJsonArray{9, 7, 4}));
        QVERIFY(nearArray(e["spacing"].toArray(), {0.5, 0.75, 2.0}));
        const glm::dvec3 normal = glm::normalize(glm::cross(s.rowDir, s.colDir));
        QVERIFY(nearArray(e["origin"].toArray(), {-20, 15, 100}));
        const QJsonArray dirs = e["direction"].toArray();
        QCOMPARE(dirs.size(), 3);
        QVERIFY(nearArray(dirs[0].toArray(), s.rowDir));
        QVERIFY(nearArray(dirs[1].toArray(), s.colDir));
        QVERIFY(nearArray(dirs[2].toArray(), normal)); // k ascends along row x column
        QVERIFY(e["warnings"].toArray().isEmpty());
    }

    void infoTableIsReadable() {
        QTemporaryDir dir;
        const test::SyntheticSeries s = obliqueSeries();
        test::writeSeries(dir.path().toStdString(), s, stackPositions(s, 3, 1.0));
        std::ofstream(dir.filePath("notes.txt").toStdString()) << "hello";
        const test::CliRun r = test::runCli({"info", dir.path()});
        QCOMPARE(r.exitCode, 0);
        QVERIFY(r.out.contains("volume"));
        QVERIFY(r.out.contains("9x7x3"));
        QVERIFY(r.out.contains("notes.txt: not a DICOM file"));
    }

    void exitStatusAndMessages() {
        QCOMPARE(test::runCli({}).exitCode, 2);
        QCOMPARE(test::runCli({"frobnicate"}).exitCode, 2);
        QCOMPARE(test::runCli({"info"}).exitCode, 2);
        QCOMPARE(test::runCli({"info", "a", "b"}).exitCode, 2);
        QCOMPARE(test::runCli({"info", "/x", "--bogus"}).exitCode, 2);
        const test::CliRun missing = test::runCli({"info", "/nonexistent/lucent"});
        QCOMPARE(missing.exitCode, 3);
        QVERIFY(missing.err.contains("/nonexistent/lucent: no such file or folder"));
        QTemporaryDir dir;
        std::ofstream(dir.filePath("scan.dcm").toStdString()) << "garbage, not DICOM";
        const test::CliRun junk = test::runCli({"info", dir.path()});
        QCOMPARE(junk.exitCode, 3);
        QVERIFY2(junk.err.contains("scan.dcm") && junk.err.contains("nothing loadable"),
                 qPrintable(junk.err));
        QCOMPARE(test::runCli({"convert", dir.path()}).exitCode, 2);
        QCOMPARE(test::runCli({"convert", dir.path(), "out.nii"}).exitCode, 2);
        QCOMPARE(test::runCli({"convert", dir.path(), dir.filePath("o.mhd")}).exitCode, 3);
    }

    void convertRoundTripKeepsGeometryAndVoxels() {
        QTemporaryDir dir;
        const fs::path in = fs::path(dir.path().toStdString()) / "in";
        fs::create_directories(in);
        const test::SyntheticSeries s = obliqueSeries();
        test::writeSeries(in.string(), s, stackPositions(s, 5, 1.5));
        const QString out = dir.filePath("vol.mhd");
        const test::CliRun r = test::runCli({"convert", QString::fromStdString(in.string()), out});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY(fs::exists(dir.filePath("vol.raw").toStdString()));

        const Volume original = loadPath(in);
        const Volume converted = readMetaImage(out.toStdString());
        QCOMPARE(converted.type(), VoxelType::Int16);
        QCOMPARE(converted.dims(), original.dims());
        const VolumeGeometry& a = original.geometry();
        const VolumeGeometry& b = converted.geometry();
        QVERIFY(glm::length(a.origin - b.origin) < 1e-6);
        QVERIFY(glm::length(a.spacing - b.spacing) < 1e-9);
        for (int c = 0; c < 3; ++c) {
            QVERIFY(glm::length(a.direction[c] - b.direction[c]) < 1e-9);
        }
        QVERIFY(std::equal(original.bytes().begin(), original.bytes().end(),
                           converted.bytes().begin()));
        // i fastest in the .raw: the first bytes are row 0 of the lowest slice.
        std::ifstream raw(dir.filePath("vol.raw").toStdString(), std::ios::binary);
        std::int16_t first[2] = {};
        raw.read(reinterpret_cast<char*>(first), sizeof first);
        QCOMPARE(double(first[0]), original.value(0, 0, 0));
        QCOMPARE(double(first[1]), original.value(1, 0, 0));
    }

    void convertSelectsSeriesById() {
        QTemporaryDir dir;
        test::SyntheticSeries s = obliqueSeries();
        test::writeSeries(dir.path().toStdString(), s, stackPositions(s, 3, 1.0), "a");
        test::SyntheticSeries t = s;
        t.seriesUid = "1.2.826.0.1.3680043.2.1125.99";
        t.columns = 4;
        test::writeSeries(dir.path().toStdString(), t, stackPositions(t, 2, 1.0), "b");
        const QString out = dir.filePath("second.mhd");
        QCOMPARE(test::runCli(
                     {"convert", dir.path(), out, "--series", QString::fromStdString(t.seriesUid)})
                     .exitCode,
                 0);
        QCOMPARE(readMetaImage(out.toStdString()).dims(), glm::ivec3(4, 7, 2));
        const test::CliRun unknown =
            test::runCli({"convert", dir.path(), out, "--series", "1.2.3"});
        QCOMPARE(unknown.exitCode, 3);
        QVERIFY(unknown.err.contains("no series with id or UID 1.2.3"));
    }

    void convertRealCtKeepsHu() {
        const fs::path data = fs::path(LUCENT_TEST_DATA_DIR) / "dcmqi_ct3slice";
        if (!fs::exists(data)) {
            QSKIP("real test data not found: ../shared/data/dcmqi_ct3slice");
        }
        QTemporaryDir dir;
        const QString out = dir.filePath("ct.mhd");
        QCOMPARE(test::runCli({"convert", QString::fromStdString(data.string()), out}).exitCode, 0);
        const Volume v = readMetaImage(out.toStdString());
        const Volume ref = loadPath(data);
        QCOMPARE(v.dims(), glm::ivec3(512, 512, 3));
        QVERIFY(std::equal(v.bytes().begin(), v.bytes().end(), ref.bytes().begin()));
        QVERIFY(v.valueRange().first <= -1000);
    }
};

QTEST_GUILESS_MAIN(TestCli)
#include "test_cli.moc"
