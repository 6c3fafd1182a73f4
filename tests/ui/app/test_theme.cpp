// The workstation's look: the dark reading-room palette (dark greys, soft text,
// every text/background pair readable), the light one, View > Theme switching and
// persisting the choice, and a screenshot of the dark main window on the demo CT
// with the PACS dock open, against a baseline (tests/ui/baselines). Offscreen.
#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QMenuBar>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QStyle>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>
#include <filesystem>

#include "tests/support/BaselineImage.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/app/MainWindow.h"
#include "ui/study/StudyBrowser.h"
#include "ui/theme/Theme.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;

namespace {

const QString kDemoCt = QStringLiteral("/usr/share/doc/invesalius-examples/examples/Cranium.inv3");

// WCAG 2 relative luminance and contrast ratio (1 to 21).
double luminance(const QColor& c) {
    const auto linear = [](double v) {
        return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    };
    return 0.2126 * linear(c.redF()) + 0.7152 * linear(c.greenF()) + 0.0722 * linear(c.blueF());
}

double contrast(const QColor& a, const QColor& b) {
    const double la = luminance(a), lb = luminance(b);
    return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}

QAction* themeAction(MainWindow& window, Theme theme) {
    for (QAction* action : window.menuBar()->findChildren<QAction*>()) {
        if (action->data().toString() == themeName(theme) && action->isCheckable()) {
            return action;
        }
    }
    return nullptr;
}

// The mean grey (0-255) of an image area.
double meanGrey(const QImage& image, const QRect& area) {
    double sum = 0.0;
    for (int y = area.top(); y <= area.bottom(); ++y) {
        for (int x = area.left(); x <= area.right(); ++x) {
            sum += qGray(image.pixel(x, y));
        }
    }
    return sum / (double(area.width()) * area.height());
}

} // namespace

