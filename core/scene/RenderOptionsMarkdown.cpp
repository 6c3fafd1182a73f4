// The render options as a Markdown table (docs/options.md).
#include "core/scene/RenderOptions.h"

#include "core/scene/RenderOptions_p.h"

namespace lucent {

using detail::choiceText;
using detail::rangeText;
using detail::table;

std::string renderOptionsMarkdown() {
    std::string md = "| option | command line | wire | kind | range or choices | default | "
                     "what it does |\n|---|---|---|---|---|---|---|\n";
    for (const RenderOption& o : table()) {
        std::string cli = o.cliFlag.empty() ? "" : "`--" + std::string(o.cliFlag);
        if (!o.cliFlag.empty()) {
            cli += o.cliSets.empty() ? " " + std::string(o.valueName) + "`"
                                     : "` (sets " + std::string(o.cliSets) + ")";
        }
        const std::string wire = o.wireMessage.empty() ? ""
                                                       : "`" + std::string(o.wireMessage) + "." +
                                                             std::string(o.wireKey) + "`";
        std::string kind, range;
        switch (o.kind) {
        case OptionKind::Number:
            kind = "number";
            range = rangeText(o);
            break;
        case OptionKind::Integer:
            kind = "integer";
            range = rangeText(o);
            break;
        case OptionKind::Choice:
            kind = "choice";
            range = choiceText(o.choices);
            break;
        case OptionKind::Switch:
            kind = "switch";
            range = "true, false";
            break;
        case OptionKind::Size:
            kind = "WxH";
            range = "1 to " + std::to_string(kMaxImageSide) + " per side";
            break;
        case OptionKind::Box:
            kind = "box";
            range = "X0,Y0,Z0,X1,Y1,Z1 (voxels, X0 <= X1 ...) or all";
            break;
        case OptionKind::Window:
            kind = "window";
            range = "C,W (width above 0) or auto";
            break;
        }
        md += "| `" + std::string(o.name) + "` | " + cli + " | " + wire + " | " + kind + " | " +
              range + " | " + renderOptionDefault(o) + " | " + std::string(o.help) + " |\n";
    }
    return md;
}

} // namespace lucent
