// Memory of the viewport grid with 2, 4 and 8 real 140-slice CT series shown (each a
// copy of the phantom as another study), and what the library drops when series
// not shown exceed its budget. Prints the resident set after each step, what one
// series costs beside its voxels, and the budget rule at work. Label perf.
#include <QApplication>
#include <QFile>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include <cstdio>

#include "tests/support/OffscreenPlatform.h"
#include "tests/support/PriorStudy.h"
#include "tests/support/RealData.h"
#include "ui/viewports/SeriesLibrary.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportWorkspace.h"

using namespace lucent;

namespace {

const char* kCt = "dcm_qa_ct/Philips_S21570/S2020";

double residentMiB() {
    QFile status(QStringLiteral("/proc/self/status"));
    if (!status.open(QIODevice::ReadOnly)) {
        return 0.0;
    }
    for (const QByteArray& line : status.readAll().split('\n')) {
        if (line.startsWith("VmRSS:")) {
            return line.mid(6).trimmed().split(' ').front().toDouble() / 1024.0;
        }
    }
    return 0.0;
}

} // namespace

class BenchViewportMemory : public QObject {
    Q_OBJECT

private slots:
    void seriesOpen() {
        REQUIRE_DATA(kCt);
        QTemporaryDir dir;
        QStringList folders;
        for (int n = 0; n < 8; ++n) {
            const QString folder = dir.filePath(QStringLiteral("study%1").arg(n));
            test::writePriorStudy(
                test::kRealData / kCt, folder.toStdString(),
                QStringLiteral("2020%1").arg(101 + n, 4, 10, QLatin1Char('0')).toStdString());
            folders << folder;
        }
        ViewportWorkspace workspace;
        workspace.resize(1600, 800);
        workspace.show();
        workspace.grid()->setShape(regularGridShape(2, 4));
        const double base = residentMiB();
        std::printf("grid 2x4, nothing shown: RSS %.0f MiB\n", base);
        int shown = 0;
        for (const int upTo : {2, 4, 8}) {
            for (; shown < upTo; ++shown) {
                QSignalSpy ready(&workspace, &ViewportWorkspace::seriesShown);
                workspace.showSeries(workspace.grid()->viewport(shown), folders[shown], {},
                                     ViewportView::Axial);
                QVERIFY(ready.wait(120000));
            }
            workspace.repaint();
            QCoreApplication::processEvents();
            const double rss = residentMiB();
            const double voxels = static_cast<double>(workspace.library()->bytes()) / (1 << 20);
            std::printf(
                "%d series shown: RSS %.0f MiB (+%.0f over the empty grid), voxels %.0f MiB, "
                "%.1f MiB per series of which %.1f beside its voxels\n",
                upTo, rss, rss - base, voxels, (rss - base) / upTo, (rss - base - voxels) / upTo);
        }
        // Series not shown go once all held exceed the budget, oldest first.
        const std::size_t one = workspace.library()->bytes() / 8;
        workspace.setMemoryBudget(5 * one);
        workspace.grid()->setShape(*gridShape(QStringLiteral("1x2")));
        QSignalSpy ready(&workspace, &ViewportWorkspace::seriesShown);
        workspace.showSeries(workspace.grid()->viewport(0), folders[0], {}, ViewportView::Axial);
        QVERIFY(ready.wait(120000));
        QCoreApplication::processEvents();
        std::printf("1x2 shown with a budget of 5 series: %d series kept, RSS %.0f MiB\n",
                    workspace.library()->count(), residentMiB());
        QVERIFY(workspace.library()->count() <= 5);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    BenchViewportMemory bench;
    return QTest::qExec(&bench, argc, argv);
}

#include "bench_viewport_memory.moc"
