#include "ui/viewports/StudyHanging.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <QDir>
#include <QMetaObject>

#include "core/hanging/HangingProtocolJson.h"
#include "core/io/Catalog.h"
#include "core/mpr/WindowPresets.h"
#include "core/pacs/PacsService.h"
#include "core/pacs/PriorsForStudy.h"
#include "core/store/StudyStore.h"
#include "ui/mpr/MprCursor.h"
#include "ui/viewports/SeriesLibrary.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportRegistration.h"
#include "ui/viewports/ViewportWorkspace.h"

namespace lucent {

namespace {

constexpr const char* kPresetProperty = "hangingWindowPreset";

// True for the MPR layout of one series: its axial, coronal, sagittal and 3D views.
bool isMprOfOneSeries(const HangingResult& r) {
    if (r.viewports.size() != 4 || r.viewports.front().series == nullptr) {
        return false;
    }
    std::set<ViewportView> views;
    for (const ViewportAssignment& v : r.viewports) {
        if (v.seriesIndex != r.viewports.front().seriesIndex) {
            return false;
        }
        views.insert(v.spec.view);
    }
    return views == std::set<ViewportView>{ViewportView::Axial, ViewportView::Coronal,
                                           ViewportView::Sagittal, ViewportView::Volume3D};
}

std::string escapeRegex(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (std::string_view("\\^$.|?*+()[]{}").find(c) != std::string_view::npos) {
            out += '\\';
        }
        out += c;
    }
    return out;
}

// The preset whose window the cursor shows, if any.
std::string presetOf(const MprCursor& cursor) {
    for (const WindowPreset& p : windowPresets()) {
        if (std::abs(p.center - cursor.windowCenter()) < 0.5 &&
            std::abs(p.width - cursor.windowWidth()) < 0.5) {
            return std::string(p.name);
        }
    }
    return {};
}

} // namespace

StudyHanging::StudyHanging(ViewportWorkspace* workspace, PacsService* service, QString userFolder,
                           QObject* parent)
    : QObject(parent), workspace_(workspace), service_(service),
      userFolder_(std::move(userFolder)) {
    if (service_ != nullptr) {
        priors_ = std::make_unique<PriorsForStudy>(*service_);
        connect(priors_.get(), &PriorsForStudy::priorReady, this,
                [this](int order, const QString& folder, const QStringList&) {
                    priorReady(order, folder);
                });
        connect(priors_.get(), &PriorsForStudy::noPrior, this,
                [this](int order, const QString& reason) {
                    emit message(tr("No prior %1: %2").arg(order).arg(reason), 8000);
                    priorGone(order);
                });
    }
    connect(workspace_, &ViewportWorkspace::seriesShown, this, [this](Viewport* viewport) {
        const QString preset = viewport->property(kPresetProperty).toString();
        SeriesSession* session = viewport->session();
        if (session != nullptr && !preset.isEmpty()) {
            // Another viewport of this series in another window needs a cursor of its own.
            for (Viewport* other : workspace_->grid()->viewports()) {
                if (other != viewport && other->session() == session &&
                    other->property(kPresetProperty).toString() != preset) {
                    session = workspace_->library()->sibling(session);
                    viewport->show(session, viewport->view());
                    break;
                }
            }
            if (const WindowPreset* p = findWindowPreset(preset.toStdString())) {
                session->cursor()->setWindow(p->center, p->width);
            }
        }
        waiting_.erase(viewport->objectName());
        viewportShown();
    });
    reloadProtocols();
}

StudyHanging::~StudyHanging() {
    scans_.clear(); // joins: a scan posts only to this object
}

QStringList StudyHanging::reloadProtocols() {
    std::vector<std::string> errors;
    protocols_ = loadHangingProtocols(hangingFolders(userFolder_.toStdString()), &errors);
    QStringList out;
    for (const std::string& e : errors) {
        out << QString::fromStdString(e);
    }
    if (!out.isEmpty()) {
        emit message(out.join(QStringLiteral("; ")), 15000);
    }
    return out;
}

