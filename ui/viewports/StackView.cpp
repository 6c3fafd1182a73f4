#include "ui/viewports/StackView.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>

#include <algorithm>
#include <cmath>

#include "core/stack/StackRendering.h"
#include "ui/mpr/SliceOverlay.h"

namespace lucent {
namespace {

// Pixel spacing (mm) of the current frame, or square pixels when unknown.
glm::dvec2 spacingOf(const ImageStack& s, int frame) {
    const StackFrame& f = s.frames[static_cast<std::size_t>(frame)];
    return f.hasPixelSpacing ? f.pixelSpacing : glm::dvec2(1.0);
}

} // namespace

StackView::StackView(QWidget* parent) : QWidget(parent) {
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(64, 64);
    setAttribute(Qt::WA_OpaquePaintEvent);
    cine_.setTimerType(Qt::PreciseTimer);
    connect(&cine_, &QTimer::timeout, this, &StackView::advanceCine);
}

void StackView::setStack(std::shared_ptr<const ImageStack> stack) {
    cine_.stop();
    stack_ = std::move(stack);
    frame_ = 0;
    cachedFrame_ = -1;
    resetView();
    emit frameChanged(frame_);
}

void StackView::setFrame(int frame) {
    if (!stack_ || stack_->frameCount() == 0) {
        return;
    }
    frame = std::clamp(frame, 0, stack_->frameCount() - 1);
    if (frame == frame_) {
        return;
    }
    frame_ = frame;
    update();
    emit frameChanged(frame_);
}

void StackView::setWindow(const GreyWindow& window) {
    const GreyWindow w{window.centre, std::max(window.width, 1e-6)};
    if (w.centre == window_.centre && w.width == window_.width) {
        return;
    }
    window_ = w;
    update();
    emit windowChanged();
}

void StackView::setZoom(double zoom, const QPointF& anchor) {
    zoom = std::clamp(zoom, 0.05, 64.0);
    // The image point under the anchor stays there: its offset from the image
    // centre scales with the zoom.
    const QPointF centre = QPointF(width() / 2.0, height() / 2.0) + pan_;
    pan_ = anchor - (anchor - centre) * (zoom / zoom_) - QPointF(width() / 2.0, height() / 2.0);
    zoom_ = zoom;
    update();
    emit viewChanged();
}

void StackView::setPan(const QPointF& pan) {
    pan_ = pan;
    update();
    emit viewChanged();
}

void StackView::resetView() {
    zoom_ = 1.0;
    pan_ = {};
    window_ = stack_ ? stack_->defaultWindow() : GreyWindow{};
    update();
    emit viewChanged();
    emit windowChanged();
}

void StackView::setCineRunning(bool running) {
    if (!running || !stack_ || stack_->frameCount() < 2) {
        cine_.stop();
    } else {
        cine_.start(static_cast<int>(std::lround(stack_->cineIntervalMs())));
    }
    update();
}

void StackView::advanceCine() {
    if (!stack_ || stack_->frameCount() < 2) {
        cine_.stop();
        return;
    }
    setFrame((frame_ + 1) % stack_->frameCount());
}

QRectF StackView::imageRect() const {
    if (!stack_ || stack_->frameCount() == 0) {
        return {};
    }
    const glm::dvec2 spacing = spacingOf(*stack_, frame_);
    const double w = stack_->columns * spacing.x;
    const double h = stack_->rows * spacing.y;
    const double scale = std::min(width() / w, height() / h) * zoom_;
    const QSizeF size(w * scale, h * scale);
    const QPointF centre = QPointF(width() / 2.0, height() / 2.0) + pan_;
    return {centre - QPointF(size.width() / 2.0, size.height() / 2.0), size};
}

QImage StackView::frameImage() const {
    if (cachedFrame_ == frame_ && cachedWindow_.centre == window_.centre &&
        cachedWindow_.width == window_.width) {
        return cached_;
    }
    const ImageRGBA8 rgba = renderStackFrame(*stack_, frame_, window_);
    cached_ =
        QImage(rgba.pixels.data(), rgba.width, rgba.height, rgba.width * 4, QImage::Format_RGBA8888)
            .copy();
    cachedFrame_ = frame_;
    cachedWindow_ = window_;
    return cached_;
}

void StackView::paintTo(QPainter& painter) const {
    painter.fillRect(rect(), Qt::black);
    if (!stack_ || stack_->frameCount() == 0) {
        painter.setPen(QColor(160, 160, 160));
        painter.drawText(rect(), Qt::AlignCenter, tr("No images"));
        return;
    }
    const ImageStack& s = *stack_;
    const QRectF target = imageRect();
    // Smooth when the frame is shrunk; pixels stay visible as squares when enlarged.
    painter.setRenderHint(QPainter::SmoothPixmapTransform, target.width() < s.columns);
    painter.drawImage(target, frameImage());

    QStringList topLeft = seriesOverlayLines(s);
    QStringList topRight{tr("Frame %1/%2").arg(frame_ + 1).arg(s.frameCount())};
    if (s.frameTimeMs > 0.0) {
        topRight << tr("%1 ms").arg(s.frames[static_cast<std::size_t>(frame_)].timeMs, 0, 'f', 0);
    }
    if (cine_.isActive()) {
        topRight << tr("Cine %1 fps").arg(1000.0 / s.cineIntervalMs(), 0, 'g', 3);
    }
    QString bottomLeft = zoom_ != 1.0 ? tr("Zoom %1x").arg(zoom_, 0, 'f', 2) : QString();
    QString bottomRight =
        s.colour == StackColour::Grey
            ? tr("W %1  L %2").arg(window_.width, 0, 'g', 5).arg(window_.centre, 0, 'g', 5)
            : QString::fromStdString(s.photometric);
    const QRect inner = rect().adjusted(6, 4, -6, -4);
    painter.setPen(QColor(220, 220, 220));
    painter.drawText(inner, Qt::AlignTop | Qt::AlignLeft, topLeft.join(u'\n'));
    painter.drawText(inner, Qt::AlignTop | Qt::AlignRight, topRight.join(u'\n'));
    painter.drawText(inner, Qt::AlignBottom | Qt::AlignLeft, bottomLeft);
    painter.drawText(inner, Qt::AlignBottom | Qt::AlignRight, bottomRight);
    const StackFrame& f = s.frames[static_cast<std::size_t>(frame_)];
    if (f.hasPixelSpacing && target.width() > 0.0) {
        paintScaleBar(painter, rect(), s.columns * f.pixelSpacing.x / target.width());
    }
}

QImage StackView::image() const {
    QImage out(size(), QImage::Format_RGB32);
    QPainter painter(&out);
    paintTo(painter);
    return out;
}

void StackView::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    paintTo(painter);
}

