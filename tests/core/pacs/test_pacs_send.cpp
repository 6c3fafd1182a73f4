// Sending to a real Orthanc on loopback: C-STORE and STOW-RS of real DICOM
// files (uncompressed and compressed), each instance retrieved back by WADO-RS
// and compared element by element, byte for byte. Label pacs.
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcostrmb.h>

#include "core/pacs/DicomWebClient.h"
#include "core/pacs/InstanceSender.h"
#include "tests/support/CliRunner.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/RealData.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

const fs::path kData = test::kRealData;

// The data set of a file (every element but the file meta group, which each
// writer makes for itself), written in its own transfer syntax with explicit
// lengths, so equal values give equal bytes.
QByteArray datasetBytes(const fs::path& file) {
    DcmFileFormat f;
    if (f.loadFile(file.c_str()).bad()) {
        return {};
    }
    DcmDataset& d = *f.getDataset();
    const E_TransferSyntax xfer = d.getOriginalXfer();
    d.transferInit();
    const Uint32 length = d.calcElementLength(xfer, EET_ExplicitLength);
    QByteArray out(static_cast<qsizetype>(length) + 1024, '\0');
    DcmOutputBufferStream stream(out.data(), static_cast<offile_off_t>(out.size()));
    d.write(stream, xfer, EET_ExplicitLength, nullptr);
    d.transferEnd();
    void* buffer = nullptr;
    offile_off_t filled = 0;
    stream.flushBuffer(buffer, filled);
    out.truncate(static_cast<qsizetype>(filled));
    return out;
}

std::vector<InstanceHeader> headersOf(const std::vector<fs::path>& files) {
    std::vector<InstanceHeader> out;
    for (const fs::path& f : files) {
        out.push_back(readInstanceHeader(f));
    }
    return out;
}

} // namespace

class TestPacsSend : public QObject {
    Q_OBJECT
    std::unique_ptr<test::OrthancServer> orthanc_;
    DicomWebService service_;

    PacsNode node() const { return PacsNode::parse(orthanc_->node().toStdString()); }

    // Retrieves the series of `sent` by WADO-RS (transfer-syntax=*: as
    // stored) into a fresh store and compares each instance with its file.
    void verifyStoredAsSent(const std::vector<InstanceHeader>& sent) {
        QTemporaryDir storeDir;
        StudyStore store(storeDir.path().toStdString());
        std::map<std::string, fs::path> retrieved;
        std::set<std::pair<std::string, std::string>> series;
        for (const InstanceHeader& h : sent) {
            series.insert({h.studyUid, h.seriesUid});
        }
        for (const auto& [study, uid] : series) {
            const RetrieveResult r = wadoRetrieveSeries(service_, study, uid, store);
            QVERIFY(r.complete);
            for (const auto& entry : fs::directory_iterator(r.folder)) {
                retrieved[readInstanceHeader(entry.path()).sopInstanceUid] = entry.path();
            }
        }
        for (const InstanceHeader& h : sent) {
            const auto found = retrieved.find(h.sopInstanceUid);
            QVERIFY2(found != retrieved.end(), h.file.c_str());
            QCOMPARE(readInstanceHeader(found->second).transferSyntaxUid, h.transferSyntaxUid);
            const QByteArray original = datasetBytes(h.file);
            QVERIFY(original.size() > 1000);
            QVERIFY2(datasetBytes(found->second) == original, h.file.c_str());
        }
    }

private slots:
    void initTestCase() {
        orthanc_ = std::make_unique<test::OrthancServer>();
        QVERIFY2(orthanc_->isRunning(), qPrintable("no test PACS: " + orthanc_->error()));
        service_.baseUrl = orthanc_->dicomWebUrl().toStdString();
        service_.timeoutSeconds = 20;
    }
    void cleanupTestCase() { orthanc_.reset(); }

    void cStoreKeepsEveryByte() {
        REQUIRE_DATA("dcmqi_ct3slice");
        REQUIRE_DATA("nema_wg04/CT1/CT1_JPLL.dcm");
        // Implicit little endian CT, a segmentation, and JPEG lossless in its own syntax.
        const std::vector<InstanceHeader> sent =
            headersOf({kData / "dcmqi_ct3slice/01.dcm", kData / "dcmqi_ct3slice/02.dcm",
                       kData / "dcmqi_ct3slice/03.dcm", kData / "dcmqi_ct3slice/liver_seg.dcm",
                       kData / "nema_wg04/CT1/CT1_JPLL.dcm"});
        std::vector<std::pair<int, int>> progress;
        SendControl control;
        control.onProgress = [&](int done, int total) { progress.emplace_back(done, total); };
        const SendResult r = sendByCStore(node(), {}, sent, control);
        for (const SentInstance& s : r.instances) {
            QVERIFY2(s.outcome == SentInstance::Outcome::Stored, s.message.c_str());
        }
        QCOMPARE(progress.size(), std::size_t(5));
        QCOMPARE(progress.back(), std::make_pair(5, 5));
        verifyStoredAsSent(sent);
    }

