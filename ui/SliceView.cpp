#include "ui/SliceView.h"

#include <algorithm>
#include <cmath>

#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>

#include "ui/MprCursor.h"

namespace lucent {

namespace {

int dominantAxis(const glm::dvec3& d) {
    const glm::dvec3 a = glm::abs(d);
    return a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
}

// Each orientation has its colour; a crosshair line shows the plane of that colour.
QColor orientationColour(Orientation orientation) {
    switch (orientation) {
    case Orientation::Axial:
        return {230, 80, 80};
    case Orientation::Coronal:
        return {90, 200, 90};
    case Orientation::Sagittal:
        return {230, 200, 60};
    }
    return Qt::white;
}

// The standard orientation whose plane is normal to the patient axis closest to d.
Orientation planeNormalTo(const glm::dvec3& d) {
    switch (dominantAxis(d)) {
    case 0:
        return Orientation::Sagittal;
    case 1:
        return Orientation::Coronal;
    default:
        return Orientation::Axial;
    }
}

bool samePlane(const SlicePlane& a, const SlicePlane& b) {
    return a.centre == b.centre && a.u == b.u && a.v == b.v && a.pixelSize == b.pixelSize &&
           a.width == b.width && a.height == b.height && a.slabThickness == b.slabThickness &&
           a.slabMode == b.slabMode;
}

} // namespace

SliceView::SliceView(Orientation orientation, MprCursor* cursor, QWidget* parent)
    : QWidget(parent), orientation_(orientation), cursor_(cursor) {
    setAttribute(Qt::WA_OpaquePaintEvent);
    setFocusPolicy(Qt::WheelFocus);
    setContextMenuPolicy(Qt::PreventContextMenu);
    connect(cursor_, &MprCursor::pointChanged, this, qOverload<>(&QWidget::update));
    connect(cursor_, &MprCursor::windowChanged, this, qOverload<>(&QWidget::update));
}

void SliceView::setVolume(std::shared_ptr<const Volume> volume) {
    volume_ = std::move(volume);
    samplesValid_ = false;
    imageValid_ = false;
    samples_.clear();
    update();
}

SlicePlane SliceView::plane() const {
    if (!volume_ || volume_->empty()) {
        return standardPlane({}, orientation_, cursor_->point(), width(), height());
    }
    const VolumeGeometry& g = volume_->geometry();
    const glm::dvec3 mid = volumeCentre(g);
    SlicePlane p = standardPlane(g, orientation_, mid, width(), height());
    // Through the crosshair point along the normal, centred on the volume within the plane.
    const glm::dvec3 n = p.normal();
    p.centre = mid + n * glm::dot(cursor_->point() - mid, n);
    return p;
}

double SliceView::sliceStep() const {
    if (!volume_ || volume_->empty()) {
        return 1.0;
    }
    return lucent::sliceStep(volume_->geometry(), plane().normal());
}

glm::dvec3 SliceView::positiveNormal() const {
    const glm::dvec3 n = plane().normal();
    return n[dominantAxis(n)] < 0.0 ? -n : n;
}

double SliceView::slicePosition() const {
    return glm::dot(cursor_->point(), positiveNormal());
}

void SliceView::moveSlices(double slices) {
    if (!volume_ || volume_->empty()) {
        return;
    }
    const VolumeGeometry& g = volume_->geometry();
    const glm::dvec3 n = plane().normal();
    const glm::dvec3 mid = volumeCentre(g);
    // Keep the plane within the volume's voxel-centre box along the normal.
    double reach = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 ijk((corner & 1) ? g.dims.x - 1 : 0, (corner & 2) ? g.dims.y - 1 : 0,
                             (corner & 4) ? g.dims.z - 1 : 0);
        reach = std::max(reach, std::abs(glm::dot(g.toPatient(ijk) - mid, n)));
    }
    const glm::dvec3 point = cursor_->point();
    const double now = glm::dot(point - mid, n);
    const double wanted = std::clamp(now + slices * sliceStep(), -reach, reach);
    cursor_->setPoint(point + n * (wanted - now));
}

void SliceView::setCrosshair(const QPointF& pos) {
    if (!volume_ || volume_->empty()) {
        return;
    }
    cursor_->setPoint(plane().pointAt(pos.x(), pos.y()));
}

QImage SliceView::image() {
    const SlicePlane p = plane();
    if (!volume_ || volume_->empty() || p.width <= 0 || p.height <= 0) {
        return {};
    }
    if (!samplesValid_ || !samePlane(p, sampledPlane_)) {
        samples_ = sampleImage(*volume_, p);
        sampledPlane_ = p;
        samplesValid_ = true;
        imageValid_ = false;
    }
    const double center = cursor_->windowCenter();
    const double width = cursor_->windowWidth();
    if (!imageValid_ || center != imageCenter_ || width != imageWidth_ ||
        image_.size() != QSize(p.width, p.height)) {
        image_ = QImage(p.width, p.height, QImage::Format_Grayscale8);
        for (int y = 0; y < p.height; ++y) {
            uchar* line = image_.scanLine(y);
            const float* row = samples_.data() + static_cast<std::size_t>(y) * p.width;
            for (int x = 0; x < p.width; ++x) {
                line[x] = windowToGrey(row[x], center, width);
            }
        }
        imageCenter_ = center;
        imageWidth_ = width;
        imageValid_ = true;
    }
    return image_;
}

