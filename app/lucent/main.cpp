// lucent [PATH] [--series UID]: the workstation. Without PATH it opens the demo CT.
#include <QApplication>
#include <QCommandLineParser>
#include <QFileInfo>
#include <QMessageBox>
#include <QSurfaceFormat>
#include <QTimer>

#include "ui/app/MainWindow.h"
#include "ui/volume/VolumeView.h"

namespace {
const QString kDemo = QStringLiteral("/usr/share/doc/invesalius-examples/examples/Cranium.inv3");
}

int main(int argc, char** argv) {
    // Before the application: every GL context is then 4.3+ core (the 3D view's renderer needs it).
    QSurfaceFormat::setDefaultFormat(lucent::VolumeView::surfaceFormat());
    QApplication app(argc, argv);
    // The window's settings (layout, last folder, geometry, docks): ~/.config/lucent/Lucent.conf
    QApplication::setOrganizationName(QStringLiteral("lucent"));
    QApplication::setApplicationName(QStringLiteral("Lucent"));
    QApplication::setApplicationVersion(QStringLiteral(LUCENT_VERSION));

    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral("Lucent CT/MR workstation"));
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addPositionalArgument(
        QStringLiteral("path"),
        QStringLiteral("DICOM folder, DICOM file, DICOMDIR, .mhd, .nii(.gz) or .inv3 to open "
                       "(default: the InVesalius demo CT)"),
        QStringLiteral("[PATH]"));
    const QCommandLineOption series(QStringLiteral("series"),
                                    QStringLiteral("Open the series with this UID or id."),
                                    QStringLiteral("UID"));
    parser.addOption(series);
    const QCommandLineOption study(
        QStringLiteral("study"),
        QStringLiteral("Open PATH as a study: its hanging protocol in the viewport grid, with the "
                       "patient's prior fetched from PACS when the protocol asks for one."));
    parser.addOption(study);
    parser.process(app);
    const QStringList args = parser.positionalArguments();
    if (args.size() > 1) {
        parser.showHelp(2);
    }

    lucent::MainWindow window;
    window.show();

    QString path = args.value(0);
    if (path.isEmpty()) {
        if (QFileInfo::exists(kDemo)) {
            path = kDemo;
        } else {
            QMessageBox::information(&window, QStringLiteral("Lucent"),
                                     QStringLiteral("The demo CT %1 is not installed (Debian "
                                                    "package invesalius-examples). Use File > "
                                                    "Open to open a study.")
                                         .arg(kDemo));
        }
    }
    if (!path.isEmpty()) {
        const QString uid = parser.value(series);
        const bool asStudy = parser.isSet(study);
        QTimer::singleShot(0, &window, [&window, path, uid, asStudy] {
            if (asStudy) {
                window.openStudy(path);
            } else {
                window.openPath(path, uid);
            }
        });
    }
    return QApplication::exec();
}
