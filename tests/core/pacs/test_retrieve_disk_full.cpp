// A study store on a 2 MiB tmpfs that fills during a retrieval (C-GET and
// WADO-RS from a real Orthanc): the retrieval fails with an error naming the
// store and "no space", no partial file is left (in tmp/ or files/), the index
// agrees with the files, and once the file system is grown the next retrieval
// fetches only the rest. Needs root to mount the tmpfs (the tests run as
// root); without it the test fails and says why. Label pacs.
#include <QTemporaryDir>
#include <QTest>

#include <cerrno>
#include <cstring>
#include <memory>

#include <fcntl.h>
#include <sys/mount.h>
#include <unistd.h>

#include "StoreConsistency.h"
#include "core/pacs/DicomWebClient.h"
#include "core/pacs/SeriesRetriever.h"
#include "tests/support/OrthancServer.h"
#include "tests/support/SyntheticDicom.h"

using namespace lucent;

namespace {
const char* kStudy = "1.2.826.0.1.3680043.2.1125.971";
const char* kSeries = "1.2.826.0.1.3680043.2.1125.9711";
// 100 images of 128 x 128 x 16 bit: about 3.3 MiB, more than the tmpfs holds.
constexpr int kImages = 100;
constexpr int kSide = 128;

// A tmpfs of `size` mounted on a new temporary folder, unmounted on destruction.
class SmallFileSystem {
public:
    explicit SmallFileSystem(const char* size) {
        if (!dir_.isValid()) {
            error_ = "cannot create a temporary folder for the tmpfs";
            return;
        }
        const std::string options = std::string("size=") + size;
        if (::mount("tmpfs", dir_.path().toUtf8().constData(), "tmpfs", 0, options.c_str()) != 0) {
            error_ = QString("cannot mount a %1 tmpfs on %2: %3 (the test needs root, or "
                             "CAP_SYS_ADMIN, to make a small file system)")
                         .arg(size, dir_.path(), std::strerror(errno));
            return;
        }
        mounted_ = true;
    }
    ~SmallFileSystem() {
        if (mounted_) {
            ::umount2(dir_.path().toUtf8().constData(), MNT_DETACH);
        }
    }
    SmallFileSystem(const SmallFileSystem&) = delete;
    SmallFileSystem& operator=(const SmallFileSystem&) = delete;

    bool mounted() const { return mounted_; }
    const QString& error() const { return error_; }
    std::filesystem::path path() const { return dir_.path().toStdString(); }
    // Grows (or shrinks) it in place; empty on success, else why not.
    QString resize(const char* size) {
        const std::string options = std::string("size=") + size;
        if (::mount("tmpfs", dir_.path().toUtf8().constData(), "tmpfs", MS_REMOUNT,
                    options.c_str()) != 0) {
            return QString("cannot remount the tmpfs with %1: %2").arg(size, std::strerror(errno));
        }
        return {};
    }

private:
    QTemporaryDir dir_;
    bool mounted_ = false;
    QString error_;
};
} // namespace

class TestRetrieveDiskFull : public QObject {
    Q_OBJECT
    std::unique_ptr<test::OrthancServer> orthanc_;
    QTemporaryDir files_;

    // Writes a small image of its own series into a temporary file of the store.
    static std::pair<std::filesystem::path, InstanceRecord> incoming(StudyStore& store, int n) {
        test::SyntheticSeries s;
        s.studyUid = "1.2.826.0.1.3680043.2.1125.972";
        s.seriesUid = "1.2.826.0.1.3680043.2.1125.9721";
        const std::filesystem::path temp = store.temporaryFile();
        test::writeImage(temp.string(), s, n, {0.0, 0.0, 1.0 * n}, n + 1);
        DcmFileFormat file;
        OFString sop;
        file.loadFile(temp.c_str());
        file.getDataset()->findAndGetOFString(DCM_SOPInstanceUID, sop);
        InstanceRecord r;
        r.series.studyUid = s.studyUid;
        r.series.seriesUid = s.seriesUid;
        r.sopInstanceUid = sop.c_str();
        return {temp, r};
    }

