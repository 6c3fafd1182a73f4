#pragma once

#include <array>
#include <optional>

#include <QString>
#include <QWidget>

class QSplitter;

namespace lucent {

// The view area of the workstation: the three MPR views and the 3D view in one of
// three arrangements, in resizable splitters.
//   Grid2x2: axial and coronal above, sagittal and 3D below.
//   Row1x3:  axial, coronal and sagittal in one row (the 3D view hidden).
//   Single:  one view alone (the active one).
// A double-click on a view maximizes it (Single); another double-click restores
// the arrangement it came from; a view whose property "keepsDoubleClick" is true
// (an MPR view drawing with a tool) gets the double-click itself. The view last
// pressed is the active one.
class ViewLayout : public QWidget {
    Q_OBJECT

public:
    enum class Arrangement { Grid2x2, Row1x3, Single };
    static constexpr int kViewCount = 4;

    // views: axial, coronal, sagittal, 3D. They become children of this widget.
    ViewLayout(const std::array<QWidget*, kViewCount>& views, QWidget* parent = nullptr);

    Arrangement arrangement() const { return arrangement_; }
    // Single shows the active view; the others show theirs.
    void setArrangement(Arrangement arrangement);

    // Shows `view` alone; restore() returns to the arrangement before it.
    void maximize(QWidget* view);
    void restore();
    bool maximized() const { return restoreTo_.has_value(); }

    QWidget* activeView() const { return views_[activeIndex_]; }
    int activeIndex() const { return activeIndex_; }
    void setActiveView(QWidget* view);
    const std::array<QWidget*, kViewCount>& views() const { return views_; }

    // "2x2", "1x3", "1x1": the names the settings and menus use.
    static QString name(Arrangement arrangement);
    static std::optional<Arrangement> fromName(const QString& name);

signals:
    void arrangementChanged(lucent::ViewLayout::Arrangement arrangement);
    void activeViewChanged(QWidget* view);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    int indexOf(const QObject* view) const;
    void place(Arrangement arrangement);

    std::array<QWidget*, kViewCount> views_;
    QSplitter* rows_;
    QSplitter* top_;
    QSplitter* bottom_;
    Arrangement arrangement_ = Arrangement::Grid2x2;
    std::optional<Arrangement> restoreTo_;
    int activeIndex_ = 0;
};

} // namespace lucent
