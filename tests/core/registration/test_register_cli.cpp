// lucent-cli register on the real CT: against itself (identity within 0.1 mm), against a
// copy whose ImagePositionPatient moved by a known shift in a new Frame of Reference
// (writePriorStudy: the same anatomy `shift` away, so fixed -> moving is x + shift), and
// the usage errors; --sro writes the shifted copy's registration as a DICOM Spatial
// Registration object that dciodvfy finds no error in, whose moving item maps back by -shift.
// --affine on a copy of the CT resampled under a known affine transform (a MetaImage, no
// Frame of Reference): under 1 mm over the body.
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include "core/formats/MetaImage.h"
#include "core/io/Catalog.h"
#include "tests/support/CliRunner.h"
#include "tests/support/KnownTransform.h"
#include "tests/support/PriorStudy.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";

// The matrix of transform.json: 4 rows of 4.
QList<QList<double>> matrixOf(const QString& file) {
    QFile f(file);
    if (!f.open(QIODevice::ReadOnly)) {
        return {};
    }
    QList<QList<double>> m;
    for (const QJsonValue& row : QJsonDocument::fromJson(f.readAll())["matrix"].toArray()) {
        QList<double> values;
        for (const QJsonValue& v : row.toArray()) {
            values << v.toDouble();
        }
        m << values;
    }
    return m;
}

// The largest distance between where the matrix and x + shift put the corners of a
// 200 mm box around the volume's centre.
double worstCornerError(const QList<QList<double>>& m, const glm::dvec3& centre,
                        const glm::dvec3& shift) {
    double worst = 0.0;
    for (int n = 0; n < 8; ++n) {
        const glm::dvec3 p =
            centre + 100.0 * glm::dvec3(n & 1 ? 1 : -1, n & 2 ? 1 : -1, n & 4 ? 1 : -1);
        glm::dvec3 q;
        for (int r = 0; r < 3; ++r) {
            q[r] = m[r][0] * p.x + m[r][1] * p.y + m[r][2] * p.z + m[r][3];
        }
        worst = std::max(worst, glm::length(q - (p + shift)));
    }
    return worst;
}

} // namespace

