#include "RenderFlags.h"

#include <stdexcept>

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

} // namespace lucent::cli
