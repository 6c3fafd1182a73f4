// lucent-cli pacs send: instances from a file or folder to a PACS, by C-STORE
// (--pacs) or STOW-RS (--stow), with each instance's outcome.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTextStream>

#include "CliCommand.h"
#include "PacsOptions.h"
#include "core/pacs/InstanceSender.h"

namespace lucent::cli {
namespace {

void print(const SendResult& r, bool json, QTextStream& out) {
    if (json) {
        QJsonArray list;
        for (const SentInstance& s : r.instances) {
            list.append(QJsonObject{{"file", QString::fromStdString(s.file.string())},
                                    {"sop_instance_uid", QString::fromStdString(s.sopInstanceUid)},
                                    {"outcome", outcomeName(s.outcome)},
                                    {"message", QString::fromStdString(s.message)}});
        }
        out << QJsonDocument(list).toJson(QJsonDocument::Indented);
        return;
    }
    for (const SentInstance& s : r.instances) {
        if (s.outcome != SentInstance::Outcome::Stored) {
            out << QString::fromStdString(s.file.string()) << ": " << outcomeName(s.outcome)
                << (s.message.empty() ? "" : ": ") << QString::fromStdString(s.message) << "\n";
        }
    }
    using O = SentInstance::Outcome;
    out << r.count(O::Stored) + r.count(O::StoredWithWarning) << " of " << r.instances.size()
        << " instance(s) stored (" << r.count(O::StoredWithWarning) << " with a warning), "
        << r.count(O::Failed) << " failed, " << r.count(O::NotSent) << " not sent\n";
}

} // namespace

int runPacsSend(const QStringList& args) {
    QCommandLineParser p;
    p.setApplicationDescription(
        "Sends the DICOM instances of a file or folder to a PACS by C-STORE (--pacs) or "
        "STOW-RS (--stow), each in its own transfer syntax.");
    addNodeOptions(p);
    p.addOptions({
        {"stow", "DICOMweb base URL: send by STOW-RS to URL/studies instead of C-STORE.", "URL"},
        {"series", "Send only the instances of this Series Instance UID.", "UID"},
        {"json", "Each instance's outcome as JSON on stdout."},
    });
    p.addPositionalArgument("PATH", "A DICOM file or a folder (searched recursively).");
    QTextStream err(stderr);
    if (!p.parse(args)) {
        err << "lucent-cli pacs send: " << p.errorText() << "\n";
        return kUsage;
    }
    if (p.isSet("help")) {
        QTextStream(stdout) << p.helpText();
        return kOk;
    }
    try {
        if (p.positionalArguments().size() != 1) {
            throw std::invalid_argument("give one PATH (a DICOM file or folder)");
        }
        if (p.isSet("stow") == p.isSet("pacs")) {
            throw std::invalid_argument("give either --pacs AET@HOST:PORT or --stow URL");
        }
        std::vector<std::string> passedOver;
        const std::vector<InstanceHeader> instances = collectInstances(
            p.positionalArguments()[0].toStdString(), p.value("series").toStdString(), passedOver);
        for (const std::string& why : passedOver) {
            err << "lucent-cli pacs send: passed over " << QString::fromStdString(why) << "\n";
        }
        if (instances.empty()) {
            err << "lucent-cli pacs send: no DICOM instances to send in "
                << p.positionalArguments()[0]
                << (p.isSet("series") ? " of series " + p.value("series") : QString()) << "\n";
            return kBadInput;
        }
        const SendResult r = p.isSet("stow") ? sendByStow(serviceFrom(p, "stow"), instances) : [&] {
            const auto [node, settings] = nodeFrom(p);
            return sendByCStore(node, settings, instances);
        }();
        QTextStream out(stdout);
        print(r, p.isSet("json"), out);
        return r.allStored() ? kOk : kPacsFailure;
    } catch (const std::invalid_argument& e) {
        err << "lucent-cli pacs send: " << e.what() << "\n";
        return kUsage;
    } catch (const PacsError& e) {
        err << "lucent-cli pacs send: " << e.what() << "\n";
        return kPacsFailure;
    } catch (const InstanceFileError& e) {
        err << "lucent-cli pacs send: " << e.what() << "\n";
        return kBadInput;
    }
}

} // namespace lucent::cli
