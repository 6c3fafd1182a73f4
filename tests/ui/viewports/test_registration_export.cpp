// "Save Registrations to the Study Store (DICOM)": the real CT and a prior copy of it in
// another Frame of Reference (DCMTK), shown in a 1x2 grid, registered by a kept transform;
// the save writes one Spatial Registration object into the store, in the CT's study, whose
// matrix takes the prior's points onto the CT's. Without a transform or a store it says why.
#include <QApplication>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcitem.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/store/StudyStore.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/PriorStudy.h"
#include "tests/support/RealData.h"
#include "ui/viewports/GridShape.h"
#include "ui/viewports/RegistrationExport.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportLinks.h"
#include "ui/viewports/ViewportWorkspace.h"

using namespace lucent;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";
const glm::dvec3 kShift(7.5, -4.0, 12.25);

// The matrix of the Registration Sequence item for `frame`, row-major as stored.
std::vector<double> matrixFor(DcmItem& sro, const std::string& frame) {
    for (unsigned long i = 0;; ++i) {
        DcmItem* item = nullptr;
        if (sro.findAndGetSequenceItem(DCM_RegistrationSequence, item, static_cast<int>(i)).bad()) {
            return {};
        }
        OFString uid;
        item->findAndGetOFString(DCM_FrameOfReferenceUID, uid);
        if (uid.c_str() != frame) {
            continue;
        }
        DcmItem* matrixItem = nullptr;
        item->findAndGetSequenceItem(DCM_MatrixRegistrationSequence, matrixItem, 0);
        DcmItem* matrix = nullptr;
        if (matrixItem == nullptr ||
            matrixItem->findAndGetSequenceItem(DCM_MatrixSequence, matrix, 0).bad()) {
            return {};
        }
        std::vector<double> values(16);
        for (unsigned long k = 0; k < 16; ++k) {
            matrix->findAndGetFloat64(DCM_FrameOfReferenceTransformationMatrix, values[k], k);
        }
        return values;
    }
}

} // namespace

class TestRegistrationExport : public QObject {
    Q_OBJECT

private slots:
    void savesTheKeptTransformAsASpatialRegistration() {
        REQUIRE_DATA(kCt);
        QTemporaryDir priorDir;
        QTemporaryDir storeDir;
        const test::PriorStudy prior = test::writePriorStudy(
            test::kRealData / kCt, priorDir.path().toStdString(), "20190101", kShift);
        ViewportWorkspace workspace;
        workspace.grid()->setShape(*gridShape(QStringLiteral("1x2")));
        Viewport* left = workspace.grid()->viewports()[0];
        Viewport* right = workspace.grid()->viewports()[1];
        QString text;
        // No store yet: nothing is written, and it says why.
        QVERIFY(saveRegistrations(workspace, left, &text).empty());
        QVERIFY2(text.contains(QStringLiteral("no study store")), qPrintable(text));
        workspace.links()->setStoreFolder(storeDir.path());

        QSignalSpy shown(&workspace, &ViewportWorkspace::seriesShown);
        workspace.showSeries(left, QString::fromStdString((test::kRealData / kCt).string()), {},
                             ViewportView::Axial);
        workspace.showSeries(right, priorDir.path(), {}, ViewportView::Axial);
        while (shown.count() < 2) {
            QVERIFY(shown.wait(60000));
        }
        QVERIFY(left->session() != nullptr && right->session() != nullptr);
        // Not registered: nothing to save.
        QVERIFY(saveRegistrations(workspace, left, &text).empty());
        QVERIFY2(text.contains(QStringLiteral("no viewport is registered")), qPrintable(text));

        const std::string ct = left->session()->info().seriesUid;
        workspace.links()->setTransform(ct, prior.seriesUid,
                                        glm::translate(glm::dmat4(1.0), kShift));
        const std::vector<SavedRegistration> saved = saveRegistrations(workspace, left, &text);
        QVERIFY2(saved.size() == 1, qPrintable(text));
        QCOMPARE(saved[0].movingSeries.toStdString(), prior.seriesUid);

        const StudyStore store(storeDir.path().toStdString());
        const StoredSeries* reg = nullptr;
        const std::vector<StoredSeries> listed = store.listSeries();
        for (const StoredSeries& s : listed) {
            if (s.info.modality == "REG") {
                reg = &s;
            }
        }
        QVERIFY(reg != nullptr);
        QCOMPARE(reg->info.studyUid, left->session()->info().studyUid);
        const auto files = store.instanceFiles(reg->info.seriesUid);
        QCOMPARE(files.size(), std::size_t{1});
        QCOMPARE(files[0].first, saved[0].sopInstanceUid.toStdString());
        DcmFileFormat file;
        QVERIFY(file.loadFile(files[0].second.c_str()).good());
        // The prior's item takes its points onto the CT's: p_ct = p_prior - shift.
        const std::vector<double> m = matrixFor(*file.getDataset(), prior.frameOfReferenceUid);
        QCOMPARE(m.size(), std::size_t{16});
        QVERIFY(std::abs(m[3] + kShift.x) < 1e-9);
        QVERIFY(std::abs(m[7] + kShift.y) < 1e-9);
        QVERIFY(std::abs(m[11] + kShift.z) < 1e-9);
        QVERIFY(std::abs(m[0] - 1.0) < 1e-12 && std::abs(m[15] - 1.0) < 1e-12);

        // Another store that holds the object but no transform of the pair (the study came
        // from PACS with it): the two series link through it.
        QTemporaryDir otherStore;
        {
            StudyStore other(otherStore.path().toStdString());
            const std::filesystem::path copy = other.temporaryFile();
            std::filesystem::copy_file(files[0].second, copy,
                                       std::filesystem::copy_options::overwrite_existing);
            InstanceRecord record;
            record.series = reg->info;
            record.sopInstanceUid = files[0].first;
            QVERIFY(other.add(copy, record));
            QVERIFY(!other.seriesTransform(ct, prior.seriesUid).has_value());
        }
        ViewportWorkspace second;
        second.grid()->setShape(*gridShape(QStringLiteral("1x2")));
        second.links()->setStoreFolder(otherStore.path());
        QSignalSpy shownAgain(&second, &ViewportWorkspace::seriesShown);
        second.showSeries(second.grid()->viewports()[0],
                          QString::fromStdString((test::kRealData / kCt).string()), {},
                          ViewportView::Axial);
        second.showSeries(second.grid()->viewports()[1], priorDir.path(), {}, ViewportView::Axial);
        while (shownAgain.count() < 2) {
            QVERIFY(shownAgain.wait(60000));
        }
        const SeriesLink link = second.links()->linkBetween(
            *second.grid()->viewports()[0]->session(), *second.grid()->viewports()[1]->session());
        QVERIFY(link.kind == SeriesLink::Kind::Registered);
        QVERIFY(glm::length(link.map(glm::dvec3(1.0, 2.0, 3.0)) -
                            (glm::dvec3(1.0, 2.0, 3.0) + kShift)) < 1e-9);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestRegistrationExport test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_registration_export.moc"
