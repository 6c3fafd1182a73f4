#include "ui/segmentation/SliceSegments.h"

#include <algorithm>
#include <cmath>

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>

#include "core/segmentation/SegmentEffects.h"
#include "ui/mpr/SliceView.h"
#include "ui/segmentation/SegmentEditor.h"
#include "ui/segmentation/SegmentationSession.h"
#include "ui/viewports/Viewport.h"

namespace lucent {
namespace {

bool samePlane(const SlicePlane& a, const SlicePlane& b) {
    return a.centre == b.centre && a.u == b.u && a.v == b.v && a.pixelSize == b.pixelSize &&
           a.width == b.width && a.height == b.height;
}

QRgb premultiplied(const std::array<std::uint8_t, 3>& c, double alpha) {
    const int a = std::clamp(static_cast<int>(std::lround(alpha * 255.0)), 0, 255);
    return qRgba(c[0] * a / 255, c[1] * a / 255, c[2] * a / 255, a);
}

} // namespace

SliceSegments::SliceSegments(SegmentEditor* editor, SliceView* view)
    : QWidget(view), editor_(editor), view_(view) {
    setAttribute(Qt::WA_TransparentForMouseEvents);
    setAttribute(Qt::WA_NoSystemBackground);
    setGeometry(view->rect());
    view->installEventFilter(this);
    show();
}

SegmentationSession* SliceSegments::session(bool make) const {
    const std::shared_ptr<const Volume>& volume = view_->volume();
    if (!volume || volume->empty()) {
        return nullptr;
    }
    return make ? editor_->sessions()->sessionFor(volume) : editor_->sessions()->find(*volume);
}

void SliceSegments::cancel() {
    if (stroke_) {
        stroke_->session->setPreview(std::nullopt);
        stroke_.reset();
    }
    outline_.clear();
    leftDown_ = false;
    update();
}

SliceSlab SliceSegments::slabOfView() const {
    const glm::dvec3 normal = view_->plane().normal();
    return {normal, 0.5 * sliceStep(view_->volume()->geometry(), normal)};
}

SegmentationSession* SliceSegments::editable() {
    // The press makes the viewport active, as a press on the view itself does.
    for (QObject* up = view_->parent(); up != nullptr; up = up->parent()) {
        if (auto* viewport = qobject_cast<Viewport*>(up)) {
            emit viewport->pressed();
            break;
        }
    }
    SegmentationSession* s = session(true);
    if (s == nullptr) {
        return nullptr;
    }
    if (s->segmentation().segments().empty()) {
        s->addSegment();
    } else if (s->active() == nullptr) {
        editor_->say(tr("Choose a segment in the Segments panel first"));
        return nullptr;
    }
    if (s->active()->locked) {
        editor_->say(tr("%1 is locked").arg(QString::fromStdString(s->active()->name)));
        return nullptr;
    }
    return s;
}

bool SliceSegments::mousePress(const QPointF& pos) {
    const SegmentTool tool = editor_->tool();
    SegmentationSession* s = editable();
    if (s == nullptr) {
        return true; // the tool keeps the button: no crosshair jump
    }
    const glm::dvec3 point = view_->plane().pointAt(pos.x(), pos.y());
    if (tool == SegmentTool::Paint || tool == SegmentTool::Erase) {
        Stroke stroke;
        stroke.session = s;
        stroke.segment = s->activeSegment();
        stroke.mask = std::make_shared<SegmentMask>(*s->active()->mask);
        stroke.erase = tool == SegmentTool::Erase;
        if (!editor_->brushSphere()) {
            stroke.slab = slabOfView();
        }
        stroke.last = point;
        stroke_ = std::move(stroke);
        paintBrush(*stroke_->mask, s->segmentation().geometry(), point, editor_->brushRadiusMm(),
                   !stroke_->erase, stroke_->slab);
        s->setPreview(SegmentationSession::Preview{stroke_->segment, stroke_->mask});
    } else if (tool == SegmentTool::Draw) {
        outline_.push_back(point);
        outlineDragged_ = false;
        update();
    } else if (tool == SegmentTool::PickIsland) {
        const glm::ivec3 voxel(glm::round(s->segmentation().geometry().toIndex(point)));
        editor_->applyToActive(tr("Keep the island clicked"),
                               [voxel](const SegmentMask& m, const SegmentationSession&) {
                                   return keepIslandAt(m, voxel);
                               });
    }
    return true;
}

void SliceSegments::brushTo(const glm::dvec3& point) {
    const VolumeGeometry& grid = stroke_->session->segmentation().geometry();
    const double radius = editor_->brushRadiusMm();
    // Spheres close enough together that the stroke has no gaps.
    const double step =
        std::max(0.25 * radius, 0.5 * std::min({grid.spacing.x, grid.spacing.y, grid.spacing.z}));
    const double length = glm::length(point - stroke_->last);
    const int steps = std::max(1, static_cast<int>(std::ceil(length / step)));
    for (int n = 1; n <= steps; ++n) {
        const glm::dvec3 at = stroke_->last + (point - stroke_->last) * (double(n) / steps);
        paintBrush(*stroke_->mask, grid, at, radius, !stroke_->erase, stroke_->slab);
    }
    stroke_->last = point;
    stroke_->session->touchPreview();
}

void SliceSegments::mouseDrag(const QPointF& pos) {
    const glm::dvec3 point = view_->plane().pointAt(pos.x(), pos.y());
    if (stroke_) {
        brushTo(point);
    } else if (editor_->tool() == SegmentTool::Draw && !outline_.empty()) {
        // Freehand: a point every couple of pixels.
        const glm::dvec2 last = view_->plane().pixelOf(outline_.back());
        if (glm::length(last - glm::dvec2(pos.x(), pos.y())) >= 2.0) {
            outline_.push_back(point);
            outlineDragged_ = true;
            update();
        }
    }
}

void SliceSegments::mouseRelease(const QPointF& pos) {
    if (stroke_) {
        mouseDrag(pos);
        Stroke stroke = std::move(*stroke_);
        stroke_.reset();
        stroke.session->setPreview(std::nullopt);
        stroke.session->apply(stroke.segment, std::move(*stroke.mask),
                              stroke.erase ? tr("Erase") : tr("Paint"));
    } else if (editor_->tool() == SegmentTool::Draw && outlineDragged_) {
        mouseDrag(pos);
        finishOutline(); // a dragged outline ends with the button; clicks end with a double-click
    }
}

void SliceSegments::finishOutline() {
    std::vector<glm::dvec3> outline = std::move(outline_);
    outline_.clear();
    update();
    if (outline.size() < 3) {
        return;
    }
    const SliceSlab slab = slabOfView();
    editor_->applyToActive(tr("Draw"), [&](const SegmentMask& m, const SegmentationSession& s) {
        SegmentMask out = m;
        fillOutline(out, s.segmentation().geometry(), outline, slab);
        return out;
    });
}

bool SliceSegments::eventFilter(QObject* watched, QEvent* event) {
    if (watched != view_) {
        return QWidget::eventFilter(watched, event);
    }
    if (event->type() == QEvent::Resize) {
        setGeometry(view_->rect());
        return false;
    }
    const SegmentTool tool = editor_->tool();
    const bool usable = tool != SegmentTool::None && view_->volume() && !view_->volume()->empty();
    switch (event->type()) {
    case QEvent::MouseButtonPress:
    case QEvent::MouseButtonDblClick: {
        auto* mouse = static_cast<QMouseEvent*>(event);
        if (!usable || mouse->button() != Qt::LeftButton ||
            (mouse->modifiers() & Qt::ShiftModifier)) {
            return false;
        }
        if (event->type() == QEvent::MouseButtonDblClick) {
            if (tool == SegmentTool::Draw) {
                finishOutline();
            }
            return true;
        }
        leftDown_ = true;
        return mousePress(mouse->position());
    }
    case QEvent::MouseMove: {
        auto* mouse = static_cast<QMouseEvent*>(event);
        hover_ = mouse->position();
        // Only what follows the cursor repaints: the brush, the outline's next edge.
        if (tool == SegmentTool::Paint || tool == SegmentTool::Erase || !outline_.empty()) {
            update();
        }
        if (usable && leftDown_ && (stroke_ || !outline_.empty())) {
            mouseDrag(mouse->position());
            return true;
        }
        return false;
    }
    case QEvent::MouseButtonRelease: {
        auto* mouse = static_cast<QMouseEvent*>(event);
        if (!usable || mouse->button() != Qt::LeftButton || !leftDown_) {
            return false;
        }
        leftDown_ = false;
        // A click of the draw tool adds a corner; its drag ends with the button.
        if (tool != SegmentTool::Draw || outlineDragged_) {
            mouseRelease(mouse->position());
        }
        return true;
    }
    case QEvent::Leave:
        hover_.reset();
        if (tool == SegmentTool::Paint || tool == SegmentTool::Erase) {
            update();
        }
        return false;
    case QEvent::KeyPress: {
        const int key = static_cast<QKeyEvent*>(event)->key();
        if (!outline_.empty() && (key == Qt::Key_Return || key == Qt::Key_Enter)) {
            finishOutline();
            return true;
        }
        if ((stroke_ || !outline_.empty()) && key == Qt::Key_Escape) {
            cancel();
            return true;
        }
        return false;
    }
    default:
        return false;
    }
}

void SliceSegments::renderOverlay(const SegmentationSession& session, const SlicePlane& plane) {
    const VolumeGeometry& grid = session.segmentation().geometry();
    const std::size_t pixels = static_cast<std::size_t>(plane.width) * plane.height;
    if (!samePlane(plane, indexedPlane_) || indexedDims_ != grid.dims ||
        voxelOfPixel_.size() != pixels) {
        // The plane is affine in index space: the nearest voxel of each pixel by steps.
        const glm::dvec3 origin = grid.toIndex(plane.pointAt(0, 0));
        const glm::dvec3 dx = grid.toIndex(plane.pointAt(1, 0)) - origin;
        const glm::dvec3 dy = grid.toIndex(plane.pointAt(0, 1)) - origin;
        voxelOfPixel_.assign(pixels, -1);
        for (int y = 0; y < plane.height; ++y) {
            for (int x = 0; x < plane.width; ++x) {
                const glm::ivec3 v(glm::floor(origin + dx * double(x) + dy * double(y) + 0.5));
                if (v.x >= 0 && v.y >= 0 && v.z >= 0 && v.x < grid.dims.x && v.y < grid.dims.y &&
                    v.z < grid.dims.z) {
                    voxelOfPixel_[std::size_t(y) * plane.width + x] = static_cast<std::int64_t>(
                        v.x + std::size_t(grid.dims.x) * (v.y + std::size_t(grid.dims.y) * v.z));
                }
            }
        }
        indexedPlane_ = plane;
        indexedDims_ = grid.dims;
    }
    overlay_ = QImage(plane.width, plane.height, QImage::Format_ARGB32_Premultiplied);
    overlay_.fill(Qt::transparent);
    const SegmentDisplay& display = editor_->display();
    const auto& preview = session.preview();
    std::vector<std::uint8_t> in(pixels);
    for (const Segment& segment : session.segmentation().segments()) {
        const bool previewed = preview && preview->segment == segment.id && preview->mask;
        if (!segment.visible && !previewed) {
            continue;
        }
        const SegmentMask& mask = previewed ? *preview->mask : *segment.mask;
        for (std::size_t p = 0; p < pixels; ++p) {
            in[p] = voxelOfPixel_[p] >= 0 && mask.get(std::size_t(voxelOfPixel_[p])) ? 1 : 0;
        }
        const QRgb fill = premultiplied(segment.colour, display.fillOpacity);
        const QRgb line = premultiplied(segment.colour, 1.0);
        for (int y = 0; y < plane.height; ++y) {
            auto* row = reinterpret_cast<QRgb*>(overlay_.scanLine(y));
            for (int x = 0; x < plane.width; ++x) {
                const std::size_t p = std::size_t(y) * plane.width + x;
                if (in[p] == 0) {
                    continue;
                }
                const bool edge = x == 0 || y == 0 || x + 1 == plane.width ||
                                  y + 1 == plane.height || !in[p - 1] || !in[p + 1] ||
                                  !in[p - plane.width] || !in[p + plane.width];
                if ((display.outline || previewed) && edge) {
                    row[x] = line;
                } else if (display.fill) {
                    row[x] = fill;
                }
            }
        }
    }
}

void SliceSegments::paintDecorations(QPainter& painter, const SlicePlane& plane) {
    const SegmentTool tool = editor_->tool();
    painter.setRenderHint(QPainter::Antialiasing);
    if (hover_ && (tool == SegmentTool::Paint || tool == SegmentTool::Erase)) {
        const double r = editor_->brushRadiusMm() / plane.pixelSize;
        painter.setPen(
            QPen(tool == SegmentTool::Erase ? QColor(255, 120, 120) : QColor(Qt::yellow), 1.0));
        painter.setBrush(Qt::NoBrush);
        painter.drawEllipse(*hover_, r, r);
    }
    if (!outline_.empty()) {
        QPolygonF polygon;
        for (const glm::dvec3& p : outline_) {
            const glm::dvec2 at = plane.pixelOf(p);
            polygon << QPointF(at.x, at.y);
        }
        if (hover_ && !outlineDragged_) {
            polygon << *hover_;
        }
        painter.setPen(QPen(QColor(Qt::yellow), 1.5));
        painter.drawPolyline(polygon);
    }
}

void SliceSegments::paintEvent(QPaintEvent*) {
    const SlicePlane plane = view_->plane();
    if (!view_->volume() || view_->volume()->empty() || plane.width <= 0 || plane.height <= 0) {
        overlay_ = QImage();
        return;
    }
    QPainter painter(this);
    if (const SegmentationSession* s = session(false)) {
        renderOverlay(*s, plane);
        painter.drawImage(QRectF(0, 0, plane.width, plane.height), overlay_);
    } else {
        overlay_ = QImage();
    }
    paintDecorations(painter, plane);
}

} // namespace lucent
