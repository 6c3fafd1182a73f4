#include "OverlayFlags.h"

#include <stdexcept>

#include "CliCommand.h"
#include "core/fusion/OverlayResampler.h"
#include "core/fusion/TransformFile.h"

namespace lucent::cli {

void addOverlayFlags(QCommandLineParser& parser) {
    parser.addOptions({
        {"overlay",
         "A second series drawn over this one (fusion), resampled onto its grid through "
         "--transform.",
         "PATH"},
        {"overlay-series", "The overlay's series (id or UID; default the largest volume).", "UID"},
        {"transform",
         "transform.json of lucent-cli register (base = fixed, overlay = moving): \"matrix\", "
         "4 rows mapping base LPS mm to overlay LPS mm. Default: the identity, when both "
         "series share a Frame of Reference.",
         "FILE.json"},
    });
}

std::string renderOverlayUsage(const QCommandLineParser& parser) {
    if (!parser.isSet("overlay")) {
        for (const char* flag : {"overlay-map", "overlay-window", "overlay-opacity"}) {
            if (parser.isSet(flag)) {
                return std::string("--") + flag + " needs --overlay PATH";
            }
        }
        return {};
    }
    if (parser.isSet("distributed")) {
        return "--overlay is drawn by the cpu and gl backends only, not --distributed";
    }
    const QString backend = parser.value("backend");
    if (backend.startsWith("ws://") || backend.startsWith("wss://")) {
        return "--overlay is drawn by the cpu and gl backends only, not a render server";
    }
    return {};
}

glm::dmat4 baseToOverlay(const QCommandLineParser& parser, const Volume& base,
                         const Volume& overlay) {
    if (parser.isSet("transform")) {
        return readTransformFile(parser.value("transform").toStdString());
    }
    const std::string& a = base.frameOfReferenceUid;
    const std::string& b = overlay.frameOfReferenceUid;
    if (a.empty() || a != b) {
        throw std::runtime_error("--transform is needed: the base's Frame of Reference (" +
                                 (a.empty() ? "none" : a) + ") is not the overlay's (" +
                                 (b.empty() ? "none" : b) +
                                 "); lucent-cli register BASE OVERLAY -o transform.json makes one");
    }
    return glm::dmat4(1.0);
}

std::optional<Volume> loadOverlay(const QCommandLineParser& parser, const Volume& base, float fill,
                                  const LoadControl& control) {
    if (!parser.isSet("overlay")) {
        for (const char* flag : {"overlay-series", "transform"}) {
            if (parser.isSet(flag)) {
                throw UsageError(std::string("--") + flag + " needs --overlay PATH");
            }
        }
        return std::nullopt;
    }
    const Volume overlay = loadPath(parser.value("overlay").toStdString(),
                                    parser.value("overlay-series").toStdString(), control);
    const glm::dmat4 transform = baseToOverlay(parser, base, overlay);
    return resampleOverlay(overlay, base.geometry(), transform, fill);
}

} // namespace lucent::cli
