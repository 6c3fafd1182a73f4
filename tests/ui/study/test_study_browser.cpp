// The study browser on real DICOM: patients -> studies -> series from the local
// study store and from an opened folder, thumbnails of each series' middle
// image made in the background, a click that asks to open a series.
#include <QApplication>
#include <QLabel>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QTreeWidget>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include <cstring>
#include <filesystem>

#include "core/image/Image.h"
#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/mpr/PlaneSampler.h"
#include "core/store/StudyStore.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/study/StudyBrowser.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

const fs::path kData = LUCENT_TEST_DATA_DIR;
const fs::path kPhilips = kData / "dcm_qa_ct/Philips_S21570";
const fs::path kAbdomen = kData / "dcmqi_ct3slice";

// Puts every image of the catalog's CT series into the store, as a retrieval would.
int storeSeries(StudyStore& store, const Catalog& catalog) {
    int added = 0;
    for (const SeriesEntry& entry : catalog.series) {
        for (const SliceRef& slice : entry.slices) {
            DcmFileFormat file;
            if (file.loadFile(slice.file.c_str()).bad()) {
                throw std::runtime_error("cannot read " + slice.file);
            }
            OFString sop;
            file.getDataset()->findAndGetOFString(DCM_SOPInstanceUID, sop);
            InstanceRecord record;
            record.series = entry;
            record.sopInstanceUid = sop.c_str();
            const fs::path tmp = store.temporaryFile();
            fs::copy_file(slice.file, tmp);
            added += store.add(tmp, record) ? 1 : 0;
        }
    }
    return added;
}

std::vector<QTreeWidgetItem*> seriesRows(const StudyBrowser& browser) {
    std::vector<QTreeWidgetItem*> rows;
    for (QTreeWidgetItemIterator it(browser.tree()); *it != nullptr; ++it) {
        if (!(*it)->data(0, StudyBrowser::kPathRole).toString().isEmpty()) {
            rows.push_back(*it);
        }
    }
    return rows;
}

ImageRGBA8 toRgba(const QImage& image) {
    const QImage rgba = image.convertToFormat(QImage::Format_RGBA8888);
    ImageRGBA8 out = ImageRGBA8::filled(rgba.width(), rgba.height(), 0);
    for (int y = 0; y < rgba.height(); ++y) {
        std::memcpy(out.pixels.data() + std::size_t(y) * std::size_t(rgba.width()) * 4,
                    rgba.constScanLine(y), std::size_t(rgba.width()) * 4);
    }
    return out;
}

} // namespace

