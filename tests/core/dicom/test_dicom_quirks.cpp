// The quirks corpus (quirks/make_quirks.py: real files of ../shared/data re-encoded
// by DCMTK or changed by a few bytes): Lucent loads a file exactly when dcmdump
// reads it without error, with DCMTK's rows, columns, spacing and pixel values;
// where it refuses, the reason names the byte offset. The few deliberate
// differences are listed in the corpus with their reason and pinned here too.
// Also the regression of issue 27: zero padding after the data set.
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/io/Catalog.h"
#include "tests/support/RealData.h"
#include "tests/support/ReferenceDicom.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

const fs::path kQuirks = LUCENT_QUIRKS_DIR;

struct LucentResult {
    bool loaded = false;
    QString reason; // why not, as the user reads it ("FILE: REASON")
    Volume volume;
    std::vector<std::string> warnings;
};

LucentResult loadWithLucent(const fs::path& file) {
    LucentResult r;
    try {
        const Catalog c = scanPath(file);
        if (c.series.empty()) {
            r.reason = c.skipped.empty() ? QString("nothing loadable")
                                         : QString::fromStdString(c.skipped.front().file + ": " +
                                                                  c.skipped.front().reason);
            return r;
        }
        r.warnings = c.series.front().warnings;
        r.volume = loadSeries(c.series.front());
        r.loaded = true;
    } catch (const std::exception& e) {
        r.reason = QString::fromUtf8(e.what());
    }
    return r;
}

// dcmdump's exit status on the file: 0 when DCMTK reads it without error.
int dcmdump(const QString& program, const QStringList& options, const fs::path& file) {
    QProcess p;
    p.setStandardOutputFile(QProcess::nullDevice());
    p.setStandardErrorFile(QProcess::nullDevice());
    p.start(program, options + QStringList{QString::fromStdString(file.string())});
    if (!p.waitForFinished(60000)) {
        p.kill();
        p.waitForFinished();
        return -1;
    }
    return p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
}

bool anyContains(const std::vector<std::string>& texts, const char* part) {
    return std::any_of(texts.begin(), texts.end(),
                       [part](const std::string& t) { return t.find(part) != std::string::npos; });
}

// Lucent's voxels against DCMTK's: size, spacing in the plane, every value.
void compareWithDcmtk(const Volume& v, const fs::path& file) {
    const test::ReferenceImage ref = test::readReferenceImage(file.string(), true);
    QCOMPARE(v.dims().x, ref.columns);
    QCOMPARE(v.dims().y, ref.rows);
    QCOMPARE(v.dims().z, 1);
    QVERIFY(std::abs(v.geometry().spacing.x - ref.spacing.x) < 1e-9);
    QVERIFY(std::abs(v.geometry().spacing.y - ref.spacing.y) < 1e-9);
    int different = 0;
    for (int j = 0; j < ref.rows; ++j) {
        for (int i = 0; i < ref.columns; ++i) {
            different += v.value(i, j, 0) != ref.at(i, j);
        }
    }
    QCOMPARE(different, 0);
}

void copyFile(const fs::path& from, const fs::path& to, std::size_t zeros = 0,
              const std::string& after = {}) {
    fs::copy_file(from, to, fs::copy_options::overwrite_existing);
    fs::permissions(to, fs::perms::owner_write, fs::perm_options::add);
    std::ofstream out(to, std::ios::binary | std::ios::app);
    const std::string padding(zeros, '\0');
    out << padding << after;
}

} // namespace

