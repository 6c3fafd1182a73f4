// lucent-cli export: DICOM instances copied to a folder or a ZIP file,
// optionally de-identified and with a DICOMDIR (core/exchange/DicomExport).
#include <QTextStream>

#include "CliCommand.h"
#include "TerminalProgress.h"
#include "core/exchange/DicomExport.h"

namespace lucent::cli {

int runExport(const QStringList& args) {
    QCommandLineParser p;
    p.setApplicationDescription(
        "Copies the DICOM instances under PATH (or of one series) to a new folder or ZIP file, "
        "as DICOM/STnnnn/SEnnnn/IMnnnnnn. The source is only read; a failure leaves nothing at "
        "OUT.");
    p.addOptions({
        {{"o", "output"}, "A new folder, or a new file ending in .zip.", "OUT"},
        {"series", "Export only the instances of this Series Instance UID.", "UID"},
        {"anonymize",
         "De-identify after DICOM PS3.15's Basic Profile: names, IDs, dates and free text "
         "removed, UIDs replaced consistently within the export, pixels untouched."},
        {"dicomdir", "Write a DICOMDIR that lists every file."},
    });
    p.addPositionalArgument("PATH", "A DICOM file or a folder (searched recursively).");
    p.addHelpOption();
    QTextStream err(stderr);
    if (!p.parse(args)) {
        err << "lucent-cli export: " << p.errorText() << "\n";
        return kUsage;
    }
    if (p.isSet("help")) {
        QTextStream(stdout) << p.helpText();
        return kOk;
    }
    if (p.positionalArguments().size() != 1 || !p.isSet("output")) {
        err << "lucent-cli export: give one PATH and -o OUT (a new folder or a .zip file)\n";
        return kUsage;
    }
    try {
        const QString path = p.positionalArguments()[0];
        std::vector<std::string> passedOver;
        const std::vector<InstanceHeader> instances =
            collectInstances(path.toStdString(), p.value("series").toStdString(), passedOver);
        if (instances.empty()) {
            err << "lucent-cli export: no DICOM instances in " << path
                << (p.isSet("series") ? " of series " + p.value("series") : QString()) << "\n";
            return kBadInput;
        }
        for (const std::string& why : passedOver) {
            err << "lucent-cli export: passed over " << QString::fromStdString(why) << "\n";
        }
        TerminalProgress progress;
        ExportOptions options;
        options.anonymize = p.isSet("anonymize");
        options.dicomdir = p.isSet("dicomdir");
        options.onProgress = [&](int done, int total) {
            if (progress.control().onProgress) {
                progress.control().onProgress({"exporting", std::size_t(done), std::size_t(total)});
            }
        };
        const ExportResult r = exportInstances(instances, p.value("output").toStdString(), options);
        progress.finish();
        QTextStream(stdout) << r.files << " instance(s) exported"
                            << (options.anonymize ? ", de-identified," : "") << " to "
                            << QString::fromStdString(r.output.string())
                            << (options.dicomdir ? " with a DICOMDIR" : "") << "\n";
        return kOk;
    } catch (const std::exception& e) {
        err << "lucent-cli export: " << e.what() << "\n";
        return kBadInput;
    }
}

} // namespace lucent::cli
