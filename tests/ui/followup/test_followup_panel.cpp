// The follow-up panel on two real CT studies of one patient in a real study store
// (tests/core/followup/TwoStudies.h): the table's cells, a click on a lesion going to it
// in both studies, the CSV export; and marking in the measurement list ("Same lesion as",
// "Target lesion"), saved by MeasurementAutosave and shown by the panel after its refresh,
// undone the same way. Offscreen.
#include <QApplication>
#include <QElapsedTimer>
#include <QFile>
#include <QLabel>
#include <QMenu>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>

#include "core/followup/FollowUpText.h"
#include "tests/core/followup/TwoStudies.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/followup/FollowUpPanel.h"
#include "ui/mpr/MeasurementAutosave.h"
#include "ui/mpr/MeasurementList.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SeriesMeasurements.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

QAction* actionNamed(QMenu& menu, const char* name) {
    return menu.findChild<QAction*>(QString::fromLatin1(name));
}

std::uint64_t idLabelled(const SeriesMeasurements& s, const std::string& label) {
    for (const Measurement& m : s.measurements()) {
        if (m.label == label) {
            return m.id;
        }
    }
    return 0;
}

} // namespace

class TestFollowUpPanel : public QObject {
    Q_OBJECT

    QTemporaryDir dir_;
    test::TwoStudies studies_;
    QString storeDir() const { return dir_.path() + "/store"; }

    // The text of the panel's cell of a lesion (by name) at timepoint t.
    static QString lesionCell(const FollowUpPanel& panel, const std::string& name, int t) {
        for (std::size_t r = 0; r < panel.table().lesions.size(); ++r) {
            if (panel.table().lesions[r].name == name) {
                return panel.grid()->item(static_cast<int>(r), 2 + t)->text();
            }
        }
        return QStringLiteral("(no row)");
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2020");
        StudyStore store(storeDir().toStdString());
        test::makeTwoStudies(dir_.path().toStdString(), store, studies_);
    }

    void tableClickAndExport() {
        FollowUpPanel panel;
        panel.resize(800, 400);
        panel.show();
        panel.setStoreFolder(storeDir());
        QElapsedTimer clock;
        clock.start();
        panel.showPatient(test::kPatient);
        const qint64 first = clock.restart();
        panel.refresh(); // as after a save: the image headers were read once
        qInfo("follow-up refresh: first %lld ms, again %lld ms", first, clock.elapsed());
        QTableWidget* grid = panel.grid();
        QCOMPARE(grid->columnCount(), 4);
        QCOMPARE(grid->rowCount(), 4 + 5); // the lesions, then sum, changes, response, reason
        QCOMPARE(grid->horizontalHeaderItem(2)->text(), QString("2014-02-06"));
        QCOMPARE(grid->horizontalHeaderItem(3)->text(), QString("2015-02-06"));
        QCOMPARE(grid->item(0, 0)->text(), QString("Liver 1"));
        const double liver = bidirectionalLongAxisMm(studies_.priorMeasurements[0]);
        QCOMPARE(grid->item(0, 2)->text(), QString::number(liver, 'f', 1));
        QCOMPARE(grid->item(1, 1)->text(), QString("Target, lymph node"));
        QCOMPARE(grid->item(4, 0)->text(), QString("Sum of diameters (mm)"));
        QCOMPARE(grid->item(7, 3)->text(), QString("PD"));
        QVERIFY(panel.statusLabel()->text().contains("2 timepoint(s), 4 tracked lesion(s)"));

        QSignalSpy activated(&panel, &FollowUpPanel::lesionActivated);
        const QRect cell = grid->visualItemRect(grid->item(0, 3));
        QTest::mouseClick(grid->viewport(), Qt::LeftButton, {}, cell.center());
        QCOMPARE(activated.count(), 1);
        QCOMPARE(activated[0][0].toString(), QString::fromStdString(studies_.liver));
        const auto where = activated[0][1].value<std::vector<LesionLocation>>();
        QCOMPARE(where.size(), std::size_t(2));
        QCOMPARE(where[0].seriesUid, studies_.prior.seriesUid);
        QCOMPARE(where[1].seriesUid, studies_.current.seriesUid);
        QVERIFY(glm::distance(where[0].centre, test::centreOf(studies_.priorMeasurements[0])) <
                1e-6);
        QVERIFY(glm::distance(where[1].centre, test::centreOf(studies_.currentMeasurements[0])) <
                1e-6);
        // A summary row goes nowhere.
        QTest::mouseClick(grid->viewport(), Qt::LeftButton, {},
                          grid->visualItemRect(grid->item(4, 3)).center());
        QCOMPARE(activated.count(), 1);

        const QString csv = dir_.path() + "/table.csv";
        QVERIFY(panel.exportCsv(csv));
        QFile written(csv);
        QVERIFY(written.open(QIODevice::ReadOnly));
        QCOMPARE(written.readAll().toStdString(), followUpCsv(panel.table()));
        QString error;
        const QString nowhere = dir_.path() + "/missing/table.csv";
        QVERIFY(!panel.exportCsv(nowhere, &error));
        QVERIFY2(error.contains(nowhere), qPrintable(error));
    }