void SliceView::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    painter.fillRect(rect(), Qt::black);
    if (!volume_ || volume_->empty()) {
        painter.setPen(QColor(160, 160, 160));
        painter.drawText(rect(), Qt::AlignCenter,
                         QStringLiteral("%1\nNo volume (File > Open)")
                             .arg(QString::fromLatin1(orientationName(orientation_))));
        return;
    }
    const SlicePlane p = plane();
    painter.drawImage(0, 0, image());
    paintOverlay(painter, p);
}

void SliceView::paintOverlay(QPainter& painter, const SlicePlane& p) {
    // Crosshair: the line along u is the plane normal to v, the line along v the one normal to u.
    const glm::dvec2 c = p.pixelOf(cursor_->point());
    const double cx = std::floor(c.x) + 0.5;
    const double cy = std::floor(c.y) + 0.5;
    const double gap = 12.0;
    QColor horizontal = orientationColour(planeNormalTo(p.v));
    QColor vertical = orientationColour(planeNormalTo(p.u));
    horizontal.setAlpha(170);
    vertical.setAlpha(170);
    painter.setPen(QPen(horizontal, 1.0));
    painter.drawLine(QPointF(0.0, cy), QPointF(cx - gap, cy));
    painter.drawLine(QPointF(cx + gap, cy), QPointF(width(), cy));
    painter.setPen(QPen(vertical, 1.0));
    painter.drawLine(QPointF(cx, 0.0), QPointF(cx, cy - gap));
    painter.drawLine(QPointF(cx, cy + gap), QPointF(cx, height()));

    // A frame in the view's own colour.
    painter.setPen(QPen(orientationColour(orientation_), 1.0));
    painter.drawRect(QRectF(0.5, 0.5, width() - 1.0, height() - 1.0));

    // Orientation letters at the middle of each edge.
    QFont font = painter.font();
    font.setBold(true);
    painter.setFont(font);
    painter.setPen(QColor(255, 210, 120));
    const QRect inner = rect().adjusted(6, 4, -6, -4);
    auto label = [](const glm::dvec3& d) { return QString::fromStdString(directionLabel(d)); };
    painter.drawText(inner, Qt::AlignLeft | Qt::AlignVCenter, label(-p.u));
    painter.drawText(inner, Qt::AlignRight | Qt::AlignVCenter, label(p.u));
    painter.drawText(inner, Qt::AlignTop | Qt::AlignHCenter, label(-p.v));
    painter.drawText(inner, Qt::AlignBottom | Qt::AlignHCenter, label(p.v));

    // Name, slice and window in the corners.
    font.setBold(false);
    painter.setFont(font);
    painter.setPen(QColor(220, 220, 220));
    painter.drawText(inner, Qt::AlignTop | Qt::AlignLeft,
                     QString::fromLatin1(orientationName(orientation_)));
    const glm::dvec3 n = positiveNormal();
    const char axis = "xyz"[dominantAxis(n)];
    QString where = QStringLiteral("%1 = %2 mm").arg(QChar(axis)).arg(slicePosition(), 0, 'f', 1);
    const VolumeGeometry& g = volume_->geometry();
    for (int a = 0; a < 3; ++a) {
        if (std::abs(glm::dot(glm::dvec3(g.direction[a]), n)) > 0.999) {
            const long index = std::lround(g.toIndex(cursor_->point())[a]);
            where = QStringLiteral("Slice %1/%2  ").arg(index + 1).arg(g.dims[a]) + where;
        }
    }
    painter.drawText(inner, Qt::AlignBottom | Qt::AlignLeft, where);
    painter.drawText(inner, Qt::AlignBottom | Qt::AlignRight,
                     QStringLiteral("W %1  L %2")
                         .arg(cursor_->windowWidth(), 0, 'g', 5)
                         .arg(cursor_->windowCenter(), 0, 'g', 5));
}

void SliceView::wheelEvent(QWheelEvent* event) {
    // One notch is 120; finer wheels add up until they make a whole slice.
    wheelRemainder_ += event->angleDelta().y();
    const int slices = wheelRemainder_ / 120;
    wheelRemainder_ -= slices * 120;
    if (slices != 0) {
        moveSlices(slices);
    }
    event->accept();
}

void SliceView::mousePressEvent(QMouseEvent* event) {
    dragStart_ = event->position().toPoint();
    if (event->button() == Qt::LeftButton) {
        drag_ = Drag::Crosshair;
        setCrosshair(event->position());
    } else if (event->button() == Qt::RightButton) {
        drag_ = Drag::Window;
        dragCenter_ = cursor_->windowCenter();
        dragWidth_ = cursor_->windowWidth();
    }
    event->accept();
}

void SliceView::mouseMoveEvent(QMouseEvent* event) {
    if (drag_ == Drag::Crosshair) {
        setCrosshair(event->position());
    } else if (drag_ == Drag::Window) {
        const QPoint d = event->position().toPoint() - dragStart_;
        const double step = cursor_->windowStep();
        cursor_->setWindow(dragCenter_ + d.y() * step, dragWidth_ + d.x() * step);
    }
    event->accept();
}

void SliceView::mouseReleaseEvent(QMouseEvent* event) {
    if ((drag_ == Drag::Crosshair && event->button() == Qt::LeftButton) ||
        (drag_ == Drag::Window && event->button() == Qt::RightButton)) {
        mouseMoveEvent(event);
        drag_ = Drag::None;
    }
    event->accept();
}

} // namespace lucent