namespace {

// The study folders of the patient's series in the store (files/<study>), for a
// worker thread; a store that cannot be read adds none.
std::vector<std::string> storeFoldersOf(const QString& storeFolder, const std::string& patientId) {
    std::vector<std::string> folders;
    if (storeFolder.isEmpty() || patientId.empty() || !QDir(storeFolder).exists()) {
        return folders;
    }
    try {
        const StudyStore store(storeFolder.toStdString());
        for (const StoredSeries& s : store.listSeries()) {
            const std::string study = s.folder.parent_path().string();
            if (s.info.patientId == patientId &&
                std::find(folders.begin(), folders.end(), study) == folders.end()) {
                folders.push_back(study);
            }
        }
    } catch (const StoreError&) {
        // The opened path still hangs.
    }
    return folders;
}

void scanInto(const std::string& path, const LoadControl& control,
              std::vector<HangingSeries>& found) {
    try {
        for (const SeriesEntry& e : scanPath(path, control).series) {
            found.push_back(hangingSeriesOf(e, path));
        }
    } catch (const LoadCancelled&) {
        throw;
    } catch (const std::exception&) {
        // A folder that cannot be scanned hangs nothing; the others still do.
    }
}

} // namespace

void StudyHanging::open(const QString& path) {
    ++generation_;
    clock_.restart();
    reported_ = false;
    studyUid_.clear();
    patientId_.clear();
    series_.clear();
    ranking_.clear();
    rank_ = -1;
    waiting_.clear();
    priorsWanted_.clear();
    const QString store = service_ != nullptr ? service_->config().storeFolder : QString();
    scan(path, store, false);
}

void StudyHanging::scan(const QString& path, const QString& storeFolder, bool rerank,
                        int arrivedOrder) {
    const std::uint64_t generation = generation_;
    scans_.emplace_back(
        [this, path, storeFolder, rerank, generation, arrivedOrder](std::stop_token stop) {
            std::vector<HangingSeries> found;
            LoadControl control;
            control.stop = stop;
            try {
                scanInto(path.toStdString(), control, found);
                // The patient's other studies in the store (a new open only).
                std::string patient;
                for (const HangingSeries& s : found) {
                    if (s.kind == SeriesKind::Volume && !s.patientId.empty()) {
                        patient = s.patientId;
                        break;
                    }
                }
                for (const std::string& folder : storeFoldersOf(storeFolder, patient)) {
                    if (folder != path.toStdString()) {
                        scanInto(folder, control, found);
                    }
                }
            } catch (const LoadCancelled&) {
                return;
            }
            QMetaObject::invokeMethod(
                this,
                [this, found = std::move(found), rerank, generation, arrivedOrder]() mutable {
                    if (generation == generation_) {
                        priorsWanted_.erase(arrivedOrder); // its series are among them now
                        scanned(std::move(found), rerank);
                    }
                },
                Qt::QueuedConnection);
        });
}

void StudyHanging::scanned(std::vector<HangingSeries> found, bool rerank) {
    for (HangingSeries& s : found) {
        const bool known = std::any_of(series_.begin(), series_.end(), [&](const HangingSeries& k) {
            return k.seriesUid == s.seriesUid && k.id == s.id;
        });
        if (!known) {
            series_.push_back(std::move(s));
        }
    }
    if (studyUid_.isEmpty()) {
        // The study opened: the newest of the opened path's (orderStudies' rule).
        const std::vector<HangingSeries> ordered = orderStudies(series_);
        for (const HangingSeries& s : ordered) {
            if (s.studyOrder == 0) {
                studyUid_ = QString::fromStdString(s.studyUid);
                patientId_ = QString::fromStdString(s.patientId);
                break;
            }
        }
    }
    series_ = orderStudies(std::move(series_), studyUid_.toStdString());
    const QString before = rank_ >= 0 && rank_ < static_cast<int>(ranking_.size())
                               ? QString::fromStdString(ranking_[rank_].protocol->name)
                               : QString();
    ranking_ = rankProtocols(protocols_, series_, {priorsWanted_.empty() && rerank});
    if (ranking_.empty() || !ranking_.front().applicable) {
        emit message(tr("No hanging protocol fits this study."), 8000);
        return;
    }
    int rank = 0;
    for (int n = 0; rerank && n < static_cast<int>(ranking_.size()); ++n) {
        if (ranking_[n].applicable &&
            QString::fromStdString(ranking_[n].protocol->name) == before) {
            rank = n; // a prior arrived: the same protocol, now with it
        }
    }
    apply(rank, setShowingPriors(rank, rerank ? set_ : 0));
    const HangingResult* now = applied();
    if (!rerank && priors_ && now != nullptr) {
        // The timeline lists the patient's studies on every open; a prior is fetched
        // only when the protocol asks for one that is not here.
        CurrentStudy current;
        current.patientId = patientId_.toStdString();
        current.studyUid = studyUid_.toStdString();
        for (const HangingSeries& s : series_) {
            if (s.studyOrder == 0 && s.kind == SeriesKind::Volume) {
                current.modality = s.modality;
                current.bodyPart = s.bodyPart;
                current.studyDate = s.studyDate;
                current.studyTime = s.studyTime;
                break;
            }
        }
        QList<int> orders;
        for (const int order : now->missingStudyOrders) {
            orders << order;
            priorsWanted_.insert(order);
        }
        priors_->start(current, orders);
    }
}

