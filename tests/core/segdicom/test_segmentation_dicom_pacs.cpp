// Lucent's SEG of the real CT saved in a study store, sent with the CT to a real Orthanc
// (C-STORE), retrieved by C-GET into a fresh store and loaded again equal. Label pacs.
#include <QTemporaryDir>
#include <QTest>

#include "core/exchange/InstanceFiles.h"
#include "core/pacs/InstanceSender.h"
#include "core/pacs/SeriesRetriever.h"
#include "core/segdicom/SegmentationArchive.h"
#include "tests/core/report/StoredCopies.h"
#include "tests/core/segdicom/SegmentedCt.h"
#include "tests/support/OrthancServer.h"

using namespace lucent;
namespace fs = std::filesystem;

class TestSegmentationDicomPacs : public QObject {
    Q_OBJECT

private slots:
    void sentRetrievedAndLoadedAgain() {
        REQUIRE_DATA(test::kSegmentedCt);
        const test::OrthancServer orthanc;
        QVERIFY2(orthanc.isRunning(), qPrintable("no test PACS: " + orthanc.error()));
        const PacsNode node = PacsNode::parse(orthanc.node().toStdString());

        QTemporaryDir here;
        StudyStore store(here.path().toStdString());
        for (const fs::path& file : test::segmentedCtFiles()) {
            QVERIFY(test::storeCopy(store, file, "CT"));
        }
        const Volume ct = loadPath(test::kRealData / test::kSegmentedCt);
        const Segmentation seg = test::segmentedCt(ct);
        SegmentationArchive archive(store);
        const ReferencedSeries& series = archive.referencedSeries(
            readInstanceHeader(test::segmentedCtFiles().front()).seriesUid);
        const std::string segSop = archive.save(series.seriesUid, seg);

        // The study, the SEG among it, to the PACS.
        std::vector<InstanceHeader> sent;
        std::string segSeries;
        for (const StoredSeries& s : store.listSeries()) {
            for (const auto& [sop, file] : store.instanceFiles(s.info.seriesUid)) {
                sent.push_back(readInstanceHeader(file));
                if (sop == segSop) {
                    segSeries = s.info.seriesUid;
                    QCOMPARE(sent.back().sopClassUid, std::string(kSegmentationSopClassUid));
                }
            }
        }
        QCOMPARE(sent.size(), std::size_t(141));
        const SendResult result = sendByCStore(node, {}, sent);
        for (const SentInstance& s : result.instances) {
            QVERIFY2(s.outcome == SentInstance::Outcome::Stored, s.message.c_str());
        }

        QTemporaryDir there;
        StudyStore fresh(there.path().toStdString());
        for (const std::string& uid : {series.seriesUid, segSeries}) {
            const RetrieveResult r = retrieveSeries(node, {}, series.studyUid, uid, fresh);
            QVERIFY2(r.complete, uid.c_str());
        }
        SegmentationArchive again(fresh);
        const auto loaded = again.load(series.seriesUid, ct.geometry());
        QVERIFY(loaded.errors.empty());
        QCOMPARE(loaded.loaded.size(), std::size_t(1));
        const auto& read = loaded.loaded.front().segmentation;
        QCOMPARE(read.header.sopInstanceUid, segSop);
        QCOMPARE(read.segments.size(), seg.segments().size());
        for (std::size_t i = 0; i < read.segments.size(); ++i) {
            QCOMPARE(read.segments[i].name, seg.segments()[i].name);
            QVERIFY(read.segments[i].type == seg.segments()[i].type);
            QVERIFY(read.segments[i].colour == seg.segments()[i].colour);
            QVERIFY2(*read.segments[i].mask == *seg.segments()[i].mask,
                     seg.segments()[i].name.c_str());
        }
    }
};

QTEST_GUILESS_MAIN(TestSegmentationDicomPacs)
#include "test_segmentation_dicom_pacs.moc"
