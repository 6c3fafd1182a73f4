#include "RenderFlags.h"

#include <stdexcept>

#include "CliCommand.h"
#include "core/scene/DefaultPreset.h"
#include "core/scene/RenderOptions.h"

namespace lucent::cli {
namespace {

QString text(std::string_view s) {
    return QString::fromUtf8(s.data(), qsizetype(s.size()));
}

} // namespace

void addRenderFlags(QCommandLineParser& parser) {
    for (const RenderOption& o : renderOptions()) {
        if (o.cliFlag.empty()) {
            continue;
        }
        QString help = text(o.help);
        if (o.kind == OptionKind::Choice) {
            QStringList choices;
            for (const std::string_view c : o.choices) {
                choices << text(c);
            }
            help += " One of " + choices.join(", ") + ".";
        }
        if (o.cliSets.empty()) {
            help += " Default " + QString::fromStdString(renderOptionDefault(o)) + ".";
            parser.addOption({text(o.cliFlag), help, text(o.valueName)});
        } else {
            help += " (Sets " + text(o.name) + " to " + text(o.cliSets) + "; default " +
                    QString::fromStdString(renderOptionDefault(o)) + ".)";
            parser.addOption({text(o.cliFlag), help});
        }
    }
}

void applyRenderFlags(const QCommandLineParser& parser, RenderDescription& description) {
    for (const RenderOption& o : renderOptions()) {
        if (o.cliFlag.empty() || !parser.isSet(text(o.cliFlag))) {
            continue;
        }
        const std::string value = o.cliSets.empty() ? parser.value(text(o.cliFlag)).toStdString()
                                                    : std::string(o.cliSets);
        try {
            applyRenderOption(description, o, value);
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument("--" + std::string(o.cliFlag) + ": " + e.what());
        }
    }
}

bool anyRenderFlagSet(const QCommandLineParser& parser) {
    for (const RenderOption& o : renderOptions()) {
        if (!o.cliFlag.empty() && parser.isSet(text(o.cliFlag))) {
            return true;
        }
    }
    return false;
}

// The table's options, then the transfer function (whose preset may depend on
// the mode), then the options again, since shading lives in the transfer function.
RenderDescription describeFromFlags(const QCommandLineParser& p, const Volume& volume) {
    RenderDescription d;
    d.volume = &volume;
    applyRenderFlags(p, d);
    if (p.isSet("preset") && p.isSet("tf")) {
        throw UsageError("--preset and --tf exclude each other");
    }
    if (p.isSet("tf")) {
        d.transferFunction = readTransferFunction(p.value("tf").toStdString());
    } else {
        d.transferFunction =
            loadPreset(p.isSet("preset") ? p.value("preset").toStdString()
                                         : defaultPresetName(volume.modality, d.mode));
    }
    applyRenderFlags(p, d);
    return d;
}

} // namespace lucent::cli
