#pragma once
// The options that name a PACS, shared by every pacs verb: --pacs, --aet,
// --timeout for DIMSE and --wado for DICOMweb.

#include <QCommandLineParser>

#include <utility>

#include "core/pacs/DicomWebClient.h"
#include "core/pacs/PacsNode.h"

namespace lucent::cli {

constexpr int kPacsFailure = 4;

void addNodeOptions(QCommandLineParser& p);
// The node and settings of --pacs, --aet and --timeout; std::invalid_argument when malformed.
std::pair<PacsNode, PacsSettings> nodeFrom(const QCommandLineParser& p);
// The DICOMweb service of the URL option `option` (--wado, --stow) and --timeout.
DicomWebService serviceFrom(const QCommandLineParser& p, const QString& option = "wado");

} // namespace lucent::cli
