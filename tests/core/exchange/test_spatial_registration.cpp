// A registration of a real CT with a moved copy of itself (another Frame of
// Reference, another study) written as a DICOM Spatial Registration object:
// dciodvfy finds no error in it, DCMTK reads back the Frames of Reference and the
// matrix (moving -> fixed, the inverse of fixedToMoving); with LUCENT_SRO_PACS a
// real Orthanc accepts it.
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>
#include <filesystem>
#include <numbers>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/exchange/SpatialRegistrationReader.h"
#include "core/exchange/SpatialRegistrationWriter.h"
#include "tests/support/PriorStudy.h"
#include "tests/support/RealData.h"
#ifdef LUCENT_SRO_PACS
#include <QEventLoop>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QNetworkAccessManager>
#include <QNetworkReply>

#include "tests/support/OrthancServer.h"
#endif

using namespace lucent;
namespace fs = std::filesystem;

namespace {

const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";

std::string text(DcmItem& item, const DcmTagKey& tag, unsigned long pos = 0) {
    OFString v;
    item.findAndGetOFString(tag, v, pos);
    return v.c_str();
}

// The series' UIDs and instances, read with DCMTK from every DICOM file in `folder`.
RegisteredSeries readSeries(const fs::path& folder, SpatialRegistrationInput* patient) {
    RegisteredSeries s;
    for (const auto& entry : fs::directory_iterator(folder)) {
        DcmFileFormat file;
        if (!entry.is_regular_file() ||
            file.loadFile(entry.path().c_str(), EXS_Unknown, EGL_noChange, 4096, ERM_autoDetect)
                .bad()) {
            continue;
        }
        DcmDataset& d = *file.getDataset();
        s.studyUid = text(d, DCM_StudyInstanceUID);
        s.seriesUid = text(d, DCM_SeriesInstanceUID);
        s.frameOfReferenceUid = text(d, DCM_FrameOfReferenceUID);
        s.instances.push_back({text(d, DCM_SOPClassUID), text(d, DCM_SOPInstanceUID)});
        if (patient) {
            patient->patientName = text(d, DCM_PatientName);
            patient->patientId = text(d, DCM_PatientID);
            patient->patientBirthDate = text(d, DCM_PatientBirthDate);
            patient->patientSex = text(d, DCM_PatientSex);
            patient->studyUid = s.studyUid;
            patient->studyDate = text(d, DCM_StudyDate);
            patient->studyTime = text(d, DCM_StudyTime);
            patient->studyId = text(d, DCM_StudyID);
            patient->accessionNumber = text(d, DCM_AccessionNumber);
        }
    }
    return s;
}

// Rotation about z by 7 degrees, then a translation: fixed LPS -> moving LPS.
glm::dmat4 knownMatrix() {
    const glm::dmat4 r =
        glm::rotate(glm::dmat4(1.0), 7.0 * std::numbers::pi / 180.0, glm::dvec3(0.0, 0.0, 1.0));
    return glm::translate(glm::dmat4(1.0), glm::dvec3(5.0, -3.0, 2.0)) * r;
}

struct Written {
    fs::path file;
    SpatialRegistrationInput input;
    SpatialRegistrationIds ids;
};

Written writeExample(const QTemporaryDir& dir, const glm::dmat4& fixedToMoving = knownMatrix()) {
    Written w;
    const test::PriorStudy prior =
        test::writePriorStudy(test::kRealData / kCt, fs::path(dir.path().toStdString()) / "moved",
                              "20100101", glm::dvec3(5.0, -3.0, 2.0));
    w.input.fixed = readSeries(test::kRealData / kCt, &w.input);
    w.input.moving = readSeries(fs::path(dir.path().toStdString()) / "moved", nullptr);
    w.input.fixedToMoving = fixedToMoving;
    w.input.contentDescription = "test registration";
    w.file = fs::path(dir.path().toStdString()) / "reg.dcm";
    w.ids = writeSpatialRegistration(w.file, w.input);
    return w;
}

} // namespace

class TestSpatialRegistration : public QObject {
    Q_OBJECT
private slots:
#ifndef LUCENT_SRO_PACS
    void validByDciodvfy() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        const Written w = writeExample(dir);
        QVERIFY(w.input.fixed.instances.size() > 1);
        QCOMPARE(w.input.moving.instances.size(), w.input.fixed.instances.size());
        QVERIFY(w.input.moving.frameOfReferenceUid != w.input.fixed.frameOfReferenceUid);
        QVERIFY(w.input.moving.studyUid != w.input.fixed.studyUid);