class TestDicomQuirks : public QObject {
    Q_OBJECT
    QString dcmdumpProgram;
    QJsonArray cases;

private slots:
    void initTestCase() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        dcmdumpProgram = QStandardPaths::findExecutable("dcmdump");
        QVERIFY2(!dcmdumpProgram.isEmpty(),
                 "dcmdump (DCMTK) not found on PATH: packaging/install-deps.sh installs dcmtk");
        QFile f(QString::fromStdString((kQuirks / "cases.json").string()));
        QVERIFY2(f.open(QIODevice::ReadOnly), "the quirks corpus was not made (make_quirks.py)");
        cases = QJsonDocument::fromJson(f.readAll()).array();
        QVERIFY2(cases.size() >= 20, "the quirks corpus is incomplete");
    }

    void loadsExactlyWhenDcmdumpReads_data() {
        QTest::addColumn<QJsonObject>("quirk");
        for (const QJsonValue c : cases) {
            QTest::newRow(qPrintable(c["name"].toString())) << c.toObject();
        }
    }

    void loadsExactlyWhenDcmdumpReads() {
        QFETCH(QJsonObject, quirk);
        const fs::path file = kQuirks / quirk["file"].toString().toStdString();
        QStringList options;
        for (const QJsonValue o : quirk["dcmdump_options"].toArray()) {
            options << o.toString();
        }
        const int status = dcmdump(dcmdumpProgram, options, file);
        QVERIFY2(status == 0 || status == 1, qPrintable(QString("dcmdump: status %1").arg(status)));
        const bool dcmtkReads = status == 0;
        const bool divergent = quirk.contains("divergence");
        const LucentResult lucent = loadWithLucent(file);
        const QString what = QString("%1: dcmdump %2 reads it, Lucent %3 (%4)")
                                 .arg(quirk["what"].toString(), options.join(' '))
                                 .arg(lucent.loaded ? "loads it" : "refuses it", lucent.reason);
        QVERIFY2(lucent.loaded == (dcmtkReads != divergent),
                 qPrintable((dcmtkReads ? "" : "not: ") + what));
        if (lucent.loaded) {
            // Compressed: the voxels are those of the same image uncompressed. Where
            // DCMTK cannot read the file, they are its source's.
            const QString reference = quirk.contains("pixels_of") ? quirk["pixels_of"].toString()
                                      : dcmtkReads                ? QString()
                                                                  : quirk["source"].toString();
            compareWithDcmtk(lucent.volume, reference.isEmpty()
                                                ? file
                                                : test::kRealData / reference.toStdString());
        } else {
            // The message names the file, the offset and the reason.
            QVERIFY2(lucent.reason.startsWith(QString::fromStdString(file.string())),
                     qPrintable(lucent.reason));
            QVERIFY2(lucent.reason.contains(" at byte "), qPrintable(lucent.reason));
        }
    }

    // What was untidy is said, with the number of bytes or the element.
    void warningsSayWhatWasUntidy() {
        const auto warnings = [](const char* name) {
            return loadWithLucent(kQuirks / (std::string(name) + ".dcm")).warnings;
        };
        QVERIFY(
            anyContains(warnings("trailing-zeros"), "2500000 zero bytes after the last element"));
        QVERIFY(anyContains(warnings("trailing-zeros-odd-count"), "3 zero bytes"));
        QVERIFY(anyContains(warnings("meta-explicit-data-implicit"), "data set is in implicit VR"));
        QVERIFY(anyContains(warnings("meta-group-length-wrong"), "group length (0002,0000)"));
        QVERIFY(anyContains(warnings("imager-pixel-spacing"), "ImagerPixelSpacing (0018,1164)"));
        QVERIFY(warnings("group-lengths-absent").empty());
    }

    // Issue 27: one file of a series padded with 2.5 MB of zeros after its last
    // element; the series keeps all its slices, and its voxels are those of the
    // files without padding. Zeros followed by anything else are refused.
    void zeroPaddingKeepsEverySlice() {
        REQUIRE_DATA("dcmqi_ct3slice");
        const fs::path source = test::kRealData / "dcmqi_ct3slice";
        QTemporaryDir dir;
        const fs::path padded = dir.path().toStdString();
        for (const char* name : {"01.dcm", "02.dcm", "03.dcm"}) {
            copyFile(source / name, padded / name, name[1] == '2' ? 2500000 : 0);
        }
        const Catalog c = scanPath(padded);
        QCOMPARE(c.series.size(), std::size_t(1));
        QCOMPARE(c.series.front().slices.size(), std::size_t(3));
        QVERIFY2(anyContains(c.series.front().warnings, "02.dcm: 2500000 zero bytes"),
                 c.series.front().warnings.empty() ? "no warning"
                                                   : c.series.front().warnings.front().c_str());
        const Volume withPadding = loadSeries(c.series.front());
        const Volume original = loadPath(source, c.series.front().id);
        QCOMPARE(withPadding.byteCount(), original.byteCount());
        QVERIFY(std::memcmp(withPadding.bytes().data(), original.bytes().data(),
                            original.byteCount()) == 0);

        // Padding in every file, of other lengths: one warning of its kind.
        for (const char* name : {"01.dcm", "02.dcm", "03.dcm"}) {
            copyFile(source / name, padded / name, 4096 * (name[1] - '0'));
        }
        const std::vector<std::string> grouped = scanPath(padded).series.front().warnings;
        QCOMPARE(grouped.size(), std::size_t(1));
        QVERIFY2(grouped.front().find("zero bytes after the last element") != std::string::npos &&
                     grouped.front().find("(and in 2 more files; first: ") != std::string::npos,
                 grouped.front().c_str());

        copyFile(source / "02.dcm", padded / "02.dcm", 4096, "LUCENT");
        const Catalog refused = scanPath(padded);
        QCOMPARE(refused.series.front().slices.size(), std::size_t(2));
        QCOMPARE(refused.skipped.size(), std::size_t(1));
        QCOMPARE(refused.skipped.front().file, (padded / "02.dcm").string());
        const std::uint64_t end = fs::file_size(source / "02.dcm") + 4096;
        QVERIFY2(refused.skipped.front().reason.find("data after 4096 zero bytes") !=
                         std::string::npos &&
                     refused.skipped.front().reason.find("at byte " + std::to_string(end)) !=
                         std::string::npos,
                 refused.skipped.front().reason.c_str());
    }
};

QTEST_GUILESS_MAIN(TestDicomQuirks)
#include "test_dicom_quirks.moc"