class TestStudyBrowser : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        if (!fs::exists(kPhilips) || !fs::exists(kAbdomen)) {
            QSKIP("real DICOM data (../shared/data) is absent");
        }
    }

    void storeListsPatientsStudiesSeriesWithThumbnails() {
        QTemporaryDir dir;
        StudyStore store(dir.filePath("store").toStdString());
        const Catalog philips = scanPath(kPhilips / "S2010");
        const Catalog abdomen = scanPath(kAbdomen / "01.dcm");
        QCOMPARE(storeSeries(store, philips), 28);
        QCOMPARE(storeSeries(store, abdomen), 1);

        StudyBrowser browser;
        browser.resize(300, 600);
        browser.show();
        browser.setStoreFolder(dir.filePath("store"));
        QCOMPARE(browser.count(), 2);
        QCOMPARE(browser.tree()->topLevelItemCount(), 2); // two patients
        QTRY_COMPARE_WITH_TIMEOUT(browser.pending(), 0, 30000);

        const SeriesEntry& ct = philips.series.front();
        const QString folder =
            QString::fromStdString(store.seriesFolder(ct.studyUid, ct.seriesUid).string());
        QTreeWidgetItem* row = browser.findSeries(folder, QString::fromStdString(ct.seriesUid));
        QVERIFY(row != nullptr);
        QVERIFY2(row->text(0).contains(QString::fromStdString(ct.description)),
                 qPrintable(row->text(0)));
        QVERIFY2(row->text(0).contains("in store"), qPrintable(row->text(0)));
        const QString patient = row->parent()->parent()->text(0);
        QVERIFY2(patient.contains(QString::fromStdString(ct.patientId)), qPrintable(patient));
        for (QTreeWidgetItem* r : seriesRows(browser)) {
            QVERIFY2(!r->icon(0).isNull(), qPrintable(r->text(0) + ": no thumbnail"));
        }

        // The thumbnail is the middle image (14 of 28) of the stored series: the
        // same plane of the whole volume, loaded independently, looks the same.
        const Volume volume = loadSeries(ct);
        const VolumeGeometry& g = volume.geometry();
        SlicePlane plane;
        plane.u = glm::normalize(g.direction[0]);
        plane.v = glm::normalize(g.direction[1]);
        plane.centre = g.toPatient({(g.dims.x - 1) / 2.0, (g.dims.y - 1) / 2.0, 14.0});
        plane.width = plane.height = StudyBrowser::kThumbnailSize;
        plane.pixelSize = fitPixelSize(g, plane.u, plane.v, plane.width, plane.height);
        const std::vector<float> values = sampleImage(volume, plane);
        QImage want(plane.width, plane.height, QImage::Format_Grayscale8);
        const WindowLevel window = defaultWindow(volume);
        for (int y = 0; y < plane.height; ++y) {
            for (int x = 0; x < plane.width; ++x) {
                want.scanLine(y)[x] = windowToGrey(values[std::size_t(y * plane.width + x)],
                                                   window.center, window.width);
            }
        }
        const QImage got = row->icon(0).pixmap(StudyBrowser::kThumbnailSize).toImage();
        QCOMPARE(got.size(), want.size());
        const double p = psnr(toRgba(got), toRgba(want));
        qInfo("store thumbnail against slice 14 of the loaded volume: %.1f dB", p);
        QVERIFY2(p >= 40.0, qPrintable(QString("thumbnail %1 dB from the middle image").arg(p)));
        QVERIFY(got.convertToFormat(QImage::Format_Grayscale8).pixelColor(48, 48).value() > 0);

        // A click asks to open the stored series.
        QSignalSpy open(&browser, &StudyBrowser::openRequested);
        browser.tree()->scrollToItem(row);
        QTest::mouseClick(browser.tree()->viewport(), Qt::LeftButton, {},
                          browser.tree()->visualItemRect(row).center());
        QCOMPARE(open.count(), 1);
        QCOMPARE(open.at(0).at(0).toString(), folder);
        QCOMPARE(open.at(0).at(1).toString(), QString::fromStdString(ct.seriesUid));

        // A refresh after more arrives adds it without duplicating the rest.
        const Catalog thick = scanPath(kPhilips / "S2020");
        QVERIFY(storeSeries(store, thick) == 140);
        browser.refreshStore();
        QCOMPARE(browser.count(), 3);
    }

    void folderListsEverySeriesAndMarksLocalizers() {
        StudyBrowser browser;
        browser.addFolder(QString::fromStdString(kPhilips.string()));
        QTRY_COMPARE_WITH_TIMEOUT(browser.pending(), 0, 60000);
        QCOMPARE(browser.tree()->topLevelItemCount(), 1); // one phantom
        const std::vector<QTreeWidgetItem*> rows = seriesRows(browser);
        QCOMPARE(int(rows.size()), 3); // 5 mm, 1 mm and the localizer
        int localizers = 0;
        for (QTreeWidgetItem* r : rows) {
            localizers += r->text(0).contains("localizer") ? 1 : 0;
            QVERIFY2(!r->icon(0).isNull(), qPrintable(r->text(0) + ": no thumbnail"));
            // Not a black square: the middle image shows the phantom.
            const QImage t = r->icon(0).pixmap(StudyBrowser::kThumbnailSize).toImage();
            int lit = 0;
            for (int y = 0; y < t.height(); ++y) {
                for (int x = 0; x < t.width(); ++x) {
                    lit += qGray(t.pixel(x, y)) > 40 ? 1 : 0;
                }
            }
            QVERIFY2(lit > t.width() * t.height() / 20, qPrintable(r->text(0)));
        }
        QCOMPARE(localizers, 1);
    }

    void unreadableFolderSaysSo() {
        StudyBrowser browser;
        browser.addFolder(QStringLiteral("/nonexistent/lucent-study"));
        QTRY_COMPARE_WITH_TIMEOUT(browser.pending(), 0, 10000);
        QCOMPARE(browser.count(), 0);
        const QLabel* status = browser.findChild<QLabel*>();
        QVERIFY(status != nullptr);
        QVERIFY2(status->text().contains("/nonexistent/lucent-study"), qPrintable(status->text()));
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestStudyBrowser test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_study_browser.moc"
