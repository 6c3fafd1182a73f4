#include "ui/segmentation/Scissors3d.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QWidget>

#include <cmath>

#include "core/scene/ViewFrame.h"
#include "core/segmentation/Segmentation.h"
#include "ui/volume/VolumeView.h"

namespace lucent {

// Draws the shape being drawn over the view (a child covering it, above the render surface,
// transparent to the mouse).
class ScissorsOverlay : public QWidget {
public:
    ScissorsOverlay(VolumeView* view, const Scissors3d& scissors)
        : QWidget(view), scissors_(scissors) {
        setAttribute(Qt::WA_TransparentForMouseEvents);
        setAttribute(Qt::WA_NoSystemBackground);
        setAttribute(Qt::WA_TranslucentBackground);
        hide();
    }

protected:
    void paintEvent(QPaintEvent*) override {
        const ScreenShape shape = scissors_.currentShape();
        QPainter painter(this);
        painter.setRenderHint(QPainter::Antialiasing, true);
        painter.setPen(QPen(QColor(255, 230, 80), 1.5, Qt::DashLine));
        painter.setBrush(QColor(255, 230, 80, 40));
        switch (shape.kind()) {
        case ScreenShape::Kind::Circle:
            painter.drawEllipse(QPointF(shape.centre().x, shape.centre().y), shape.radius(),
                                shape.radius());
            break;
        case ScreenShape::Kind::Rectangle: {
            const auto& c = shape.points();
            painter.drawRect(QRectF(QPointF(c[0].x, c[0].y), QPointF(c[1].x, c[1].y)));
            break;
        }
        case ScreenShape::Kind::Polygon: {
            QPolygonF outline;
            for (const glm::dvec2& p : shape.points()) {
                outline << QPointF(p.x, p.y);
            }
            painter.drawPolygon(outline);
            break;
        }
        }
    }

private:
    const Scissors3d& scissors_;
};

Scissors3d::Scissors3d(VolumeView* view, Segmentation* segmentation, std::uint32_t segment)
    : QObject(view), view_(view), watched_(view), watchedObject_(view), segmentation_(segmentation),
      segment_(segment), overlay_(std::make_unique<ScissorsOverlay>(view, *this)) {
    view->installEventFilter(this);
}

Scissors3d::~Scissors3d() {
    // isNull() and the QObject pointer: no cast to VolumeView, which may be going (this is
    // then deleted as its child, before the overlay, a later child).
    if (view_.isNull()) {
        (void)overlay_.release(); // the view took its children with it
    } else if (QObject* watched = watchedObject_.data()) {
        watched->removeEventFilter(this);
    }
}

void Scissors3d::setEnabled(bool enabled) {
    if (!enabled) {
        cancel();
    }
    enabled_ = enabled;
}

ScreenShape Scissors3d::currentShape() const {
    if (points_.empty()) {
        return ScreenShape::polygon({});
    }
    const glm::dvec2 first(points_.front().x(), points_.front().y());
    const glm::dvec2 last(points_.back().x(), points_.back().y());
    switch (shape_) {
    case Shape::Circle:
        return ScreenShape::circle(first, glm::length(last - first));
    case Shape::Rectangle:
        return ScreenShape::rectangle(first, last);
    case Shape::Freehand:
        break;
    }
    std::vector<glm::dvec2> outline;
    outline.reserve(points_.size());
    for (const QPointF& p : points_) {
        outline.emplace_back(p.x(), p.y());
    }
    return ScreenShape::polygon(std::move(outline));
}

void Scissors3d::cancel() {
    drawing_ = false;
    points_.clear();
    overlay_->hide();
}

bool Scissors3d::eventFilter(QObject* watched, QEvent* event) {
    if (!enabled_ || watched != watched_) {
        return false;
    }
    switch (event->type()) {
    case QEvent::MouseButtonPress: {
        auto* mouse = static_cast<QMouseEvent*>(event);
        if (mouse->button() != Qt::LeftButton || drawing_) {
            return drawing_;
        }
        drawing_ = true;
        points_ = {mouse->position()};
        overlay_->setGeometry(view_->rect());
        overlay_->show();
        overlay_->raise(); // above the render surface, which the view may have remade
        return true;
    }
    case QEvent::MouseMove: {
        if (!drawing_) {
            return false;
        }
        const QPointF p = static_cast<QMouseEvent*>(event)->position();
        if (shape_ == Shape::Freehand || points_.size() < 2) {
            points_.push_back(p);
        } else {
            points_.back() = p;
        }
        overlay_->update();
        return true;
    }
    case QEvent::MouseButtonRelease: {
        auto* mouse = static_cast<QMouseEvent*>(event);
        if (!drawing_ || mouse->button() != Qt::LeftButton) {
            return drawing_;
        }
        if (shape_ != Shape::Freehand && points_.size() < 2) {
            points_.push_back(mouse->position());
        } else if (shape_ != Shape::Freehand) {
            points_.back() = mouse->position();
        }
        finish();
        return true;
    }
    case QEvent::KeyPress:
        if (drawing_ && static_cast<QKeyEvent*>(event)->key() == Qt::Key_Escape) {
            cancel();
            return true;
        }
        return false;
    default:
        return false;
    }
}

void Scissors3d::finish() {
    const ScreenShape shape = currentShape();
    cancel();
    const auto& volume = view_->volume();
    const Segment* segment = segmentation_->find(segment_);
    if (!volume || !segment || !shape.enclosesArea()) {
        if (!volume || !segment) {
            emit refused(tr("Scissors: no volume or no segment to cut"));
        }
        return;
    }
    if (volume->dims() != segmentation_->geometry().dims) {
        emit refused(tr("Scissors: the segments lie on another grid than the 3D view's volume"));
        return;
    }
    // The view's frame at its size in widget pixels: the fractions, and so where each voxel
    // shows, are those of the frame rendered (its device pixels have the same aspect).
    const int w = std::max(1, view_->width()), h = std::max(1, view_->height());
    const ImageProjection projection =
        imageProjection(makeViewFrame(volume->geometry(), view_->camera(), w, h));
    const SegmentMask before = segment->mask ? *segment->mask : SegmentMask(volume->dims());
    const SegmentMask after =
        applyScissors(before, volume->geometry(), projection, glm::dvec2(w, h), shape, operation_);
    SegmentMask changed = after;
    changed.subtract(before);
    SegmentMask lost = before;
    lost.subtract(after);
    const std::size_t count = changed.count() + lost.count();
    if (count > 0 && !segmentation_->setMask(segment_, after, "Scissors")) {
        emit refused(tr("Scissors: the segment is locked"));
        return;
    }
    emit cut(count);
}

} // namespace lucent
