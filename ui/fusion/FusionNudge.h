#pragma once
// Nudging a fused overlay by hand in an MPR view, when the registration is nearly right:
// while on, a left-drag moves the overlay in the plane, a Shift+left-drag turns it about
// the crosshair around the plane's normal, the arrow keys move it 1 mm and Ctrl+Left/Right
// turn it 1 degree. Each finished nudge is kept as the pair's transform (ViewportFusion).

#include <optional>

#include <QObject>
#include <QPoint>

#include <glm/glm.hpp>

namespace lucent {

class SliceView;
class Viewport;
class ViewportFusion;

class FusionNudge : public QObject {
    Q_OBJECT

public:
    explicit FusionNudge(ViewportFusion* fusion);

    // Watches (or stops watching) a viewport's slice view.
    void watch(SliceView* view);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    bool press(Viewport* viewport, SliceView* view, const QPoint& pos, bool turn);
    void drag(SliceView* view, const QPoint& pos, bool finished);
    bool key(Viewport* viewport, SliceView* view, int key, bool ctrl);

    ViewportFusion* fusion_;
    struct Drag {
        Viewport* viewport = nullptr;
        QPoint start;
        glm::dmat4 transform{1.0}; // at the press
        bool turn = false;
    };
    std::optional<Drag> drag_;
};

} // namespace lucent
