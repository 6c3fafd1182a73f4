#pragma once

#include <QFrame>
#include <QString>

#include "core/hanging/HangingProtocol.h"

class QLabel;
class QToolButton;
class QVBoxLayout;

namespace lucent {

class SeriesSession;
class SliceView;
class StackView;
class VolumeView;

// One cell of the viewport grid: a series of a SeriesSession shown as an MPR plane
// (SliceView, every tool of the MPR views), as 3D (VolumeView), as the 2D images of a
// stack (StackView), or empty. Its corner
// names the series and the study date; its link button puts it in a link group
// (ViewportLinks). A series dragged from the study browser and dropped on it is
// asked for with seriesDropped.
class Viewport : public QFrame {
    Q_OBJECT

public:
    explicit Viewport(int number, QWidget* parent = nullptr);

    // 1-based, as the corner and the reference lines name it.
    int number() const { return number_; }
    void setNumber(int number);

    // Shows `view` of the session's series (the session is not owned); nullptr: empty.
    void show(SeriesSession* session, ViewportView view);
    SeriesSession* session() const { return session_; }
    ViewportView view() const { return view_; }
    // The MPR view shown (nullptr for 3D or empty) and the 3D view (nullptr otherwise).
    SliceView* sliceView() const { return slice_; }
    VolumeView* volumeView() const { return volume_; }
    // The 2D image stack shown (a session of a stack), else nullptr.
    StackView* stackView() const { return stack_; }
    QWidget* content() const;

    // 0: not linked; viewports of the same non-zero group move together.
    int linkGroup() const { return linkGroup_; }
    void setLinkGroup(int group);
    // Turns the link on (the last group it had, 1 at first) or off.
    void toggleLink();

    void setActive(bool active);
    bool isActive() const { return active_; }

signals:
    void seriesDropped(const QString& path, const QString& series);
    void linkGroupChanged(int group);
    void pressed();
    // The content widget was replaced (the linker reconnects).
    void contentChanged();

protected:
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void updateHeader();
    void clearContent();

    int number_;
    SeriesSession* session_ = nullptr;
    ViewportView view_ = ViewportView::Axial;
    SliceView* slice_ = nullptr;
    VolumeView* volume_ = nullptr;
    StackView* stack_ = nullptr;
    QWidget* empty_ = nullptr;
    QVBoxLayout* column_;
    QLabel* title_;
    QToolButton* link_;
    int linkGroup_ = 0;
    int lastGroup_ = 1;
    bool active_ = false;
};

// "Axial", "Coronal", "Sagittal", "Oblique", "3D", "Images".
QString viewportViewTitle(ViewportView view);

} // namespace lucent
