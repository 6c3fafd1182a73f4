#include "ui/mpr/SliceMeasurements.h"

#include <algorithm>
#include <cmath>

#include <QLineEdit>
#include <QPainter>
#include <QShortcut>
#include <QWidget>

#include "core/measure/MeasurementGeometry.h"
#include "ui/mpr/MeasurementPainter.h"

namespace lucent {

namespace {

glm::dvec3 pointAt(const SlicePlane& plane, const QPointF& pos) {
    return plane.pointAt(pos.x(), pos.y());
}

} // namespace

void SliceMeasurements::setDocument(SeriesMeasurements* document) {
    cancel();
    document_ = document;
}

std::optional<SliceMeasurements::Grab>
SliceMeasurements::handleAt(const SlicePlane& plane, double tolerance, const QPointF& pos) const {
    std::optional<Grab> best;
    double bestDistance = kHandleGrabPixels;
    const std::vector<Measurement>& all = document_->measurements();
    // The last drawn is on top: it wins a tie.
    for (auto m = all.rbegin(); m != all.rend(); ++m) {
        if (m->readOnly || !measurementInPlane(*m, plane, tolerance)) {
            continue;
        }
        for (std::size_t i = 0; i < m->points.size(); ++i) {
            const glm::dvec2 px = plane.pixelOf(m->points[i]) + 0.5;
            const double d = std::hypot(px.x - pos.x(), px.y - pos.y());
            if (d < bestDistance) {
                bestDistance = d;
                best = Grab{m->id, static_cast<int>(i), *m, false};
            }
        }
    }
    return best;
}

bool SliceMeasurements::press(const SlicePlane& plane, double tolerance, const QPointF& pos,
                              std::optional<MeasurementKind> kind) {
    if (document_ == nullptr) {
        return false;
    }
    if (draft_.active()) {
        draft_.press(draft_.kind(), plane, pointAt(plane, pos));
        return true;
    }
    grab_ = handleAt(plane, tolerance, pos);
    if (grab_) {
        document_->select(grab_->id);
        return true;
    }
    if (!kind) {
        return false;
    }
    draft_.press(*kind, plane, pointAt(plane, pos));
    return true;
}

void SliceMeasurements::move(const SlicePlane& plane, const QPointF& pos) {
    if (grab_) {
        grab_->moved =
            moveMeasurementPoint(grab_->edited, grab_->index, pointAt(plane, pos)) || grab_->moved;
    } else if (draft_.active()) {
        draft_.hover(pointAt(plane, pos));
    }
}

void SliceMeasurements::release(const SlicePlane& plane, const QPointF& pos, bool click) {
    if (grab_) {
        const Grab grab = std::move(*grab_);
        grab_.reset();
        if (grab.moved && document_ != nullptr) {
            document_->change(grab.edited);
        }
        return;
    }
    if (!draft_.active() || !draft_.release(pointAt(plane, pos), click) || document_ == nullptr) {
        return;
    }
    Measurement m = draft_.result();
    if (m.kind == MeasurementKind::Arrow) {
        askArrowText(plane, std::move(m));
    } else {
        document_->add(std::move(m));
    }
}

void SliceMeasurements::askArrowText(const SlicePlane& plane, Measurement arrow) {
    const glm::dvec2 tail = plane.pixelOf(arrow.points[0]);
    arrow_ = std::move(arrow);
    auto* editor = new QLineEdit(view_);
    editor->setObjectName(QStringLiteral("arrowTextEditor"));
    editor->setPlaceholderText(QObject::tr("Arrow text"));
    editor->resize(160, editor->sizeHint().height());
    editor->move(std::clamp(int(tail.x) + 6, 0, std::max(0, view_->width() - editor->width())),
                 std::clamp(int(tail.y) + 6, 0, std::max(0, view_->height() - editor->height())));
    QObject::connect(editor, &QLineEdit::editingFinished, view_, [this] { finishArrow(true); });
    auto* escape = new QShortcut(QKeySequence(Qt::Key_Escape), editor);
    escape->setContext(Qt::WidgetShortcut);
    QObject::connect(escape, &QShortcut::activated, view_, [this] { finishArrow(false); });
    editor_ = editor;
    editor->show();
    editor->setFocus(Qt::OtherFocusReason);
}

void SliceMeasurements::finishArrow(bool keep) {
    if (!arrow_) {
        return;
    }
    Measurement arrow = std::move(*arrow_);
    arrow_.reset();
    if (editor_ != nullptr) {
        arrow.text = editor_->text().trimmed().toStdString();
        editor_->hide();
        editor_->deleteLater();
        editor_ = nullptr;
    }
    view_->setFocus(Qt::OtherFocusReason);
    if (keep && document_ != nullptr) {
        document_->add(std::move(arrow));
    }
    view_->update();
}

void SliceMeasurements::cancel() {
    draft_.cancel();
    grab_.reset();
    finishArrow(false);
}

void SliceMeasurements::paint(QPainter& painter, const SlicePlane& plane, double tolerance) const {
    if (document_ != nullptr) {
        for (const Measurement& stored : document_->measurements()) {
            const Measurement& m = grab_ && grab_->id == stored.id ? grab_->edited : stored;
            if (!measurementInPlane(m, plane, tolerance)) {
                continue;
            }
            const MeasurementLook look = m.readOnly                      ? MeasurementLook::ReadOnly
                                         : m.id == document_->selected() ? MeasurementLook::Selected
                                                                         : MeasurementLook::Normal;
            paintMeasurement(painter, plane, m, look);
        }
    }
    if (draft_.active()) {
        paintMeasurement(painter, plane, draft_.preview(), MeasurementLook::Draft);
    }
    if (arrow_) {
        paintMeasurement(painter, plane, *arrow_, MeasurementLook::Draft);
    }
}

} // namespace lucent
