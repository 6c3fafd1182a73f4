#pragma once
// Which viewport of the grid fuses which series over its own: the overlay found through
// the link between the two series (the same Frame of Reference, a registration, or a
// "link here" offset: ViewportLinks), a default look by modality, and the layer kept
// across a viewport's view changes and refreshed when a registration lands.

#include <cstdint>
#include <map>
#include <optional>
#include <thread>
#include <vector>

#include <QObject>
#include <QPointer>
#include <QString>

#include "core/fusion/FusionStyle.h"
#include "core/linking/SeriesLink.h"

namespace lucent {

class SeriesSession;
class Viewport;
class ViewportWorkspace;
class FusionNudge;
class OverlayWindowDrag;
struct FusionLayer;

// The base -> overlay transform of a link (identity, the registration's, or the offset's
// translation); nullopt when the link knows no relation.
std::optional<glm::dmat4> fusionTransform(const SeriesLink& link);

// The look an overlay starts with: PET in hot iron blended at 50 % with what is below
// its window cleared; the same modality as the base (a registration check) as a grey
// checkerboard in the base's window; anything else in hot iron blended at 40 %; the window
// from defaultWindow().
FusionStyle defaultFusionStyle(const Volume& base, const Volume& overlay);

class ViewportFusion : public QObject {
    Q_OBJECT

public:
    explicit ViewportFusion(ViewportWorkspace* workspace, QObject* parent = nullptr);

    // Fuses `overlay` over the viewport's series (an MPR or 3D view of a volume). False,
    // with the reason in `message`, when the viewport shows no volume or the two series
    // have no known relation (Register or Link Here first).
    bool fuse(Viewport* viewport, SeriesSession* overlay, QString* message = nullptr);
    void clear(Viewport* viewport);
    // The viewport's overlay and its look; nullptr / nullopt without one.
    SeriesSession* overlayOf(const Viewport* viewport) const;
    std::optional<FusionStyle> styleOf(const Viewport* viewport) const;
    void setStyle(Viewport* viewport, const FusionStyle& style);

    // Nudging by hand (FusionNudge on every fused MPR view while on).
    bool nudging() const { return nudging_; }
    void setNudging(bool on);
    // The base -> overlay transform the viewport's overlay is drawn through now.
    std::optional<glm::dmat4> transformOf(const Viewport* viewport) const;
    // Draws the overlay through `transform` for now (a nudge being dragged).
    void previewTransform(Viewport* viewport, const glm::dmat4& transform);
    // Keeps `transform` as the pair's (ViewportLinks: the study store, the linked views) and
    // draws every viewport that fuses the pair through it.
    void keepTransform(Viewport* viewport, const glm::dmat4& transform);

signals:
    // A viewport's overlay or look changed (the controls follow).
    void fusionChanged(lucent::Viewport* viewport);
    // A 3D viewport's overlay, resampled onto its grid, is drawn from now on.
    void overlayShownIn3d(lucent::Viewport* viewport);

private:
    struct Fused {
        QPointer<SeriesSession> base;
        QPointer<SeriesSession> overlay;
        FusionStyle style;
    };
    // Puts the layer on the viewport's slice view again (a new view, a new transform).
    bool apply(Viewport* viewport, const Fused& fused, QString* message);
    // A 3D viewport: the overlay resampled onto the base's grid on a worker thread, then
    // handed to its VolumeView (the last job of a viewport wins).
    void applyTo3d(Viewport* viewport, const Fused& fused, const glm::dmat4& transform);
    void reapplyAll();

    ViewportWorkspace* workspace_;
    std::map<Viewport*, Fused, std::less<>> fused_;
    std::map<const Viewport*, std::uint64_t, std::less<>> jobs_; // the 3D resampling wanted
    std::uint64_t lastJob_ = 0;
    FusionNudge* nudge_;            // a child
    OverlayWindowDrag* windowDrag_; // a child
    bool nudging_ = false;
    std::vector<std::jthread> workers_; // last: joined before the rest goes
};

} // namespace lucent
