#include "ui/segmentation/GrowFromSeedsEffect.h"

#include <algorithm>
#include <stdexcept>

#include "ui/segmentation/SegmentationSession.h"

namespace lucent {

namespace {

constexpr const char* kWhat = "Grow from seeds";

bool isStroke(const std::string& undoText) {
    return undoText == "Paint" || undoText == "Erase" || undoText == "Draw";
}

} // namespace

GrowFromSeedsEffect::GrowFromSeedsEffect(QObject* parent) : QObject(parent) {}

GrowFromSeedsEffect::~GrowFromSeedsEffect() = default;

std::vector<std::uint32_t>
GrowFromSeedsEffect::seededSegments(const SegmentationSession& session) const {
    std::vector<std::uint32_t> ids;
    for (const Segment& s : session.segmentation().segments()) {
        if (s.visible && !s.locked && s.mask && s.mask->any()) {
            ids.push_back(s.id);
        }
    }
    return ids;
}

// A segment's voxels gained since the last grow are new seeds of it (and no longer of any
// other segment); those it lost are seeds no more.
void GrowFromSeedsEffect::updateSeeds(State& state, const SegmentationSession& session) const {
    for (std::size_t n = 0; n < state.ids.size(); ++n) {
        const SegmentMask& now = *session.segmentation().find(state.ids[n])->mask;
        SegmentMask gained = now;
        gained.subtract(state.result[n]);
        SegmentMask lost = state.result[n];
        lost.subtract(now);
        if (gained.any()) {
            for (std::size_t m = 0; m < state.seeds.size(); ++m) {
                if (m != n) {
                    state.seeds[m].subtract(gained);
                }
            }
            state.seeds[n] |= gained;
        }
        if (lost.any()) {
            state.seeds[n].subtract(lost);
        }
    }
}

bool GrowFromSeedsEffect::grow(SegmentationSession& session) {
    if (!session.volume()) {
        return false;
    }
    const std::vector<std::uint32_t> ids = seededSegments(session);
    if (ids.size() < 2) {
        emit message(tr("Grow from seeds: paint seeds in two or more visible, unlocked "
                        "segments first"),
                     8000);
        return false;
    }
    State& state = states_[&session];
    if (state.ids != ids || !state.grower || state.marginMm != marginMm_) {
        state = State{};
        state.ids = ids;
        for (const std::uint32_t id : ids) {
            state.seeds.push_back(*session.segmentation().find(id)->mask);
        }
        state.marginMm = marginMm_;
        state.grower = std::make_unique<SeedGrower>(*session.volume(), GrowOptions{marginMm_});
        watch(session);
    } else {
        updateSeeds(state, session);
    }
    try {
        outcome_ = state.grower->grow(state.seeds);
    } catch (const std::invalid_argument& e) {
        states_.erase(&session);
        emit message(tr("Grow from seeds: %1").arg(QString::fromUtf8(e.what())), 8000);
        return false;
    }
    state.result = state.grower->masks();
    std::vector<std::pair<std::uint32_t, SegmentMask>> masks;
    for (std::size_t n = 0; n < ids.size(); ++n) {
        masks.emplace_back(ids[n], state.result[n]);
    }
    applying_ = true;
    session.segmentation().setMasks(std::move(masks), kWhat, "Lucent grow from seeds");
    session.notifyChanged();
    applying_ = false;
    emit message(tr("Grow from seeds: %1 segments in %2 ms (%3)")
                     .arg(ids.size())
                     .arg(outcome_.ms, 0, 'f', 0)
                     .arg(outcome_.incremental ? tr("updated") : tr("computed afresh")),
                 5000);
    return true;
}

void GrowFromSeedsEffect::watch(SegmentationSession& session) {
    if (watched_.contains(&session)) {
        return;
    }
    watched_.insert(&session);
    connect(&session, &SegmentationSession::segmentsChanged, this,
            [this, s = &session] { strokeMade(*s); });
    connect(&session, &QObject::destroyed, this, [this, s = &session] {
        states_.erase(s);
        watched_.remove(s);
    });
}

void GrowFromSeedsEffect::strokeMade(SegmentationSession& session) {
    // A stroke just made is the last step with nothing to redo (an undo leaves a redo).
    const Segmentation& segmentation = session.segmentation();
    if (applying_ || !updateAfterStrokes_ || !states_.contains(&session) ||
        !isStroke(segmentation.undoText()) || segmentation.canRedo()) {
        return;
    }
    grow(session);
}

} // namespace lucent
