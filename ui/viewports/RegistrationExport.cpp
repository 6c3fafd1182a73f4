#include "ui/viewports/RegistrationExport.h"

#include <QStringList>

#include "core/exchange/SpatialRegistrationSource.h"
#include "core/store/StudyStore.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportLinks.h"
#include "ui/viewports/ViewportWorkspace.h"

namespace lucent {
namespace {

const SeriesEntry& entryOf(const Catalog& catalog, const SeriesSession& session) {
    const SeriesEntry* entry = catalog.find(session.info().seriesUid);
    if (entry == nullptr) {
        throw std::runtime_error(session.path().toStdString() + " no longer holds series " +
                                 session.info().seriesUid);
    }
    return *entry;
}

// Writes fixed -> moving into the store; returns the object's SOP Instance UID.
std::string storeRegistration(StudyStore& store, const SeriesSession& fixed,
                              const SeriesSession& moving, const glm::dmat4& fixedToMoving) {
    const Catalog fixedCatalog = scanPath(fixed.path().toStdString());
    const Catalog movingCatalog = scanPath(moving.path().toStdString());
    SpatialRegistrationInput in = spatialRegistrationInput(
        entryOf(fixedCatalog, fixed), entryOf(movingCatalog, moving), fixedToMoving);
    in.contentDescription = "Registration kept by Lucent: " + moving.title().toStdString() +
                            " onto " + fixed.title().toStdString();
    const std::filesystem::path temp = store.temporaryFile();
    const SpatialRegistrationIds ids = writeSpatialRegistration(temp, in);
    InstanceRecord record;
    record.series = fixed.info();
    record.series.seriesUid = ids.seriesUid;
    record.series.modality = "REG";
    record.series.description = in.seriesDescription;
    record.seriesNumber = in.seriesNumber;
    record.sopInstanceUid = ids.sopInstanceUid;
    store.add(temp, record);
    return ids.sopInstanceUid;
}

} // namespace

std::vector<SavedRegistration> saveRegistrations(ViewportWorkspace& workspace, Viewport* fixed,
                                                 QString* message) {
    std::vector<SavedRegistration> saved;
    QStringList problems;
    const QString folder = workspace.links()->storeFolder();
    SeriesSession* base = fixed != nullptr ? fixed->session() : nullptr;
    if (folder.isEmpty() || base == nullptr || !base->volume()) {
        problems << (folder.isEmpty() ? QObject::tr("there is no study store")
                                      : QObject::tr("the active viewport shows no volume"));
    } else {
        try {
            StudyStore store(folder.toStdString());
            std::set<std::string> done;
            for (Viewport* other : workspace.grid()->viewports()) {
                SeriesSession* moving = other->session();
                if (moving == nullptr || !moving->volume() || moving->volume() == base->volume() ||
                    !done.insert(moving->info().seriesUid).second) {
                    continue;
                }
                const auto transform =
                    workspace.links()->transform(base->info().seriesUid, moving->info().seriesUid);
                if (!transform) {
                    continue;
                }
                try {
                    const std::string sop = storeRegistration(store, *base, *moving, *transform);
                    saved.push_back(
                        {base->seriesUid(), moving->seriesUid(), QString::fromStdString(sop)});
                } catch (const std::exception& e) {
                    problems << QStringLiteral("%1: %2").arg(moving->title(),
                                                             QString::fromUtf8(e.what()));
                }
            }
        } catch (const StoreError& e) {
            problems << QString::fromUtf8(e.what());
        }
    }
    if (message != nullptr) {
        *message = QObject::tr("%n registration(s) saved to the study store", nullptr,
                               static_cast<int>(saved.size()));
        if (saved.empty() && problems.isEmpty()) {
            *message += QObject::tr(": no viewport is registered with the active one");
        }
        if (!problems.isEmpty()) {
            *message += QStringLiteral("; not saved: ") + problems.join(QStringLiteral("; "));
        }
    }
    return saved;
}

} // namespace lucent
