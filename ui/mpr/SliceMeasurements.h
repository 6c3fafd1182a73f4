#pragma once

#include <cstdint>
#include <optional>

#include <QLineEdit>
#include <QPointF>
#include <QPointer>

#include "core/measure/Measurement.h"
#include "ui/mpr/MeasurementDraft.h"
#include "ui/mpr/SeriesMeasurements.h"

class QPainter;
class QWidget;

namespace lucent {

// The measurements of a series as one MPR view draws and edits them: the shared
// document's measurements that lie in the view's plane, a new one drawn with the
// mouse (MeasurementDraft), a point handle dragged (one "Change" edit when let go),
// and an arrow's text typed in a line edit over the view (Enter or leaving it adds
// the arrow, Esc drops it). Positions are the view's widget pixels on its plane.
class SliceMeasurements {
public:
    explicit SliceMeasurements(QWidget* view) : view_(view) {}

    void setDocument(SeriesMeasurements* document);
    SeriesMeasurements* document() const { return document_; }

    // A left press: grabs the handle under the mouse (any tool), or goes on with the
    // measurement being drawn, or starts one of `kind`. Returns whether it took the press.
    bool press(const SlicePlane& plane, double tolerance, const QPointF& pos,
               std::optional<MeasurementKind> kind);
    // The mouse moved, a button held or not.
    void move(const SlicePlane& plane, const QPointF& pos);
    // The left button let go; `click`: the mouse stayed where it was pressed.
    void release(const SlicePlane& plane, const QPointF& pos, bool click);
    // Drops the measurement being drawn (and an arrow waiting for its text).
    void cancel();
    // Drawing, dragging a handle or typing an arrow's text.
    bool busy() const { return draft_.active() || grab_.has_value() || editor_ != nullptr; }
    // The arrow's text editor while it is open; nullptr otherwise.
    QLineEdit* textEditor() const { return editor_; }

    void paint(QPainter& painter, const SlicePlane& plane, double tolerance) const;

private:
    struct Grab {
        std::uint64_t id = 0;
        int index = 0;
        Measurement edited;
        bool moved = false;
    };
    std::optional<Grab> handleAt(const SlicePlane& plane, double tolerance,
                                 const QPointF& pos) const;
    void askArrowText(const SlicePlane& plane, Measurement arrow);
    void finishArrow(bool keep);

    QWidget* view_;
    QPointer<SeriesMeasurements> document_;
    MeasurementDraft draft_;
    std::optional<Grab> grab_;
    std::optional<Measurement> arrow_; // waiting for its text
    QPointer<QLineEdit> editor_;
};

} // namespace lucent
