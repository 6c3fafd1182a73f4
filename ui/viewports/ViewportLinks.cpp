#include "ui/viewports/ViewportLinks.h"

#include <QDir>

#include "core/store/StudyStore.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SliceView.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"

namespace lucent {

namespace {

std::string uidOf(const SeriesSession& s) {
    return s.info().seriesUid;
}

QString describe(const Viewport& v) {
    return QStringLiteral("viewport %1 (%2)").arg(v.number()).arg(viewportViewTitle(v.view()));
}

} // namespace

ViewportLinks::ViewportLinks(ViewportGrid* grid, QObject* parent) : QObject(parent), grid_(grid) {
    connect(grid_, &ViewportGrid::viewportsChanged, this, &ViewportLinks::rewire);
    // A series shown may have come with a study that holds registrations.
    connect(grid_, &ViewportGrid::viewportContentChanged, this,
            &ViewportLinks::reloadStoredRegistrations);
    rewire();
}

ViewportLinks::~ViewportLinks() = default;

QString ViewportLinks::storeFolder() const {
    return store_ ? QString::fromStdString(store_->root().string()) : QString();
}

void ViewportLinks::setStoreFolder(const QString& folder) {
    store_.reset();
    if (folder.isEmpty()) {
        return;
    }
    try {
        QDir().mkpath(folder);
        store_ = std::make_unique<StudyStore>(folder.toStdString());
        reloadStoredRegistrations();
    } catch (const StoreError& e) {
        say(tr("Link offsets are kept for this session only: %1").arg(e.what()));
    }
}

std::optional<glm::dvec3> ViewportLinks::offset(const std::string& a, const std::string& b) const {
    if (store_) {
        try {
            return store_->seriesOffset(a, b);
        } catch (const StoreError&) {
            // Fall back to what this session set.
        }
    }
    if (const auto it = sessionOffsets_.find({a, b}); it != sessionOffsets_.end()) {
        return it->second;
    }
    return std::nullopt;
}

std::optional<glm::dmat4> ViewportLinks::transform(const std::string& a,
                                                   const std::string& b) const {
    if (const auto it = sessionTransforms_.find({a, b}); it != sessionTransforms_.end()) {
        return it->second;
    }
    if (store_) {
        try {
            return store_->seriesTransform(a, b);
        } catch (const StoreError&) {
            // Not registered, as far as this session knows.
        }
    }
    return std::nullopt;
}

void ViewportLinks::setTransform(const std::string& a, const std::string& b,
                                 const glm::dmat4& aToB) {
    sessionTransforms_[{a, b}] = aToB;
    sessionTransforms_[{b, a}] = glm::inverse(aToB);
    if (store_) {
        try {
            store_->setSeriesTransform(a, b, aToB);
        } catch (const StoreError& e) {
            say(tr("The registration is kept for this session only: %1").arg(e.what()));
        }
    }
    updateReferenceLines();
}

SeriesLink ViewportLinks::linkBetween(const SeriesSession& a, const SeriesSession& b) const {
    std::optional<glm::dmat4> known = transform(uidOf(a), uidOf(b));
    if (!known) {
        known = registrations_.between(a.info().frameOfReferenceUid, b.info().frameOfReferenceUid);
    }
    return linkSeries(*a.volume(), *b.volume(), offset(uidOf(a), uidOf(b)), known);
}

void ViewportLinks::reloadStoredRegistrations() {
    registrations_.clear();
    if (!store_) {
        return;
    }
    try {
        registrations_.load(*store_);
    } catch (const StoreError& e) {
        say(tr("The store's registrations cannot be read: %1").arg(e.what()));
    }
    for (const std::string& problem : registrations_.problems()) {
        say(tr("A Spatial Registration in the store is not used: %1")
                .arg(QString::fromStdString(problem)));
    }
}

void ViewportLinks::say(const QString& text) {
    lastNotice_ = text;
    if (said_.insert(text).second) {
        emit notice(text);
    }
}

void ViewportLinks::rewire() {
    for (const QMetaObject::Connection& c : connections_) {
        disconnect(c);
    }
    connections_.clear();
    std::set<SeriesSession*> sessions;
    for (Viewport* v : grid_->viewports()) {
        connections_.push_back(connect(v, &Viewport::contentChanged, this, &ViewportLinks::rewire));
        connections_.push_back(
            connect(v, &Viewport::linkGroupChanged, this, &ViewportLinks::updateReferenceLines));
        if (v->session() != nullptr) {
            sessions.insert(v->session());
        }
        if (SliceView* slice = v->sliceView()) {
            connections_.push_back(
                connect(slice, &SliceView::zoomPanChanged, this, [this, v] { zoomPanChanged(v); }));
        }
    }
    windows_.clear();
    for (SeriesSession* s : sessions) {
        MprCursor* cursor = s->cursor();
        windows_[s] = {cursor->windowCenter(), cursor->windowWidth()};
        connections_.push_back(
            connect(cursor, &MprCursor::pointChanged, this, [this, s] { pointMoved(s); }));
        connections_.push_back(connect(cursor, &MprCursor::rotationChanged, this,
                                       &ViewportLinks::updateReferenceLines));
        connections_.push_back(
            connect(cursor, &MprCursor::windowChanged, this, [this, s] { windowChanged(s); }));
    }
    updateReferenceLines();
}

Viewport* ViewportLinks::sourceViewport(SeriesSession* session, int group) const {
    Viewport* active = grid_->activeViewport();
    if (active != nullptr && active->session() == session && active->linkGroup() == group) {
        return active;
    }
    for (Viewport* v : grid_->viewports()) {
        if (v->session() == session && v->linkGroup() == group && v->sliceView() != nullptr) {
            return v;
        }
    }
    return nullptr;
}

void ViewportLinks::pointMoved(SeriesSession* source) {
    if (propagating_) {
        updateReferenceLines();
        return;
    }
    propagating_ = true;
    const glm::dvec3 point = source->cursor()->point();
    std::set<int> groups;
    for (Viewport* v : grid_->viewports()) {
        if (v->session() == source && v->linkGroup() != 0) {
            groups.insert(v->linkGroup());
        }
    }
    for (const int group : groups) {
        Viewport* from = sourceViewport(source, group);
        if (from == nullptr || from->sliceView() == nullptr) {
            continue;
        }
        const glm::dvec3 normal = from->sliceView()->plane().normal();
        std::set<SeriesSession*> moved;
        for (Viewport* to : grid_->viewports()) {
            SeriesSession* target = to->session();
            if (to->linkGroup() != group || target == nullptr || target == source ||
                to->sliceView() == nullptr || moved.count(target) != 0) {
                continue;
            }
            const SeriesLink link = linkBetween(*source, *target);
            if (!link.linked()) {
                say(tr("%1 and %2 are not linked: %3")
                        .arg(describe(*from), describe(*to), QString::fromStdString(link.reason)));
                continue;
            }
            const glm::dvec3 targetNormal = to->sliceView()->plane().normal();
            // A registered prior may lie rotated: its plane is compared in its own frame.
            const glm::dvec3 mapped = link.mapDirection(normal);
            if (!planesParallel(mapped, targetNormal)) {
                say(tr("%1 does not scroll with %2: their planes are %3° apart (more than %4°)")
                        .arg(describe(*to), describe(*from))
                        .arg(planeAngleDegrees(mapped, targetNormal), 0, 'f', 1)
                        .arg(kParallelToleranceDegrees));
                continue;
            }
            target->cursor()->setPoint(
                linkedPoint(link, target->volume()->geometry(), point, targetNormal));
            moved.insert(target);
        }
    }
    propagating_ = false;
    updateReferenceLines();
}

void ViewportLinks::windowChanged(SeriesSession* source) {
    const MprCursor* from = source->cursor();
    const std::pair<double, double> now{from->windowCenter(), from->windowWidth()};
    const auto known = windows_.find(source);
    if (known == windows_.end()) {
        windows_[source] = now;
        return;
    }
    const std::pair<double, double> before = known->second;
    known->second = now;
    if (propagating_) {
        return;
    }
    propagating_ = true;
    std::set<int> groups;
    for (Viewport* v : grid_->viewports()) {
        if (v->session() == source && v->linkGroup() != 0) {
            groups.insert(v->linkGroup());
        }
    }
    // Only viewports that showed the same window follow: a lung window and a soft
    // tissue window of one study stay apart, each linked to its like in the prior.
    for (Viewport* to : grid_->viewports()) {
        SeriesSession* target = to->session();
        if (target == nullptr || target == source || groups.count(to->linkGroup()) == 0 ||
            target->info().modality != source->info().modality ||
            std::pair(target->cursor()->windowCenter(), target->cursor()->windowWidth()) !=
                before) {
            continue;
        }
        target->cursor()->setWindow(now.first, now.second);
        windows_[target] = now;
    }
    propagating_ = false;
}

void ViewportLinks::zoomPanChanged(Viewport* source) {
    if (propagating_ || source->linkGroup() == 0 || source->sliceView() == nullptr) {
        return;
    }
    propagating_ = true;
    const SliceView* from = source->sliceView();
    for (Viewport* to : grid_->viewports()) {
        if (to == source || to->linkGroup() != source->linkGroup() || to->sliceView() == nullptr ||
            !planesParallel(from->plane().normal(), to->sliceView()->plane().normal())) {
            continue;
        }
        to->sliceView()->setZoomAndPan(from->zoom(), from->pan());
    }
    propagating_ = false;
}

void ViewportLinks::updateReferenceLines() {
    for (Viewport* v : grid_->viewports()) {
        SliceView* view = v->sliceView();
        if (view == nullptr) {
            continue;
        }
        std::vector<ReferencePlane> planes;
        for (Viewport* other : grid_->viewports()) {
            // Viewports of the same series show their planes as the crosshair already.
            if (other == v || other->sliceView() == nullptr || other->session() == v->session()) {
                continue;
            }
            const SeriesLink link = linkBetween(*other->session(), *v->session());
            if (!link.linked()) {
                continue;
            }
            const SlicePlane p = other->sliceView()->plane();
            planes.push_back({link.map(p.centre), link.mapDirection(p.normal()),
                              QColor(230, 190, 60), QString::number(other->number())});
        }
        view->setReferencePlanes(std::move(planes));
    }
}

int ViewportLinks::linkHere(Viewport* viewport, QString* message) {
    SeriesSession* here =
        viewport != nullptr && viewport->session() != nullptr && viewport->session()->volume()
            ? viewport->session()
            : nullptr;
    QStringList done;
    int linked = 0;
    if (here != nullptr) {
        if (viewport->linkGroup() == 0) {
            viewport->toggleLink();
        }
        std::set<SeriesSession*> seen{here};
        for (Viewport* other : grid_->viewports()) {
            SeriesSession* there = other->session();
            if (there == nullptr || !there->volume() ||
                other->linkGroup() != viewport->linkGroup() || !seen.insert(there).second ||
                (!here->volume()->frameOfReferenceUid.empty() &&
                 here->volume()->frameOfReferenceUid == there->volume()->frameOfReferenceUid)) {
                continue;
            }
            const glm::dvec3 offset =
                linkHereOffset(here->cursor()->point(), there->cursor()->point());
            const std::string a = uidOf(*here);
            const std::string b = uidOf(*there);
            sessionOffsets_[{a, b}] = offset;
            sessionOffsets_[{b, a}] = -offset;
            if (store_) {
                try {
                    store_->setSeriesOffset(a, b, offset);
                } catch (const StoreError& e) {
                    done << tr("viewport %1 for this session only (%2)")
                                .arg(other->number())
                                .arg(QString::fromUtf8(e.what()));
                    ++linked;
                    continue;
                }
            }
            done << tr("viewport %1").arg(other->number());
            ++linked;
        }
    }
    const QString text =
        linked == 0 ? tr("Link here: no linked viewport shows a series of another Frame of "
                         "Reference. Turn on the link of the viewports to align, put the "
                         "crosshair on the same anatomy in each, then choose Link Here.")
                    : tr("Linked viewport %1 here with %2.")
                          .arg(viewport->number())
                          .arg(done.join(QStringLiteral(", ")));
    if (message != nullptr) {
        *message = text;
    }
    lastNotice_ = text;
    emit notice(text);
    updateReferenceLines();
    return linked;
}

void ViewportLinks::linkAll(int group) {
    for (Viewport* v : grid_->viewports()) {
        v->setLinkGroup(group);
    }
}

} // namespace lucent