class TestRegisterCli : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    QString ct_;

    // `init`: the start the command must report (the CT against itself shares its Frame
    // of Reference; the shifted copy has its own).
    void check(const QString& moving, const glm::dvec3& shift, const QString& init) {
        const QString out = dir_.filePath("transform.json");
        QFile::remove(out);
        const test::CliRun run = test::runCli({"register", ct_, moving, "-o", out, "--stats"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        qInfo("%s", qPrintable(run.out.trimmed()));
        QVERIFY(run.out.contains("fixed -> moving"));
        QVERIFY(run.out.contains("transform=rigid init=" + init + " "));
        QVERIFY(test::statOf(run.out, "iterations") > 0);
        QVERIFY(test::statOf(run.out, "seconds") > 0);
        const QList<QList<double>> m = matrixOf(out);
        QCOMPARE(m.size(), 4);
        QCOMPARE(m[3], (QList<double>{0, 0, 0, 1}));
        // The CT's centre (info: origin -115.5, -1.85, 696.2; 512 x 0.45 mm, 28 x 5 mm).
        const glm::dvec3 centre(-115.5 + 115.3, -1.85 + 115.3, 696.2 - 67.5);
        const double error = worstCornerError(m, centre, shift);
        qInfo("worst corner error %.4f mm", error);
        QVERIFY2(error < 0.1, qPrintable(QString("%1 mm").arg(error)));
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        ct_ = QString::fromStdString((test::kRealData / kCt).string());
    }

    void itself() { check(ct_, glm::dvec3(0.0), "frame"); }

    void shiftedCopy() {
        const glm::dvec3 shift(12.5, -20.0, 7.5);
        const QString moved = dir_.filePath("moved");
        test::writePriorStudy(test::kRealData / kCt, moved.toStdString(), "20200101", shift);
        check(moved, shift, "centres");
    }

    // A 4 % stretch along x, a shear, 5 degrees and 10 mm: --affine finds it within 1 mm
    // at every point of a 10 mm grid inside the body; JSON and --stats say "affine".
    void affine() {
        const Catalog catalog = scanPath(test::kRealData / kCt);
        QVERIFY(catalog.defaultEntry() != nullptr);
        const Volume ct = loadSeries(*catalog.defaultEntry());
        const glm::dmat4 truth = test::affineAbout(volumeCentre(ct.geometry()), {1.04, 1.0, 1.0},
                                                   0.03, 5.0, {10.0, -6.0, 0.0});
        const QString moved = dir_.filePath("affine.mhd");
        writeMetaImage(test::resampled(
                           ct, truth, [](double hu) { return hu; }, "CT", ""),
                       moved.toStdString());
        const QString out = dir_.filePath("affine.json");
        const test::CliRun run =
            test::runCli({"register", ct_, moved, "--affine", "-o", out, "--stats"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        qInfo("%s", qPrintable(run.out.trimmed()));
        QVERIFY(run.out.contains("transform=affine init=centres "));
        QFile f(out);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QJsonObject json = QJsonDocument::fromJson(f.readAll()).object();
        QCOMPARE(json["transform"].toString(), QString("affine"));
        QCOMPARE(json["initialisation"].toString(), QString("geometric centres"));
        const QList<QList<double>> m = matrixOf(out);
        QCOMPARE(m.size(), 4);
        glm::dmat4 found(1.0);
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 4; ++c) {
                found[c][r] = m[r][c];
            }
        }
        const test::Tre tre = test::treOf(test::bodyGrid(ct), truth, found);
        qInfo("affine: TRE mean %.3f max %.3f mm", tre.mean, tre.max);
        QVERIFY2(tre.max < 1.0, qPrintable(QString("max TRE %1 mm").arg(tre.max)));
    }

    void spatialRegistrationObject() {
        const glm::dvec3 shift(6.0, 4.0, -5.0);
        const QString moved = dir_.filePath("moved-sro");
        test::writePriorStudy(test::kRealData / kCt, moved.toStdString(), "20200101", shift);
        const QString sro = dir_.filePath("reg.dcm");
        const test::CliRun run =
            test::runCli({"register", ct_, moved, "-o", dir_.filePath("t.json"), "--sro", sro});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));

        QProcess dciodvfy;
        dciodvfy.setProcessChannelMode(QProcess::MergedChannels);
        dciodvfy.start("dciodvfy", {sro});
        if (dciodvfy.waitForStarted()) {
            QVERIFY(dciodvfy.waitForFinished(60000));
            const QString output = QString::fromUtf8(dciodvfy.readAll());
            for (const QString& line : output.split('\n')) {
                QVERIFY2(!line.startsWith("Error"), qPrintable(output));
            }
        }
        DcmFileFormat file;
        QVERIFY(file.loadFile(sro.toStdString().c_str()).good());
        DcmItem* item = nullptr;
        QVERIFY(
            file.getDataset()->findAndGetSequenceItem(DCM_RegistrationSequence, item, 1).good());
        QVERIFY(item->findAndGetSequenceItem(DCM_MatrixRegistrationSequence, item, 0).good());
        QVERIFY(item->findAndGetSequenceItem(DCM_MatrixSequence, item, 0).good());
        for (int row = 0; row < 3; ++row) {
            Float64 t = 0.0;
            QVERIFY(
                item->findAndGetFloat64(DCM_FrameOfReferenceTransformationMatrix, t, row * 4 + 3)
                    .good());
            // Moving -> fixed: the way back, -shift (the rotation is near identity).
            QVERIFY2(std::abs(t + shift[row]) < 0.2,
                     qPrintable(QString("row %1: %2").arg(row).arg(t)));
        }
        // The series against itself shares its Frame of Reference: no SRO, an error.
        QCOMPARE(test::runCli({"register", ct_, ct_, "-o", dir_.filePath("t.json"), "--sro",
                               dir_.filePath("self.dcm")})
                     .exitCode,
                 3);
    }

    void usage() {
        QCOMPARE(test::runCli({"register", ct_, ct_}).exitCode, 2); // no -o
        QCOMPARE(
            test::runCli({"register", ct_, ct_, "-o", dir_.filePath("t.json"), "--metric", "cc"})
                .exitCode,
            2);
        const test::CliRun missing =
            test::runCli({"register", ct_, dir_.filePath("none"), "-o", dir_.filePath("t.json")});
        QCOMPARE(missing.exitCode, 3);
        const test::CliRun init =
            test::runCli({"register", ct_, ct_, "-o", dir_.filePath("t.json"), "--init", "x"});
        QCOMPARE(init.exitCode, 2);
        QVERIFY(init.err.contains("--init"));
    }
};

QTEST_GUILESS_MAIN(TestRegisterCli)
#include "test_register_cli.moc"