    void stowKeepsEveryByte() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        REQUIRE_DATA("nema_wg04/MR1/MR1_RLE.dcm");
        std::vector<std::string> passedOver;
        std::vector<InstanceHeader> sent =
            collectInstances(kData / "dcm_qa_ct/Philips_S21570/S2010", "", passedOver);
        QCOMPARE(sent.size(), std::size_t(28));
        sent.push_back(readInstanceHeader(kData / "nema_wg04/MR1/MR1_RLE.dcm"));
        const SendResult r = sendByStow(service_, sent);
        for (const SentInstance& s : r.instances) {
            QVERIFY2(s.outcome == SentInstance::Outcome::Stored, s.message.c_str());
        }
        verifyStoredAsSent(sent);
    }

    void cancelLeavesTheRestUnsent() {
        REQUIRE_DATA("dcmqi_ct3slice");
        const std::vector<InstanceHeader> sent =
            headersOf({kData / "dcmqi_ct3slice/01.dcm", kData / "dcmqi_ct3slice/02.dcm",
                       kData / "dcmqi_ct3slice/03.dcm"});
        std::stop_source stop;
        SendControl control;
        control.stop = stop.get_token();
        control.onProgress = [&](int done, int) {
            if (done == 1) {
                stop.request_stop();
            }
        };
        const SendResult r = sendByCStore(node(), {}, sent, control);
        QVERIFY(r.cancelled);
        QCOMPARE(r.count(SentInstance::Outcome::Stored), 1);
        QCOMPARE(r.count(SentInstance::Outcome::NotSent), 2);
        QVERIFY(!r.allStored());
    }

    void deadPacsNamesTheNode() {
        REQUIRE_DATA("dcmqi_ct3slice");
        const std::vector<InstanceHeader> sent = headersOf({kData / "dcmqi_ct3slice/01.dcm"});
        const int port = test::OrthancServer::freePort();
        const PacsNode dead = PacsNode::parse("NOBODY@127.0.0.1:" + std::to_string(port));
        try {
            sendByCStore(dead, {}, sent);
            QFAIL("sent to a port nobody listens on");
        } catch (const PacsError& e) {
            const QString m = e.what();
            QVERIFY2(m.contains(QString("NOBODY@127.0.0.1:%1").arg(port)), e.what());
            QVERIFY2(m.contains("refused"), e.what());
        }
        DicomWebService deadWeb;
        deadWeb.baseUrl = "http://127.0.0.1:" + std::to_string(port) + "/dicom-web";
        try {
            sendByStow(deadWeb, sent);
            QFAIL("sent to a port nobody listens on");
        } catch (const PacsError& e) {
            QVERIFY2(QString(e.what()).contains(QString::fromStdString(deadWeb.baseUrl)), e.what());
        }
    }

    void commandLine() {
        REQUIRE_DATA("dcmqi_ct3slice");
        const QString dir = QString::fromStdString((kData / "dcmqi_ct3slice").string());
        const std::string ctSeries = readInstanceHeader(kData / "dcmqi_ct3slice/01.dcm").seriesUid;
        test::CliRun run = test::runCli({"pacs", "send", "--pacs", orthanc_->node(), "--series",
                                         QString::fromStdString(ctSeries), dir});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        QVERIFY2(run.out.contains("3 of 3 instance(s) stored"), qPrintable(run.out));
        QVERIFY2(run.err.contains("LICENSE"), qPrintable(run.err)); // passed over, and said so
        run = test::runCli({"pacs", "send", "--stow", orthanc_->dicomWebUrl(), "--json", dir});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        QCOMPARE(run.out.count("\"outcome\": \"stored\""), 4);
        run = test::runCli({"pacs", "send", "--pacs", "X@127.0.0.1:1", dir});
        QCOMPARE(run.exitCode, 4);
        QVERIFY2(run.err.contains("X@127.0.0.1:1"), qPrintable(run.err));
        run = test::runCli({"pacs", "send", dir});
        QCOMPARE(run.exitCode, 2);
    }
};

QTEST_MAIN(TestPacsSend)
#include "test_pacs_send.moc"