        QProcess dciodvfy;
        dciodvfy.setProcessChannelMode(QProcess::MergedChannels);
        dciodvfy.start("dciodvfy", {QString::fromStdString(w.file.string())});
        if (!dciodvfy.waitForStarted()) {
            QSKIP("dciodvfy is not installed");
        }
        QVERIFY(dciodvfy.waitForFinished(60000));
        const QString output = QString::fromUtf8(dciodvfy.readAll());
        const QStringList lines = output.split('\n', Qt::SkipEmptyParts);
        QStringList errors, warnings;
        for (const QString& line : lines) {
            if (line.startsWith("Error")) {
                errors << line;
            } else if (line.startsWith("Warning")) {
                warnings << line;
            }
        }
        qInfo().noquote() << "dciodvfy:" << errors.size() << "errors," << warnings.size()
                          << "warnings";
        for (const QString& line : warnings) {
            qInfo().noquote() << line;
        }
        if (!errors.isEmpty()) {
            qWarning().noquote() << output;
        }
        QVERIFY2(errors.isEmpty(), qPrintable(errors.join('\n')));
    }

    void readsBack() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        const Written w = writeExample(dir);
        DcmFileFormat file;
        QVERIFY(file.loadFile(w.file.c_str()).good());
        QCOMPARE(file.getDataset()->getOriginalXfer(), EXS_LittleEndianExplicit);
        DcmDataset& d = *file.getDataset();
        QCOMPARE(text(d, DCM_SOPClassUID), std::string(UID_SpatialRegistrationStorage));
        QCOMPARE(text(d, DCM_SOPInstanceUID), w.ids.sopInstanceUid);
        QCOMPARE(text(d, DCM_SeriesInstanceUID), w.ids.seriesUid);
        QCOMPARE(text(d, DCM_Modality), std::string("REG"));
        QCOMPARE(text(d, DCM_StudyInstanceUID), w.input.studyUid);
        QCOMPARE(text(d, DCM_FrameOfReferenceUID), w.input.fixed.frameOfReferenceUid);
        QCOMPARE(text(d, DCM_ContentLabel), std::string("LUCENT_REG"));
        QCOMPARE(text(d, DCM_Manufacturer), std::string("Lucent"));

        const glm::dmat4 expected = glm::inverse(knownMatrix());
        DcmItem* items[2] = {nullptr, nullptr};
        for (int k = 0; k < 2; ++k) {
            QVERIFY(d.findAndGetSequenceItem(DCM_RegistrationSequence, items[k], k).good());
        }
        QVERIFY(!d.findAndGetSequenceItem(DCM_RegistrationSequence, items[0], 2).good());
        QVERIFY(d.findAndGetSequenceItem(DCM_RegistrationSequence, items[0], 0).good());
        QCOMPARE(text(*items[0], DCM_FrameOfReferenceUID), w.input.fixed.frameOfReferenceUid);
        QCOMPARE(text(*items[1], DCM_FrameOfReferenceUID), w.input.moving.frameOfReferenceUid);
        for (int k = 0; k < 2; ++k) {
            DcmItem* matrix = nullptr;
            QVERIFY(
                items[k]->findAndGetSequenceItem(DCM_MatrixRegistrationSequence, matrix, 0).good());
            QVERIFY(matrix->findAndGetSequenceItem(DCM_MatrixSequence, matrix, 0).good());
            QCOMPARE(text(*matrix, DCM_FrameOfReferenceTransformationMatrixType),
                     std::string("RIGID"));
            const glm::dmat4 want = k == 0 ? glm::dmat4(1.0) : expected;
            for (int i = 0; i < 16; ++i) {
                Float64 v = 0.0;
                QVERIFY(matrix->findAndGetFloat64(DCM_FrameOfReferenceTransformationMatrix, v, i)
                            .good());
                const int row = i / 4, column = i % 4;
                QVERIFY2(std::abs(v - want[column][row]) < 1e-6,
                         qPrintable(QString("item %1 value %2: %3, expected %4")
                                        .arg(k)
                                        .arg(i)
                                        .arg(v)
                                        .arg(want[column][row])));
            }
            DcmItem* image = nullptr;
            QVERIFY(items[k]->findAndGetSequenceItem(DCM_ReferencedImageSequence, image, 0).good());
        }
        // The moving item maps a moving point back onto the fixed one.
        const glm::dvec4 fixedPoint(10.0, -20.0, 30.0, 1.0);
        const glm::dvec4 movingPoint = knownMatrix() * fixedPoint;
        const glm::dvec4 back = expected * movingPoint;
        QVERIFY(glm::length(glm::dvec3(back - fixedPoint)) < 1e-9);

        // Common Instance Reference: the fixed series in this study, the moving one
        // in the other study.
        DcmItem* series = nullptr;
        QVERIFY(d.findAndGetSequenceItem(DCM_ReferencedSeriesSequence, series, 0).good());
        QCOMPARE(text(*series, DCM_SeriesInstanceUID), w.input.fixed.seriesUid);
        DcmItem* study = nullptr;
        QVERIFY(d.findAndGetSequenceItem(DCM_StudiesContainingOtherReferencedInstancesSequence,
                                         study, 0)
                    .good());
        QCOMPARE(text(*study, DCM_StudyInstanceUID), w.input.moving.studyUid);
        QVERIFY(study->findAndGetSequenceItem(DCM_ReferencedSeriesSequence, series, 0).good());
        QCOMPARE(text(*series, DCM_SeriesInstanceUID), w.input.moving.seriesUid);
    }

    void readerGivesTheWrittenTransform() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        const Written w = writeExample(dir);
        const SpatialRegistration read = readSpatialRegistration(w.file);
        QCOMPARE(read.sopInstanceUid, w.ids.sopInstanceUid);
        QCOMPARE(read.frameOfReferenceUid, w.input.fixed.frameOfReferenceUid);
        QCOMPARE(read.frames.size(), std::size_t{2});
        const auto fixedToMoving = frameTransform(read, w.input.fixed.frameOfReferenceUid,
                                                  w.input.moving.frameOfReferenceUid);
        QVERIFY(fixedToMoving.has_value());
        const auto back = frameTransform(read, w.input.moving.frameOfReferenceUid,
                                         w.input.fixed.frameOfReferenceUid);
        for (int c = 0; c < 4; ++c) {
            QVERIFY(glm::length((*fixedToMoving)[c] - knownMatrix()[c]) < 1e-9);
            QVERIFY(glm::length((*back)[c] - glm::inverse(knownMatrix())[c]) < 1e-9);
        }
        QVERIFY(!frameTransform(read, w.input.fixed.frameOfReferenceUid, "1.2.3").has_value());

        // Another program may put neither frame at the identity: the pair's transform is
        // still inverse(M_to) * M_from.
        DcmFileFormat file;
        QVERIFY(file.loadFile(w.file.c_str()).good());
        DcmItem* reg = nullptr;
        DcmItem* matrixRegistration = nullptr;
        DcmItem* matrix = nullptr;
        QVERIFY(file.getDataset()->findAndGetSequenceItem(DCM_RegistrationSequence, reg, 0).good());
        QVERIFY(reg->findAndGetSequenceItem(DCM_MatrixRegistrationSequence, matrixRegistration, 0)
                    .good());
        QVERIFY(matrixRegistration->findAndGetSequenceItem(DCM_MatrixSequence, matrix, 0).good());
        QVERIFY(matrix
                    ->putAndInsertString(DCM_FrameOfReferenceTransformationMatrix,
                                         "1\\0\\0\\10\\0\\1\\0\\20\\0\\0\\1\\30\\0\\0\\0\\1")
                    .good());
        const fs::path shifted = fs::path(dir.path().toStdString()) / "shifted.dcm";
        QVERIFY(file.saveFile(shifted.c_str(), EXS_LittleEndianExplicit).good());
        const auto viaShift =
            frameTransform(readSpatialRegistration(shifted), w.input.fixed.frameOfReferenceUid,
                           w.input.moving.frameOfReferenceUid);
        const glm::dmat4 expected =
            knownMatrix() * glm::translate(glm::dmat4(1.0), glm::dvec3(10.0, 20.0, 30.0));
        for (int c = 0; c < 4; ++c) {
            QVERIFY(glm::length((*viaShift)[c] - expected[c]) < 1e-9);
        }

        // What it cannot use is refused, naming the file and the element.
        QVERIFY(matrix
                    ->putAndInsertString(DCM_FrameOfReferenceTransformationMatrix,
                                         "1\\0\\0\\0\\0\\0\\0\\0\\0\\0\\1\\0\\0\\0\\0\\1")
                    .good());
        const fs::path singular = fs::path(dir.path().toStdString()) / "singular.dcm";
        QVERIFY(file.saveFile(singular.c_str(), EXS_LittleEndianExplicit).good());
        const auto refuses = [](const fs::path& f, const char* element) {
            try {
                readSpatialRegistration(f);
            } catch (const std::runtime_error& e) {
                const std::string what = e.what();
                return what.find(f.string()) != std::string::npos &&
                       what.find(element) != std::string::npos;
            }
            return false;
        };
        QVERIFY(refuses(singular, "(3006,00C6) is singular"));
        fs::path ctFile;
        for (const auto& entry : fs::directory_iterator(test::kRealData / kCt)) {
            if (entry.is_regular_file()) {
                ctFile = entry.path();
                break;
            }
        }
        QVERIFY(refuses(ctFile, "SOPClassUID (0008,0016)"));
    }

    // The matrix type follows the matrix: an affine registration (lucent-cli register
    // --affine) is AFFINE, a rotation with a uniform scale RIGID_SCALE; the fixed item's
    // identity stays RIGID.
    void matrixTypeFollowsTheMatrix_data() {
        QTest::addColumn<glm::dmat4>("fixedToMoving");
        QTest::addColumn<QString>("type");
        glm::dmat4 sheared = glm::scale(knownMatrix(), glm::dvec3(1.04, 1.0, 1.0));
        sheared[1][0] += 0.03;
        QTest::newRow("affine") << sheared << "AFFINE";
        QTest::newRow("scaled rotation")
            << glm::scale(knownMatrix(), glm::dvec3(1.1)) << "RIGID_SCALE";
        QTest::newRow("rigid") << knownMatrix() << "RIGID";
    }
    void matrixTypeFollowsTheMatrix() {
        REQUIRE_DATA(kCt);
        QFETCH(glm::dmat4, fixedToMoving);
        QFETCH(QString, type);
        QTemporaryDir dir;
        const Written w = writeExample(dir, fixedToMoving);
        DcmFileFormat file;
        QVERIFY(file.loadFile(w.file.c_str()).good());
        for (int k = 0; k < 2; ++k) {
            DcmItem* item = nullptr;
            QVERIFY(file.getDataset()
                        ->findAndGetSequenceItem(DCM_RegistrationSequence, item, k)
                        .good());
            QVERIFY(item->findAndGetSequenceItem(DCM_MatrixRegistrationSequence, item, 0).good());
            QVERIFY(item->findAndGetSequenceItem(DCM_MatrixSequence, item, 0).good());
            QCOMPARE(
                QString::fromStdString(text(*item, DCM_FrameOfReferenceTransformationMatrixType)),
                k == 0 ? QString("RIGID") : type);
        }
    }

    void failsNamingTheFile() {
        SpatialRegistrationInput in;
        in.studyUid = "1.2.3";
        try {
            writeSpatialRegistration("/nonexistent-folder/reg.dcm", in);
            QFAIL("no exception");
        } catch (const std::runtime_error& e) {
            QVERIFY(std::string(e.what()).find("/nonexistent-folder/reg.dcm") != std::string::npos);
        }
    }