    // Marks made in the list of the follow-up series, saved as the reader works, reach the
    // panel through MeasurementAutosave::saved -> FollowUpPanel::refresh.
    void markingInTheList() {
        FollowUpPanel panel;
        panel.setStoreFolder(storeDir());
        panel.showPatient(test::kPatient);
        MeasurementAutosave autosave(storeDir());
        connect(&autosave, &MeasurementAutosave::saved, &panel, &FollowUpPanel::refresh);
        auto volume = std::make_shared<Volume>();
        volume->seriesUid = studies_.current.seriesUid;
        SeriesMeasurements measurements(volume);
        autosave.attach(&measurements);
        QCOMPARE(measurements.measurements().size(), std::size_t(5));
        MprCursor cursor;
        MeasurementList list(&cursor);
        list.setMeasurements(&measurements);
        list.setLesionChoices(
            [&panel](const std::string& series) { return panel.earlierLesions(series); });

        const std::uint64_t plain = idLabelled(measurements, "");
        QVERIFY(plain != 0);
        {
            // Every earlier lesion is measured in this series already: nothing to offer.
            std::unique_ptr<QMenu> menu(list.contextMenu(plain));
            QVERIFY(!menu->findChild<QMenu*>("lesionSameAs")->isEnabled());
        }
        QVERIFY(measurements.remove(idLabelled(measurements, "Liver 1")));
        {
            std::unique_ptr<QMenu> menu(list.contextMenu(plain));
            QMenu* same = menu->findChild<QMenu*>("lesionSameAs");
            QVERIFY(same->isEnabled());
            QCOMPARE(same->actions().size(), 1);
            QVERIFY(same->actions()[0]->text().startsWith("Liver 1 (target, 2014-02-06)"));
            same->actions()[0]->trigger();
        }
        const Measurement* marked = measurements.find(plain);
        QCOMPARE(marked->label, std::string("Liver 1"));
        QCOMPARE(marked->lesion.trackingUid, studies_.liver);
        QCOMPARE(marked->lesion.role, LesionRole::Target);
        QCOMPARE(list.table()->item(4 - 1, MeasurementList::Lesion)->text(), QString("Target"));
        autosave.flush();
        const double length = measurementLengthMm(*marked);
        QCOMPARE(lesionCell(panel, "Liver 1", 1), QString::number(length, 'f', 1));

        // Undone: the liver is not measured at follow-up any more.
        QVERIFY(measurements.undo());
        autosave.flush();
        QCOMPARE(lesionCell(panel, "Liver 1", 1), QString());

        // A target lesion of its own: a new lesion, named, with a tracking UID.
        {
            std::unique_ptr<QMenu> menu(list.contextMenu(plain));
            QVERIFY(!actionNamed(*menu, "lesionTarget")->isChecked());
            actionNamed(*menu, "lesionTarget")->trigger();
        }
        marked = measurements.find(plain);
        QCOMPARE(marked->lesion.role, LesionRole::Target);
        QVERIFY(!marked->lesion.trackingUid.empty());
        QVERIFY(!marked->label.empty());
        {
            std::unique_ptr<QMenu> menu(list.contextMenu(plain));
            QVERIFY(actionNamed(*menu, "lesionTarget")->isChecked());
            actionNamed(*menu, "lesionLymphNode")->trigger();
        }
        QVERIFY(measurements.find(plain)->lesion.lymphNode);
        autosave.flush();
        const auto& reasons = panel.table().timepoints.at(1).reasons;
        QVERIFY(std::find(reasons.begin(), reasons.end(), "new lesion: " + marked->label) !=
                reasons.end());
        QCOMPARE(lesionCell(panel, marked->label, 1), QString::number(length, 'f', 1));
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestFollowUpPanel test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_followup_panel.moc"