void StackView::wheelEvent(QWheelEvent* event) {
    // One notch is 120; finer wheels add up until they make a whole notch.
    wheelRemainder_ += event->angleDelta().y();
    const int notches = wheelRemainder_ / 120;
    wheelRemainder_ -= notches * 120;
    if (notches != 0) {
        if (event->modifiers() & Qt::ControlModifier) {
            setZoom(zoom_ * std::pow(zoomStepFactor(), notches), event->position());
        } else {
            setFrame(frame_ - notches); // scrolling down (negative) goes forward
        }
    }
    event->accept();
}

double StackView::windowStep() const {
    if (!stack_) {
        return 1.0;
    }
    const auto [lo, hi] = stack_->greyRange();
    return std::max((hi - lo) / 1000.0, 0.01);
}

void StackView::mousePressEvent(QMouseEvent* event) {
    dragStart_ = event->position().toPoint();
    if (event->button() == Qt::RightButton && stack_ && stack_->colour == StackColour::Grey) {
        drag_ = Drag::Window;
        dragWindow_ = window_;
    } else if (event->button() == Qt::MiddleButton) {
        drag_ = Drag::Pan;
        dragPan_ = pan_;
    }
    event->accept();
}

void StackView::mouseMoveEvent(QMouseEvent* event) {
    const QPoint d = event->position().toPoint() - dragStart_;
    if (drag_ == Drag::Window) {
        const double step = windowStep();
        setWindow(
            {dragWindow_.centre + d.y() * step, std::max(dragWindow_.width + d.x() * step, step)});
    } else if (drag_ == Drag::Pan) {
        setPan(dragPan_ + QPointF(d));
    }
    event->accept();
}

void StackView::mouseReleaseEvent(QMouseEvent* event) {
    if ((event->button() == Qt::RightButton && drag_ == Drag::Window) ||
        (event->button() == Qt::MiddleButton && drag_ == Drag::Pan)) {
        mouseMoveEvent(event);
        drag_ = Drag::None;
    }
    event->accept();
}

void StackView::keyPressEvent(QKeyEvent* event) {
    switch (event->key()) {
    case Qt::Key_C:
        setCineRunning(!cine_.isActive());
        break;
    case Qt::Key_R:
        resetView();
        break;
    case Qt::Key_Down:
    case Qt::Key_PageDown:
        setFrame(frame_ + 1);
        break;
    case Qt::Key_Up:
    case Qt::Key_PageUp:
        setFrame(frame_ - 1);
        break;
    case Qt::Key_Home:
        setFrame(0);
        break;
    case Qt::Key_End:
        setFrame(stack_ ? stack_->frameCount() - 1 : 0);
        break;
    default:
        QWidget::keyPressEvent(event);
        return;
    }
    event->accept();
}

} // namespace lucent
