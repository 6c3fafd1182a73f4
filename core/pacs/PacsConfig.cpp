#include "core/pacs/PacsConfig.h"

#include <QDir>
#include <QSettings>
#include <QUrl>

namespace lucent {

QString methodKey(RetrievalMethod m) {
    switch (m) {
    case RetrievalMethod::CMove:
        return QStringLiteral("cmove");
    case RetrievalMethod::Wado:
        return QStringLiteral("wado");
    case RetrievalMethod::CGet:
        break;
    }
    return QStringLiteral("cget");
}

RetrievalMethod methodFromKey(const QString& key) {
    if (key == QLatin1String("cmove")) {
        return RetrievalMethod::CMove;
    }
    return key == QLatin1String("wado") ? RetrievalMethod::Wado : RetrievalMethod::CGet;
}

QString PacsNodeConfig::validate() const {
    const QString who = name.isEmpty() ? QStringLiteral("PACS node") : "PACS node '" + name + "'";
    if (name.trimmed().isEmpty()) {
        return who + ": Name is empty";
    }
    const bool dimse = !usesDicomWeb() || !aeTitle.isEmpty() || !host.isEmpty();
    if (dimse) {
        try {
            checkAeTitle(aeTitle.toStdString(), "AE title");
        } catch (const PacsError& e) {
            return who + ": " + QString::fromStdString(e.what());
        }
        if (host.trimmed().isEmpty() || host.contains(' ')) {
            return who + ": Host is empty or has spaces";
        }
        if (port < 1 || port > 65535) {
            return who + ": Port " + QString::number(port) + " is not in 1-65535";
        }
    }
    if (usesDicomWeb() || !dicomWebUrl.isEmpty()) {
        const QUrl url(dicomWebUrl);
        if (!url.isValid() || (url.scheme() != "http" && url.scheme() != "https") ||
            url.host().isEmpty()) {
            return who + ": DICOMweb URL '" + dicomWebUrl + "' is not an http:// or https:// URL" +
                   (usesDicomWeb() ? " (WADO-RS needs it)" : "");
        }
    }
    return {};
}

PacsNode PacsNodeConfig::node() const {
    return PacsNode{aeTitle.toStdString(), host.toStdString(), port};
}

DicomWebService PacsNodeConfig::dicomWeb() const {
    DicomWebService s;
    s.baseUrl = dicomWebUrl.toStdString();
    while (!s.baseUrl.empty() && s.baseUrl.back() == '/') {
        s.baseUrl.pop_back();
    }
    return s;
}

QString PacsConfig::defaultStoreFolder() {
    return QDir::homePath() + QStringLiteral("/.local/share/lucent/store");
}

PacsConfig PacsConfig::load(QSettings& s) {
    PacsConfig c;
    s.beginGroup(QStringLiteral("pacs"));
    c.callingAeTitle = s.value(QStringLiteral("aeTitle"), c.callingAeTitle).toString();
    c.storagePort = s.value(QStringLiteral("storagePort"), c.storagePort).toInt();
    c.storeFolder = s.value(QStringLiteral("storeFolder"), defaultStoreFolder()).toString();
    c.timeoutSeconds = s.value(QStringLiteral("timeoutSeconds"), c.timeoutSeconds).toInt();
    const int n = s.beginReadArray(QStringLiteral("nodes"));
    for (int i = 0; i < n; ++i) {
        s.setArrayIndex(i);
        PacsNodeConfig node;
        node.name = s.value(QStringLiteral("name")).toString();
        node.aeTitle = s.value(QStringLiteral("aeTitle")).toString();
        node.host = s.value(QStringLiteral("host")).toString();
        node.port = s.value(QStringLiteral("port"), 104).toInt();
        node.method = methodFromKey(s.value(QStringLiteral("method")).toString());
        node.dicomWebUrl = s.value(QStringLiteral("dicomWebUrl")).toString();
        c.nodes << node;
    }
    s.endArray();
    s.endGroup();
    return c;
}

void PacsConfig::save(QSettings& s) const {
    s.beginGroup(QStringLiteral("pacs"));
    s.setValue(QStringLiteral("aeTitle"), callingAeTitle);
    s.setValue(QStringLiteral("storagePort"), storagePort);
    s.setValue(QStringLiteral("storeFolder"), storeFolder);
    s.setValue(QStringLiteral("timeoutSeconds"), timeoutSeconds);
    s.remove(QStringLiteral("nodes"));
    s.beginWriteArray(QStringLiteral("nodes"), static_cast<int>(nodes.size()));
    for (int i = 0; i < nodes.size(); ++i) {
        s.setArrayIndex(i);
        const PacsNodeConfig& node = nodes[i];
        s.setValue(QStringLiteral("name"), node.name);
        s.setValue(QStringLiteral("aeTitle"), node.aeTitle);
        s.setValue(QStringLiteral("host"), node.host);
        s.setValue(QStringLiteral("port"), node.port);
        s.setValue(QStringLiteral("method"), methodKey(node.method));
        s.setValue(QStringLiteral("dicomWebUrl"), node.dicomWebUrl);
    }
    s.endArray();
    s.endGroup();
    s.sync();
}

QString PacsConfig::validate() const {
    try {
        checkAeTitle(callingAeTitle.toStdString(), "Lucent's AE title");
    } catch (const PacsError& e) {
        return QString::fromStdString(e.what());
    }
    if (storagePort < 1 || storagePort > 65535) {
        return "Storage SCP port " + QString::number(storagePort) + " is not in 1-65535";
    }
    if (storeFolder.trimmed().isEmpty()) {
        return QStringLiteral("Store folder is empty");
    }
    if (timeoutSeconds < 1) {
        return QStringLiteral("Timeout must be at least 1 s");
    }
    for (const PacsNodeConfig& node : nodes) {
        if (const QString e = node.validate(); !e.isEmpty()) {
            return e;
        }
    }
    return {};
}

PacsSettings PacsConfig::dimse() const {
    PacsSettings s;
    s.callingAeTitle = callingAeTitle.toStdString();
    s.connectTimeoutSeconds = std::min(timeoutSeconds, 10);
    s.responseTimeoutSeconds = timeoutSeconds;
    return s;
}

} // namespace lucent