    // Retrieves into a store on a 2 MiB tmpfs until it is full; checks the
    // error and the store; grows the file system; retrieves the rest.
    template <class Retrieve> void fillTheStore(Retrieve retrieve) {
        SmallFileSystem fs("2m");
        QVERIFY2(fs.mounted(), qPrintable(fs.error()));
        const std::filesystem::path root = fs.path() / "store";
        int stored = 0;
        {
            StudyStore store(root);
            try {
                retrieve(store);
                QFAIL("the retrieval into a 2 MiB store did not fail");
            } catch (const StoreError& e) {
                const QString message = e.what();
                qInfo().noquote() << "full store:" << message;
                QVERIFY2(message.contains(QString::fromStdString(root.string())) &&
                             message.contains("no space"),
                         qPrintable(message));
            }
            stored = test::checkStoreConsistent(store, kSeries);
            QVERIFY(stored >= 0);
            QVERIFY2(stored > 0 && stored < kImages, qPrintable(QString::number(stored)));
            QVERIFY(!store.isComplete(kSeries));
            std::error_code ec;
            const std::filesystem::space_info space = std::filesystem::space(root, ec);
            qInfo().noquote() << QString("%1 of %2 instances stored, %3 KiB left free")
                                     .arg(stored)
                                     .arg(kImages)
                                     .arg(space.available / 1024);
        }
        // Nothing was lost: with room again, only the rest is fetched.
        const QString grown = fs.resize("16m");
        QVERIFY2(grown.isEmpty(), qPrintable(grown));
        StudyStore store(root);
        RetrieveResult rest;
        try {
            rest = retrieve(store);
        } catch (const std::exception& e) {
            QFAIL(e.what());
        }
        QCOMPARE(rest.alreadyStored, stored);
        QCOMPARE(rest.received, kImages - stored);
        QVERIFY(rest.complete);
        QCOMPARE(test::checkStoreConsistent(store, kSeries), kImages);
    }

private slots:
    // The index cannot grow on a full disk: the instance being added (and,
    // in a batch, those whose rows the failed commit lost) leave files/ again.
    void indexWriteFailsOnAFullDisk() {
        SmallFileSystem fs("2m");
        QVERIFY2(fs.mounted(), qPrintable(fs.error()));
        const std::filesystem::path root = fs.path() / "store";
        StudyStore store(root);
        const std::string series = "1.2.826.0.1.3680043.2.1125.9721";
        std::vector<std::pair<std::filesystem::path, InstanceRecord>> files;
        for (int n = 0; n < 4; ++n) { // written while there is room
            files.push_back(incoming(store, n));
        }
        QVERIFY(store.add(files[0].first, files[0].second));
        // Fill the file system to the last byte.
        const std::string fillerPath = (fs.path() / "filler").string();
        const int filler = ::open(fillerPath.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
        QVERIFY(filler >= 0);
        const std::vector<char> block(64 * 1024, 'x');
        for (std::size_t size = block.size(); size > 0; size /= 2) {
            while (::write(filler, block.data(), size) == ssize_t(size)) {
            }
        }
        ::close(filler);
        try {
            store.add(files[1].first, files[1].second);
            QFAIL("an instance was indexed on a full disk");
        } catch (const StoreError& e) {
            qInfo().noquote() << "index on a full disk:" << e.what();
            QVERIFY2(QString(e.what()).contains("no space") &&
                         QString(e.what()).contains(QString::fromStdString(root.string())),
                     e.what());
        }
        QVERIFY(!std::filesystem::exists(files[1].first));
        QCOMPARE(store.instancesOf(series).size(), std::size_t(1));
        // In a batch SQLite may keep the rows in memory until the commit,
        // which then fails: their files go with them.
        try {
            const StudyStore::Batch batch(store);
            store.add(files[2].first, files[2].second);
            store.add(files[3].first, files[3].second);
        } catch (const StoreError& e) {
            qInfo().noquote() << "batch on a full disk:" << e.what();
        }
        QCOMPARE(test::checkStoreConsistent(store, series), 1);
        std::filesystem::remove(fillerPath);
        QCOMPARE(test::checkStoreConsistent(store, series), 1);
    }

    void initTestCase() {
        orthanc_ = std::make_unique<test::OrthancServer>();
        QVERIFY2(orthanc_->isRunning(), qPrintable("no test PACS: " + orthanc_->error()));
        test::SyntheticSeries s;
        s.patientName = "Full^Fiona";
        s.patientId = "F001";
        s.studyUid = kStudy;
        s.seriesUid = kSeries;
        s.columns = kSide;
        s.rows = kSide;
        std::vector<glm::dvec3> positions;
        for (int k = 0; k < kImages; ++k) {
            positions.emplace_back(0.0, 0.0, 1.0 * k);
        }
        QStringList series;
        for (const std::string& f : test::writeSeries(files_.path().toStdString(), s, positions)) {
            series << QString::fromStdString(f);
        }
        QVERIFY2(orthanc_->store(series), qPrintable(orthanc_->error()));
    }
    void cleanupTestCase() { orthanc_.reset(); }

    void cGetFillsTheStore() {
        const PacsNode node = PacsNode::parse(orthanc_->node().toStdString());
        PacsSettings settings;
        settings.connectTimeoutSeconds = 5;
        settings.responseTimeoutSeconds = 10;
        fillTheStore([&](StudyStore& store) {
            return retrieveSeries(node, settings, kStudy, kSeries, store);
        });
    }

    void wadoFillsTheStore() {
        DicomWebService web;
        web.baseUrl = orthanc_->dicomWebUrl().toStdString();
        web.timeoutSeconds = 10;
        fillTheStore(
            [&](StudyStore& store) { return wadoRetrieveSeries(web, kStudy, kSeries, store); });
    }
};

QTEST_GUILESS_MAIN(TestRetrieveDiskFull)
#include "test_retrieve_disk_full.moc"
