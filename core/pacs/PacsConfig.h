#pragma once
// The PACS nodes and Lucent's own DICOM identity, as the settings keep them
// (QSettings), and their translation into the PACS library's types.

#include <QList>
#include <QString>

#include "core/pacs/DicomWebClient.h"
#include "core/pacs/PacsNode.h"

class QSettings;

namespace lucent {

enum class RetrievalMethod { CGet, CMove, Wado };
QString methodKey(RetrievalMethod m);              // "cget", "cmove", "wado"
RetrievalMethod methodFromKey(const QString& key); // unknown keys: C-GET

struct PacsNodeConfig {
    QString name; // what the user calls it
    QString aeTitle;
    QString host;
    int port = 104;
    RetrievalMethod method = RetrievalMethod::CGet;
    QString dicomWebUrl; // needed for WADO-RS; QIDO-RS is used for queries then

    // An empty string when usable, else a message naming the field that is wrong.
    QString validate() const;
    PacsNode node() const;
    DicomWebService dicomWeb() const;
    bool usesDicomWeb() const { return method == RetrievalMethod::Wado; }
};

struct PacsConfig {
    QList<PacsNodeConfig> nodes;
    QString callingAeTitle = QStringLiteral("LUCENT"); // our AE title
    int storagePort = 11112;                           // our storage SCP (C-MOVE destination)
    QString storeFolder;                               // the local study store
    int timeoutSeconds = 30;

    static QString defaultStoreFolder(); // ~/.local/share/lucent/store, as the CLI's
    static PacsConfig load(QSettings& settings);
    void save(QSettings& settings) const;
    // An empty string when usable, else a message naming the field (and node) that is wrong.
    QString validate() const;
    PacsSettings dimse() const;
};

} // namespace lucent
