#pragma once
// The overlay's own window and level by mouse in a fused MPR view: Alt+right-drag, the
// way a right-drag sets the base's (right = wider, down = higher level), a 400th of the
// width at the press per pixel.

#include <optional>

#include <QObject>
#include <QPoint>

namespace lucent {

class SliceView;
class Viewport;
class ViewportFusion;

class OverlayWindowDrag : public QObject {
    Q_OBJECT

public:
    explicit OverlayWindowDrag(ViewportFusion* fusion);
    void watch(SliceView* view);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    ViewportFusion* fusion_;
    struct Drag {
        Viewport* viewport = nullptr;
        QPoint start;
        double center = 0.0;
        double width = 1.0;
    };
    std::optional<Drag> drag_;
};

} // namespace lucent
