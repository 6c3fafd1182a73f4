#include "ui/mpr/SliceView.h"

#include <algorithm>
#include <cmath>

#include <QMouseEvent>
#include <QPainter>
#include <QTimer>
#include <QWheelEvent>

#include <glm/gtc/matrix_transform.hpp>

#include "core/mpr/CrosshairSlice.h"
#include "ui/mpr/DevicePlane.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SeriesMeasurements.h"
#include "ui/mpr/SliceOverlay.h"

namespace lucent {

namespace {

int dominantAxis(const glm::dvec3& d) {
    const glm::dvec3 a = glm::abs(d);
    return a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
}

bool samePlane(const SlicePlane& a, const SlicePlane& b) {
    return a.centre == b.centre && a.u == b.u && a.v == b.v && a.pixelSize == b.pixelSize &&
           a.width == b.width && a.height == b.height && a.slabThickness == b.slabThickness &&
           a.slabMode == b.slabMode;
}

constexpr int kClickSlop = 3; // pixels a press may move and still count as a click

} // namespace

SliceView::SliceView(Orientation orientation, MprCursor* cursor, QWidget* parent)
    : QWidget(parent), orientation_(orientation), cursor_(cursor), cine_(new QTimer(this)) {
    setAttribute(Qt::WA_OpaquePaintEvent);
    setFocusPolicy(Qt::WheelFocus);
    setMouseTracking(true);
    // The menu opens on a right-click without a drag (right-drag is window/level).
    setContextMenuPolicy(Qt::PreventContextMenu);
    connect(cursor_, &MprCursor::pointChanged, this, qOverload<>(&QWidget::update));
    connect(cursor_, &MprCursor::windowChanged, this, qOverload<>(&QWidget::update));
    connect(cursor_, &MprCursor::rotationChanged, this, qOverload<>(&QWidget::update));
    cine_->setInterval(66); // about 15 slices a second
    connect(cine_, &QTimer::timeout, this, &SliceView::nextCineFrame);
}

void SliceView::setVolume(std::shared_ptr<const Volume> volume) {
    volume_ = std::move(volume);
    samplesValid_ = false;
    imageValid_ = false;
    samples_.clear();
    measure_.cancel();
    update();
}

SlicePlane SliceView::plane() const {
    const bool none = !volume_ || volume_->empty();
    SlicePlane p = crosshairPlane(none ? VolumeGeometry{} : volume_->geometry(), orientation_,
                                  cursor_->point(), width(), height(),
                                  cursor_->rotation(orientation_), zoom_, pan_);
    p.slabThickness = slabThickness_;
    p.slabMode = slabMode_;
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

bool SliceView::moveSlices(double slices) {
    if (!volume_ || volume_->empty()) {
        return false;
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
    return std::abs(wanted - now) > 1e-9;
}

void SliceView::setCrosshair(const QPointF& pos) {
    if (!volume_ || volume_->empty()) {
        return;
    }
    cursor_->setPoint(plane().pointAt(pos.x(), pos.y()));
}

void SliceView::setZoom(double zoom, const QPointF& anchor) {
    zoom = std::clamp(zoom, 0.05, 64.0);
    const SlicePlane before = plane();
    // The plane point under the anchor stays: the centre moves by the anchor's offset
    // times the change of pixel size.
    const double oldSize = before.pixelSize;
    const double newSize = oldSize * zoom_ / zoom;
    pan_.x += (anchor.x() - 0.5 * (before.width - 1)) * (oldSize - newSize);
    pan_.y += (anchor.y() - 0.5 * (before.height - 1)) * (oldSize - newSize);
    zoom_ = zoom;
    update();
    emit zoomPanChanged();
}

void SliceView::setPan(const glm::dvec2& pan) {
    setZoomAndPan(zoom_, pan);
}

void SliceView::setZoomAndPan(double zoom, const glm::dvec2& pan) {
    zoom = std::clamp(zoom, 0.05, 64.0);
    if (zoom == zoom_ && pan == pan_) {
        return;
    }
    zoom_ = zoom;
    pan_ = pan;
    update();
    emit zoomPanChanged();
}

void SliceView::resetZoomAndPan() {
    setZoomAndPan(1.0, glm::dvec2(0.0));
}

void SliceView::setReferencePlanes(std::vector<ReferencePlane> planes) {
    references_ = std::move(planes);
    update();
}

void SliceView::setSlab(double thicknessMm, SlabMode mode) {
    slabThickness_ = std::max(0.0, thicknessMm);
    slabMode_ = mode;
    if (slabThickness_ > 0.0) {
        lastSlabThickness_ = slabThickness_;
    }
    update();
}

void SliceView::setTool(Tool tool) {
    const bool changed = tool != tool_;
    tool_ = tool;
    measure_.cancel();
    path_.clear();
    setCursor(tool == Tool::Crosshair ? Qt::ArrowCursor : Qt::CrossCursor);
    // Quick clicks of a tool are points (or the end of a path), not a maximize.
    setProperty("keepsDoubleClick", tool != Tool::Crosshair);
    update();
    if (changed) {
        emit toolChanged(tool);
    }
}

double SliceView::measurementTolerance() const {
    return 0.5 * sliceStep() + 0.5 * slabThickness_;
}

QImage SliceView::image() {
    const SlicePlane logical = plane();
    if (!volume_ || volume_->empty() || logical.width <= 0 || logical.height <= 0) {
        return {};
    }
    // At device pixels: sharp on a high-DPI screen, drawn at the widget's logical size.
    const double ratio = std::max(1.0, devicePixelRatioF());
    const SlicePlane p = devicePlane(logical, ratio);
    if (!samplesValid_ || !samePlane(p, sampledPlane_)) {
        samples_ = sampleImage(*volume_, p);
        sampledPlane_ = p;
        samplesValid_ = true;
        imageValid_ = false;
    }
    const double center = cursor_->windowCenter();
    const double width = cursor_->windowWidth();
    const bool inverted = cursor_->invertedGrey();
    if (!imageValid_ || center != imageCenter_ || width != imageWidth_ ||
        inverted != imageInverted_ || image_.size() != QSize(p.width, p.height) ||
        image_.devicePixelRatio() != ratio) {
        std::vector<std::uint8_t> grey = windowedGrey(samples_, center, width);
        if (inverted) {
            for (std::uint8_t& g : grey) {
                g = static_cast<std::uint8_t>(255 - g);
            }
        }
        image_ = QImage(p.width, p.height, QImage::Format_Grayscale8);
        for (int y = 0; y < p.height; ++y) {
            std::copy_n(grey.data() + static_cast<std::size_t>(y) * p.width, p.width,
                        image_.scanLine(y));
        }
        image_.setDevicePixelRatio(ratio);
        imageCenter_ = center;
        imageWidth_ = width;
        imageInverted_ = inverted;
        imageValid_ = true;
    }
    return image_;
}

double SliceView::valueAt(const QPointF& pos) {
    if (image().isNull()) {
        return std::nan("");
    }
    const QPoint device = devicePixelAt(pos, devicePixelRatioF());
    const int x = device.x();
    const int y = device.y();
    if (x < 0 || y < 0 || x >= sampledPlane_.width || y >= sampledPlane_.height) {
        return std::nan("");
    }
    return samples_[static_cast<std::size_t>(y) * sampledPlane_.width + x];
}

void SliceView::setFusionLayer(std::optional<FusionLayer> layer) {
    fusion_.setLayer(std::move(layer));
    update();
}

void SliceView::setFusionStyle(const FusionStyle& style) {
    fusion_.setStyle(style);
    update();
}

QImage SliceView::fusedImage() {
    const QImage grey = image();
    if (!fusion_.active() || grey.isNull()) {
        return grey;
    }
    return fusion_.apply(grey, sampledPlane_);
}

double SliceView::overlayValueAt(const QPointF& pos) {
    if (fusedImage().isNull()) {
        return std::nan("");
    }
    const QPoint device = devicePixelAt(pos, devicePixelRatioF());
    return fusion_.valueAt(device.x(), device.y());
}

QString SliceView::sliceText() const {
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
    return where;
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
    painter.drawImage(0, 0, fusedImage());

    SliceOverlay overlay;
    overlay.orientation = orientation_;
    overlay.plane = p;
    overlay.crosshair = cursor_->point();
    for (const Orientation o : {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
        overlay.normals[static_cast<std::size_t>(o)] = cursor_->planeNormal(o);
    }
    overlay.topLeft << QString::fromLatin1(orientationName(orientation_));
    if (cursor_->rotation(orientation_) != glm::dmat3(1.0)) {
        overlay.topLeft.back() += QStringLiteral(" (oblique)");
    }
    if (slabThickness_ > 0.0) {
        const char* modes[] = {"MIP", "MinIP", "Average"};
        overlay.topLeft << QStringLiteral("%1 %2 mm")
                               .arg(QString::fromLatin1(modes[static_cast<int>(slabMode_)]))
                               .arg(slabThickness_, 0, 'g', 4);
    }
    if (zoom_ != 1.0) {
        overlay.topLeft << QStringLiteral("Zoom %1x").arg(zoom_, 0, 'f', 2);
    }
    if (cine_->isActive()) {
        overlay.topLeft << QStringLiteral("Cine");
    }
    overlay.topRight = seriesOverlayLines(*volume_);
    overlay.bottomLeft = sliceText();
    overlay.bottomRight = QStringLiteral("W %1  L %2")
                              .arg(cursor_->windowWidth(), 0, 'g', 5)
                              .arg(cursor_->windowCenter(), 0, 'g', 5);
    paintSliceOverlay(painter, rect(), overlay);
    paintReferenceLines(painter, rect(), p, references_);
    measure_.paint(painter, p, measurementTolerance());
    if (fusion_.active()) {
        static const std::vector<Measurement> kNone;
        fusion_.paint(painter, rect(), p,
                      measurements() != nullptr ? measurements()->measurements() : kNone,
                      measurementTolerance());
    }
    paintCurvedPath(painter, p, path_);
}

void SliceView::finishPath() {
    if (path_.size() >= 2) {
        const std::vector<glm::dvec3> points = std::move(path_);
        emit curvedPathDrawn(points, plane().normal());
    }
    setTool(Tool::Crosshair);
}

void SliceView::mouseDoubleClickEvent(QMouseEvent* event) {
    if (tool_ == Tool::CurvedPath && event->button() == Qt::LeftButton) {
        finishPath(); // the double-click's first press added its point
        event->accept();
        return;
    }
    QWidget::mouseDoubleClickEvent(event);
}

void SliceView::wheelEvent(QWheelEvent* event) {
    // One notch is 120; finer wheels add up until they make a whole notch.
    wheelRemainder_ += event->angleDelta().y();
    const int notches = wheelRemainder_ / 120;
    wheelRemainder_ -= notches * 120;
    if (notches != 0) {
        if (event->modifiers() & Qt::ControlModifier) {
            setZoom(zoom_ * std::pow(zoomStepFactor(), notches), event->position());
        } else {
            moveSlices(notches);
        }
    }
    event->accept();
}

void SliceView::rotateOthers(const QPointF& pos) {
    const glm::dvec2 c = plane().pixelOf(cursor_->point());
    const double angle = std::atan2(pos.y() - c.y, pos.x() - c.x);
    // Screen angles grow from u towards v: a right-handed turn about n = u x v.
    const glm::dmat3 turn(
        glm::rotate(glm::dmat4(1.0), angle - dragAngle_, cursor_->planeNormal(orientation_)));
    for (const Orientation o : {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
        if (o != orientation_) {
            cursor_->setRotation(o, turn * dragRotations_[static_cast<std::size_t>(o)]);
        }
    }
}

void SliceView::mousePressEvent(QMouseEvent* event) {
    dragStart_ = event->position().toPoint();
    const bool canMeasure = volume_ && !volume_->empty();
    if (event->button() == Qt::LeftButton && (event->modifiers() & Qt::ShiftModifier)) {
        drag_ = Drag::Rotate;
        const glm::dvec2 c = plane().pixelOf(cursor_->point());
        dragAngle_ = std::atan2(event->position().y() - c.y, event->position().x() - c.x);
        for (const Orientation o :
             {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
            dragRotations_[static_cast<std::size_t>(o)] = cursor_->rotation(o);
        }
    } else if (event->button() == Qt::LeftButton && tool_ == Tool::CurvedPath && canMeasure) {
        path_.push_back(plane().pointAt(event->position().x(), event->position().y()));
        update();
    } else if (event->button() == Qt::LeftButton && canMeasure &&
               measure_.press(plane(), measurementTolerance(), event->position(),
                              sliceToolInfo(tool_).kind)) {
        drag_ = Drag::Measure;
        update();
    } else if (event->button() == Qt::LeftButton) {
        drag_ = Drag::Crosshair;
        setCrosshair(event->position());
    } else if (event->button() == Qt::RightButton) {
        drag_ = Drag::Window;
        dragCenter_ = cursor_->windowCenter();
        dragWidth_ = cursor_->windowWidth();
    } else if (event->button() == Qt::MiddleButton) {
        drag_ = Drag::Pan;
        dragPan_ = pan_;
    }
    event->accept();
}

void SliceView::mouseMoveEvent(QMouseEvent* event) {
    const QPoint d = event->position().toPoint() - dragStart_;
    if (drag_ == Drag::Crosshair) {
        setCrosshair(event->position());
    } else if (drag_ == Drag::Window) {
        const double step = cursor_->windowStep();
        cursor_->setWindow(dragCenter_ + d.y() * step, dragWidth_ + d.x() * step);
    } else if (drag_ == Drag::Pan) {
        // The image follows the mouse: the centre moves the other way.
        pan_ = dragPan_ - glm::dvec2(d.x(), d.y()) * plane().pixelSize;
        update();
        emit zoomPanChanged();
    } else if (drag_ == Drag::Rotate) {
        rotateOthers(event->position());
    } else if (measure_.busy()) {
        measure_.move(plane(), event->position());
        update();
    }
    event->accept();
}

void SliceView::mouseReleaseEvent(QMouseEvent* event) {
    const bool click = (event->position().toPoint() - dragStart_).manhattanLength() <= kClickSlop;
    const bool ends = (event->button() == Qt::RightButton && drag_ == Drag::Window) ||
                      (event->button() == Qt::MiddleButton && drag_ == Drag::Pan) ||
                      (event->button() == Qt::LeftButton && drag_ != Drag::Window &&
                       drag_ != Drag::Pan && drag_ != Drag::None);
    if (!ends) {
        event->accept();
        return;
    }
    if (drag_ == Drag::Measure) {
        measure_.release(plane(), event->position(), click);
        update();
    } else if (drag_ == Drag::Window && click) {
        cursor_->setWindow(dragCenter_, dragWidth_);
        showContextMenu(event->globalPosition().toPoint());
    } else {
        mouseMoveEvent(event);
    }
    drag_ = Drag::None;
    event->accept();
}

} // namespace lucent