int StudyHanging::setShowingPriors(int rank, int set) const {
    const auto showsPrior = [](const HangingResult& r) {
        return std::any_of(r.viewports.begin(), r.viewports.end(), [](const ViewportAssignment& v) {
            return v.series != nullptr && v.series->studyOrder > 0;
        });
    };
    const HangingProtocol& protocol = *ranking_[rank].protocol;
    const RankOptions options{priorsWanted_.empty()};
    if (showsPrior(applyProtocol(protocol, series_, set, options))) {
        return set;
    }
    for (int n = 0; n < static_cast<int>(protocol.viewportSets.size()); ++n) {
        if (showsPrior(applyProtocol(protocol, series_, n, options))) {
            return n;
        }
    }
    return set;
}

const HangingResult* StudyHanging::applied() const {
    return rank_ >= 0 && rank_ < static_cast<int>(ranking_.size()) ? &ranking_[rank_] : nullptr;
}

void StudyHanging::apply(int rank, int set) {
    if (rank < 0 || rank >= static_cast<int>(ranking_.size())) {
        return;
    }
    const HangingProtocol& protocol = *ranking_[rank].protocol;
    const int sets = static_cast<int>(protocol.viewportSets.size());
    set_ = sets == 0 ? 0 : ((set % sets) + sets) % sets;
    rank_ = rank;
    ranking_[rank] = applyProtocol(protocol, series_, set_, {priorsWanted_.empty()});
    show(ranking_[rank]);
}

void StudyHanging::show(const HangingResult& result) {
    const HangingProtocol& protocol = *result.protocol;
    const ViewportSet& set = protocol.viewportSets[static_cast<std::size_t>(set_)];
    if (isMprOfOneSeries(result)) {
        const HangingSeries& s = *result.viewports.front().series;
        emit mprRequested(QString::fromStdString(s.path), QString::fromStdString(s.id));
        waiting_.clear();
        viewportShown();
        return;
    }
    GridShape shape{
        QStringLiteral("%1x%2").arg(set.rows).arg(set.columns), set.rows, set.columns, {}};
    for (const ViewportAssignment& v : result.viewports) {
        shape.cells.push_back({v.spec.row, v.spec.column, v.spec.rowSpan, v.spec.columnSpan});
    }
    ViewportGrid* grid = workspace_->grid();
    grid->setShape(shape);
    workspace_->setCaption(
        tr("%1 — %2 (%3 of %4)   ·   Alt+Down/Up: protocols, "
           "Alt+Right/Left: viewport sets")
            .arg(QString::fromStdString(protocol.name), QString::fromStdString(set.name))
            .arg(set_ + 1)
            .arg(protocol.viewportSets.size()));
    waiting_.clear();
    for (std::size_t n = 0; n < result.viewports.size(); ++n) {
        const ViewportAssignment& v = result.viewports[n];
        Viewport* viewport = grid->viewport(static_cast<int>(n));
        viewport->setProperty(kPresetProperty, QString::fromStdString(v.spec.windowPreset));
        viewport->setLinkGroup(v.spec.linkGroup);
        if (v.series == nullptr) {
            viewport->show(nullptr, v.spec.view);
            continue;
        }
        waiting_.insert(viewport->objectName());
        workspace_->showSeries(viewport, QString::fromStdString(v.series->path),
                               QString::fromStdString(v.series->id), v.spec.view);
    }
    viewportShown();
}