#else
    void orthancAcceptsIt() {
        REQUIRE_DATA(kCt);
        test::OrthancServer orthanc;
        if (!orthanc.isRunning()) {
            QSKIP(qPrintable("Orthanc did not start: " + orthanc.error()));
        }
        QTemporaryDir dir;
        const Written w = writeExample(dir);
        QVERIFY2(orthanc.store({QString::fromStdString(w.file.string())}),
                 qPrintable(orthanc.error()));
        // Orthanc's REST API: the instance is stored, as a REG of the fixed study.
        QNetworkAccessManager net;
        const QString base = QString("http://127.0.0.1:%1").arg(orthanc.httpPort());
        auto call = [&](QNetworkReply* reply) {
            QEventLoop loop;
            QObject::connect(reply, &QNetworkReply::finished, &loop, &QEventLoop::quit);
            loop.exec();
            reply->deleteLater();
            return QJsonDocument::fromJson(reply->readAll());
        };
        QNetworkRequest lookup(QUrl(base + "/tools/lookup"));
        lookup.setHeader(QNetworkRequest::ContentTypeHeader, "text/plain");
        const QJsonArray found =
            call(net.post(lookup, QByteArray::fromStdString(w.ids.sopInstanceUid))).array();
        QCOMPARE(found.size(), 1);
        QCOMPARE(found[0].toObject()["Type"].toString(), QString("Instance"));
        const QJsonObject tags =
            call(net.get(QNetworkRequest(QUrl(base + "/instances/" +
                                              found[0].toObject()["ID"].toString() +
                                              "/simplified-tags"))))
                .object();
        QCOMPARE(tags["Modality"].toString(), QString("REG"));
        QCOMPARE(tags["StudyInstanceUID"].toString(), QString::fromStdString(w.input.studyUid));
        QCOMPARE(tags["SOPClassUID"].toString(), QString(UID_SpatialRegistrationStorage));
    }
#endif
};

QTEST_GUILESS_MAIN(TestSpatialRegistration)
#include "test_spatial_registration.moc"
