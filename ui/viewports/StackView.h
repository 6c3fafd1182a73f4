#pragma once
// A viewport for a 2D image stack (core/stack/ImageStack.h): colour and palette
// secondary captures, localizers, lone images, ultrasound and XA cine. The frame
// is fitted to the widget (keeping its pixel aspect); wheel = next/previous frame,
// C = cine at the stack's frame time (10 fps without one), right-drag = window
// (right = wider) and level (down = higher) for grey frames, ctrl+wheel = zoom
// about the mouse, middle-drag = pan, R = reset zoom, pan and window. Corner
// texts: series and patient, frame n/N (and its time in a cine), W/L, zoom.

#include <QImage>
#include <QTimer>
#include <QWidget>

#include <memory>

#include "core/stack/ImageStack.h"

namespace lucent {

class StackView : public QWidget {
    Q_OBJECT
public:
    explicit StackView(QWidget* parent = nullptr);

    // Shows the stack's first frame with its default window, zoom 1, no pan, cine off.
    // nullptr shows nothing.
    void setStack(std::shared_ptr<const ImageStack> stack);
    const std::shared_ptr<const ImageStack>& stack() const { return stack_; }

    int frame() const { return frame_; }
    // Clamped to the stack's frames; says frameChanged when it changes.
    void setFrame(int frame);

    // Grey frames only (colour frames ignore it).
    GreyWindow window() const { return window_; }
    void setWindow(const GreyWindow& window);

    // 1 fits the frame; each ctrl+wheel notch multiplies it by zoomStepFactor().
    double zoom() const { return zoom_; }
    static double zoomStepFactor() { return 1.25; }
    // Sets the zoom keeping the image point under `anchor` (widget pixels) in place.
    void setZoom(double zoom, const QPointF& anchor);
    // The image centre's offset from the widget centre, widget pixels.
    QPointF pan() const { return pan_; }
    void setPan(const QPointF& pan);
    // Zoom 1, no pan, the stack's default window.
    void resetView();

    bool cineRunning() const { return cine_.isActive(); }
    void setCineRunning(bool running);

    // Where the frame's pixel grid lies in the widget (widget pixels).
    QRectF imageRect() const;
    // What paintEvent shows: the widget's size, the frame and its corner texts.
    QImage image() const;

signals:
    void frameChanged(int frame);
    void windowChanged();
    void viewChanged(); // zoom or pan

protected:
    void paintEvent(QPaintEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;

private:
    enum class Drag { None, Window, Pan };

    void paintTo(QPainter& painter) const;
    void advanceCine();
    QImage frameImage() const; // the current frame through the window, cached
    double windowStep() const; // window units per pixel of a right-drag

    std::shared_ptr<const ImageStack> stack_;
    int frame_ = 0;
    GreyWindow window_;
    double zoom_ = 1.0;
    QPointF pan_;
    QTimer cine_;
    Drag drag_ = Drag::None;
    QPoint dragStart_;
    GreyWindow dragWindow_;
    QPointF dragPan_;
    int wheelRemainder_ = 0;
    mutable QImage cached_;
    mutable int cachedFrame_ = -1;
    mutable GreyWindow cachedWindow_;
};

} // namespace lucent
