#include "ui/viewports/ViewportRegistration.h"

#include <algorithm>

#include <QMetaObject>

#include "core/registration/Registration.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportLinks.h"

namespace lucent {

namespace {

struct Pair {
    std::shared_ptr<const Volume> fixed, moving;
    std::string fixedUid, movingUid;
    QString label;
};

std::vector<Pair> pairsFor(const ViewportGrid& grid, const ViewportLinks& links,
                           const Viewport& viewport, bool again) {
    std::vector<Pair> pairs;
    const SeriesSession* here = viewport.session();
    if (here == nullptr || !here->volume() || viewport.linkGroup() == 0) {
        return pairs;
    }
    for (const Viewport* other : grid.viewports()) {
        const SeriesSession* there = other->session();
        if (there == nullptr || !there->volume() || other->linkGroup() != viewport.linkGroup() ||
            there->info().seriesUid == here->info().seriesUid) {
            continue;
        }
        const std::string& a = here->volume()->frameOfReferenceUid;
        if (!a.empty() && a == there->volume()->frameOfReferenceUid) {
            continue; // one Frame of Reference: linked by position already
        }
        const bool known = std::any_of(pairs.begin(), pairs.end(), [&](const Pair& p) {
            return p.movingUid == there->info().seriesUid;
        });
        const bool registered =
            links.transform(here->info().seriesUid, there->info().seriesUid).has_value();
        if (!known && (again || !registered)) {
            pairs.push_back({here->volume(), there->volume(), here->info().seriesUid,
                             there->info().seriesUid,
                             ViewportRegistration::tr("viewport %1 to viewport %2")
                                 .arg(other->number())
                                 .arg(viewport.number())});
        }
    }
    return pairs;
}

} // namespace

ViewportRegistration::ViewportRegistration(ViewportGrid* grid, ViewportLinks* links,
                                           QObject* parent)
    : QObject(parent), grid_(grid), links_(links) {}

ViewportRegistration::~ViewportRegistration() {
    workers_.clear(); // requests stop and joins: a worker posts only to this object
}

void ViewportRegistration::cancel() {
    for (std::jthread& w : workers_) {
        w.request_stop();
    }
}

int ViewportRegistration::registerWith(Viewport* viewport, QString* message, bool again) {
    const std::vector<Pair> pairs =
        viewport != nullptr ? pairsFor(*grid_, *links_, *viewport, again) : std::vector<Pair>{};
    if (pairs.empty() && !again) {
        return 0; // nothing new to align: no word about it
    }
    QStringList labels;
    for (const Pair& p : pairs) {
        labels << p.label;
    }
    const QString text =
        pairs.empty() ? tr("Register: no other linked viewport shows a series of another Frame "
                           "of Reference. Turn on the link of the viewports to align.")
                      : tr("Registering %1…").arg(labels.join(QStringLiteral(", ")));
    if (message != nullptr) {
        *message = text;
    }
    emit progress(text);
    running_ += static_cast<int>(pairs.size());
    // One worker for the pairs: ITK already uses both cores for one registration.
    workers_.emplace_back([this, pairs](std::stop_token stop) {
        for (const Pair& p : pairs) {
            RegistrationOptions options;
            options.stop = stop;
            bool ok = false;
            QString said;
            RegistrationResult r;
            try {
                r = registerRigid(*p.fixed, *p.moving, options);
                ok = true;
                said = tr("Registered %1: metric %2 after %3 iterations, %4 s")
                           .arg(p.label)
                           .arg(r.metric, 0, 'f', 3)
                           .arg(r.iterations)
                           .arg(r.seconds, 0, 'f', 1);
            } catch (const std::exception& e) {
                said = tr("Not registered, %1: %2").arg(p.label, QString::fromUtf8(e.what()));
            }
            QMetaObject::invokeMethod(
                this,
                [this, p, ok, said, m = r.fixedToMoving] {
                    --running_;
                    if (ok) {
                        links_->setTransform(p.fixedUid, p.movingUid, m);
                    }
                    emit finished(ok, said);
                },
                Qt::QueuedConnection);
        }
    });
    return static_cast<int>(pairs.size());
}

} // namespace lucent