void StudyHanging::viewportShown() {
    const HangingResult* now = applied();
    if (reported_ || now == nullptr || !waiting_.empty() || !priorsWanted_.empty()) {
        return;
    }
    reported_ = true;
    emit hung(QString::fromStdString(now->protocol->name), clock_.elapsed());
    registerPriors(*now);
}

void StudyHanging::registerPriors(const HangingResult& result) {
    // A prior from another scanner (another Frame of Reference) is aligned with the
    // current study by itself, from the first viewport of the current study.
    const auto& viewports = workspace_->grid()->viewports();
    for (std::size_t n = 0; n < result.viewports.size() && n < viewports.size(); ++n) {
        const ViewportAssignment& v = result.viewports[n];
        if (v.series != nullptr && v.series->studyOrder == 0 && viewports[n]->linkGroup() != 0 &&
            viewports[n]->session() != nullptr && viewports[n]->session()->volume()) {
            workspace_->registration()->registerWith(viewports[n], nullptr, false);
            return;
        }
    }
}

void StudyHanging::priorGone(int order) {
    priorsWanted_.erase(order);
    if (priorsWanted_.empty() && !series_.empty()) {
        // Every prior there is is here: a protocol that needs a missing one no longer fits.
        scanned({}, true);
    }
}

void StudyHanging::priorReady(int order, const QString& folder) {
    scan(folder, {}, true, order);
}

void StudyHanging::stepProtocol(int step) {
    const int n = static_cast<int>(ranking_.size());
    for (int tries = 1; tries <= n && rank_ >= 0; ++tries) {
        const int next = ((rank_ + step * tries) % n + n) % n;
        if (ranking_[next].applicable) {
            apply(next, 0);
            return;
        }
    }
}

void StudyHanging::stepViewportSet(int step) {
    if (rank_ >= 0) {
        apply(rank_, set_ + step);
    }
}

QString StudyHanging::saveLayout(const QString& name, QString* error) {
    HangingProtocol p;
    p.name = name.toStdString();
    p.description = "Saved from the viewport grid";
    p.priority = 0.5; // the reader's own layout wins over a shipped one that fits as well
    ViewportSet set{
        "Saved", workspace_->grid()->shape().rows, workspace_->grid()->shape().columns, {}};
    std::map<std::string, std::string> slotOf; // series UID -> slot
    const auto& viewports = workspace_->grid()->viewports();
    for (std::size_t n = 0; n < viewports.size(); ++n) {
        const Viewport* v = viewports[n];
        const GridCell cell = workspace_->grid()->shape().cells[n];
        ViewportSpec spec{cell.row, cell.column, cell.rowSpan, cell.columnSpan,
                          {},       v->view(),   {},           v->linkGroup()};
        if (const SeriesSession* session = v->session()) {
            const std::string uid = session->info().seriesUid;
            const auto known =
                std::find_if(series_.begin(), series_.end(),
                             [&](const HangingSeries& s) { return s.seriesUid == uid; });
            if (!slotOf.count(uid)) {
                SeriesRule rule;
                rule.name = "series " + std::to_string(slotOf.size() + 1);
                rule.studyOrder = known != series_.end() ? std::max(0, known->studyOrder) : 0;
                rule.modalities = {session->info().modality};
                rule.description = "^" + escapeRegex(session->info().description) + "$";
                p.seriesSlots.push_back(rule);
                slotOf[uid] = rule.name;
                if (p.study.modalities.empty() && rule.studyOrder == 0) {
                    p.study.modalities = {session->info().modality};
                }
            }
            spec.seriesSlot = slotOf[uid];
            spec.windowPreset = presetOf(*session->cursor());
        }
        set.viewports.push_back(spec);
    }
    if (p.seriesSlots.empty()) {
        *error = tr("The grid shows no series to save.");
        return {};
    }
    p.viewportSets.push_back(set);
    const std::filesystem::path file =
        std::filesystem::path(userFolder_.toStdString()) / hangingProtocolFileName(p.name);
    try {
        std::filesystem::create_directories(file.parent_path());
        writeHangingProtocol(file, p);
    } catch (const std::exception& e) {
        *error = QString::fromUtf8(e.what());
        return {};
    }
    reloadProtocols();
    return QString::fromStdString(file.string());
}

} // namespace lucent
