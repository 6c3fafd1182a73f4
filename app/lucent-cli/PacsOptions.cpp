#include "PacsOptions.h"

#include <algorithm>
#include <stdexcept>

namespace lucent::cli {

void addNodeOptions(QCommandLineParser& p) {
    p.addOptions({
        {"pacs", "The PACS.", "AET@HOST:PORT"},
        {"aet", "Our AE title (default LUCENT).", "OUR_AET", "LUCENT"},
        {"timeout", "Seconds to wait for a connection or a response (default 10).", "S", "10"},
    });
    p.addHelpOption();
}

std::pair<PacsNode, PacsSettings> nodeFrom(const QCommandLineParser& p) {
    if (!p.isSet("pacs")) {
        throw std::invalid_argument("--pacs AET@HOST:PORT is required");
    }
    bool ok = false;
    const int timeout = p.value("timeout").toInt(&ok);
    if (!ok || timeout < 1 || timeout > 3600) {
        throw std::invalid_argument("--timeout must be a number of seconds from 1 to 3600");
    }
    PacsSettings s;
    s.callingAeTitle = p.value("aet").toStdString();
    s.connectTimeoutSeconds = timeout;
    s.responseTimeoutSeconds = std::max(timeout, 30);
    try {
        checkAeTitle(s.callingAeTitle, "--aet");
        return {PacsNode::parse(p.value("pacs").toStdString()), s};
    } catch (const PacsError& e) {
        throw std::invalid_argument(e.what()); // a malformed option is a usage error
    }
}

DicomWebService serviceFrom(const QCommandLineParser& p, const QString& option) {
    const QString url = p.value(option);
    if (!url.startsWith("http://") && !url.startsWith("https://")) {
        throw std::invalid_argument("--" + option.toStdString() +
                                    " must be an http:// or https:// DICOMweb base URL");
    }
    DicomWebService s;
    s.baseUrl = url.endsWith('/') ? url.chopped(1).toStdString() : url.toStdString();
    s.timeoutSeconds = std::max(p.value("timeout").toInt(), 1);
    return s;
}

} // namespace lucent::cli
