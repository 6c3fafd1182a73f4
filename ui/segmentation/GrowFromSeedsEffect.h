#pragma once
// The Segment Editor's "Grow from seeds" (core/segmentation/GrowFromSeeds: fast GrowCut):
// the visible, unlocked segments that hold voxels are the seeds; growing replaces each by
// its grown region, one undo step. The seeds are kept: strokes painted or erased after a grow
// (the segment's voxels gained or lost against the last result) change the seeds, so the next
// grow starts from the previous result where they only gained voxels (under half a second on
// the 512x512x140 CT). With updateAfterStrokes on, every paint, erase or draw stroke on the
// session grows again by itself, as Slicer's effect updates its preview.

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <QObject>
#include <QSet>

#include "core/segmentation/GrowFromSeeds.h"

namespace lucent {

class SegmentationSession;

class GrowFromSeedsEffect : public QObject {
    Q_OBJECT

public:
    explicit GrowFromSeedsEffect(QObject* parent = nullptr);
    ~GrowFromSeedsEffect() override;

    // The grown box: the seeds' box padded by this many mm (0: the whole volume).
    void setMarginMm(double mm) { marginMm_ = mm; }
    double marginMm() const { return marginMm_; }

    // Grows the session's seeds and applies the result (one undo step "Grow from seeds").
    // False, with the reason in message(), for fewer than two seeded segments.
    bool grow(SegmentationSession& session);
    const GrowOutcome& lastOutcome() const { return outcome_; }

    // Grows again after each stroke on a session grown before.
    void setUpdateAfterStrokes(bool on) { updateAfterStrokes_ = on; }
    bool updateAfterStrokes() const { return updateAfterStrokes_; }

signals:
    void message(const QString& text, int timeoutMs);

private:
    struct State {
        std::vector<std::uint32_t> ids;
        std::vector<SegmentMask> seeds;
        std::vector<SegmentMask> result; // what the last grow applied
        std::unique_ptr<SeedGrower> grower;
        double marginMm = 0.0;
    };
    void watch(SegmentationSession& session);
    void strokeMade(SegmentationSession& session);
    std::vector<std::uint32_t> seededSegments(const SegmentationSession& session) const;
    void updateSeeds(State& state, const SegmentationSession& session) const;

    double marginMm_ = 5.0;
    bool updateAfterStrokes_ = false;
    bool applying_ = false;
    GrowOutcome outcome_;
    std::map<const SegmentationSession*, State> states_;
    QSet<const SegmentationSession*> watched_;
};

} // namespace lucent