class TestTheme : public QObject {
    Q_OBJECT
    QTemporaryDir settingsDir_;

private slots:
    void initTestCase() {
        QVERIFY(settingsDir_.isValid());
        QStandardPaths::setTestModeEnabled(true);
        QCoreApplication::setOrganizationName(QStringLiteral("lucent-test"));
        QCoreApplication::setApplicationName(QStringLiteral("test_theme"));
        QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settingsDir_.path());
    }
    void init() { QSettings().clear(); }

    void darkPaletteIsForAReadingRoom() {
        const QPalette p = themePalette(Theme::Dark);
        // Panels dark grey, not black; text light grey, not white.
        for (const auto role : {QPalette::Window, QPalette::Base, QPalette::Button}) {
            const int l = p.color(role).lightness();
            QVERIFY2(l >= 24 && l <= 72, qPrintable(QString("role %1: %2").arg(role).arg(l)));
        }
        for (const auto role : {QPalette::WindowText, QPalette::Text, QPalette::ButtonText}) {
            const int l = p.color(role).lightness();
            QVERIFY2(l >= 180 && l <= 225, qPrintable(QString("role %1: %2").arg(role).arg(l)));
        }
    }

    void everyThemeReads_data() {
        QTest::addColumn<int>("theme");
        QTest::newRow("dark") << int(Theme::Dark);
        QTest::newRow("light") << int(Theme::Light);
    }
    void everyThemeReads() {
        QFETCH(int, theme);
        const QPalette p = themePalette(Theme(theme));
        const auto check = [&](QPalette::ColorGroup group, QPalette::ColorRole fg,
                               QPalette::ColorRole bg, double least) {
            const double c = contrast(p.color(group, fg), p.color(group, bg));
            QVERIFY2(c >= least,
                     qPrintable(QString("roles %1 on %2 (group %3): contrast %4, at least %5")
                                    .arg(fg)
                                    .arg(bg)
                                    .arg(group)
                                    .arg(c)
                                    .arg(least)));
        };
        // AAA for the body text, AA for selections and tooltips, 3:1 for disabled text.
        check(QPalette::Active, QPalette::WindowText, QPalette::Window, 7.0);
        check(QPalette::Active, QPalette::Text, QPalette::Base, 7.0);
        check(QPalette::Active, QPalette::Text, QPalette::AlternateBase, 7.0);
        check(QPalette::Active, QPalette::ButtonText, QPalette::Button, 7.0);
        check(QPalette::Active, QPalette::HighlightedText, QPalette::Highlight, 4.5);
        check(QPalette::Active, QPalette::ToolTipText, QPalette::ToolTipBase, 4.5);
        check(QPalette::Disabled, QPalette::WindowText, QPalette::Window, 3.0);
        check(QPalette::Disabled, QPalette::ButtonText, QPalette::Button, 2.5);
        // Status texts read on the window and in lists.
        for (const StatusTone tone : {StatusTone::Error, StatusTone::Ok, StatusTone::Warning}) {
            const QColor c = statusColour(tone, p);
            QVERIFY2(contrast(c, p.color(QPalette::Window)) >= 4.5, qPrintable(c.name()));
            QVERIFY2(contrast(c, p.color(QPalette::Base)) >= 4.5, qPrintable(c.name()));
        }
    }

    void namesRoundTrip() {
        for (const Theme t : {Theme::Dark, Theme::Light}) {
            QCOMPARE(themeFromName(themeName(t)), std::optional<Theme>(t));
        }
        QCOMPARE(themeFromName(QStringLiteral("sepia")), std::nullopt);
    }

    void darkByDefaultAndTheChoicePersists() {
        {
            MainWindow window;
            QCOMPARE(currentTheme(), Theme::Dark);
            QCOMPARE(QApplication::style()->name().toLower(), QStringLiteral("fusion"));
            QCOMPARE(QApplication::palette().color(QPalette::Window),
                     themePalette(Theme::Dark).color(QPalette::Window));
            QCOMPARE(window.palette().color(QPalette::Window),
                     themePalette(Theme::Dark).color(QPalette::Window));
            QAction* light = themeAction(window, Theme::Light);
            QVERIFY(light != nullptr);
            QVERIFY(themeAction(window, Theme::Dark)->isChecked());
            light->trigger();
            QCOMPARE(currentTheme(), Theme::Light);
            QCOMPARE(window.palette().color(QPalette::Window),
                     themePalette(Theme::Light).color(QPalette::Window));
            QCOMPARE(QSettings().value(QStringLiteral("view/theme")).toString(),
                     QStringLiteral("light"));
        }
        // A later start comes up light; back to dark, and that is saved too.
        applyTheme(*qApp, Theme::Dark);
        MainWindow again;
        QCOMPARE(currentTheme(), Theme::Light);
        QCOMPARE(QApplication::palette().color(QPalette::Window),
                 themePalette(Theme::Light).color(QPalette::Window));
        themeAction(again, Theme::Dark)->trigger();
        QCOMPARE(savedTheme(), Theme::Dark);
    }

    void darkWindowOnTheDemoCtMatchesTheBaseline() {
        if (!QFileInfo::exists(kDemoCt)) {
            QSKIP("the demo CT (Debian package invesalius-examples) is not installed");
        }
        MainWindow window;
        QCOMPARE(currentTheme(), Theme::Dark);
        auto* pacsDock = window.findChild<QDockWidget*>(QStringLiteral("pacsDock"));
        QVERIFY(pacsDock != nullptr);
        pacsDock->show(); // the query panel, its fields and buttons, in the picture too
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        window.resize(1280, 800);
        QSignalSpy finished(&window, &MainWindow::loadFinished);
        window.openPath(kDemoCt);
        QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 60000);
        QVERIFY(finished.at(0).at(0).toBool());
        auto* studies = window.findChild<StudyBrowser*>();
        QVERIFY(studies != nullptr);
        QTRY_COMPARE_WITH_TIMEOUT(studies->pending(), 0, 60000);
        VolumeView* view = window.volumeView();
        QTRY_VERIFY_WITH_TIMEOUT(!view->lastFrame().empty() && view->lastFrameCurrent(), 60000);
        QImage actual = window.grab().toImage();
        for (int tries = 0; tries < 20; ++tries) {
            QTest::qWait(200);
            const QImage again = window.grab().toImage();
            if (again == actual) {
                break;
            }
            actual = again;
        }
        // The chrome is dark: the menu bar and the status bar.
        const QRect menu(window.menuBar()->geometry());
        QVERIFY2(meanGrey(actual, menu) < 90.0,
                 qPrintable(QString::number(meanGrey(actual, menu))));
        LUCENT_COMPARE_BASELINE(actual, QStringLiteral("main_window_dark_demo_ct"), 30.0, 0.95);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestTheme test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_theme.moc"
