// lucent-cli options [--markdown]: the render options table (core/scene/RenderOptions.h),
// as text or as the Markdown of docs/options.md.
#include <QCommandLineParser>
#include <QTextStream>

#include "CliCommand.h"
#include "core/scene/RenderOptions.h"

namespace lucent::cli {

int runOptions(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription("Lists every render option: name, flag, wire key, range, "
                                     "default.");
    parser.addOption({"markdown", "Print the table of docs/options.md."});
    parser.addHelpOption();
    QTextStream err(stderr), out(stdout);
    if (!parser.parse(args) || !parser.positionalArguments().isEmpty()) {
        err << "lucent-cli options: "
            << (parser.errorText().isEmpty() ? "takes no arguments" : parser.errorText()) << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        out << parser.helpText();
        return kOk;
    }
    if (parser.isSet("markdown")) {
        out << QString::fromStdString(renderOptionsMarkdown());
        return kOk;
    }
    for (const RenderOption& o : renderOptions()) {
        out << QString::fromUtf8(o.name.data(), qsizetype(o.name.size())) << " = "
            << QString::fromStdString(renderOptionDefault(o)) << "\n";
    }
    return kOk;
}

} // namespace lucent::cli
