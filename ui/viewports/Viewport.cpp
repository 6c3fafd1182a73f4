#include "ui/viewports/Viewport.h"

#include <QDragEnterEvent>
#include <QDropEvent>
#include <QHBoxLayout>
#include <QLabel>
#include <QMimeData>
#include <QToolButton>
#include <QVBoxLayout>

#include "ui/mpr/SliceView.h"
#include "ui/study/SeriesDrag.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/StackView.h"
#include "ui/volume/VolumeView.h"

namespace lucent {

QString viewportViewTitle(ViewportView view) {
    switch (view) {
    case ViewportView::Axial:
        return QStringLiteral("Axial");
    case ViewportView::Coronal:
        return QStringLiteral("Coronal");
    case ViewportView::Sagittal:
        return QStringLiteral("Sagittal");
    case ViewportView::Oblique:
        return QStringLiteral("Oblique");
    case ViewportView::Volume3D:
        return QStringLiteral("3D");
    case ViewportView::Stack:
        return QStringLiteral("Images");
    }
    return {};
}

namespace {

Orientation sliceOrientation(ViewportView view) {
    switch (view) {
    case ViewportView::Coronal:
        return Orientation::Coronal;
    case ViewportView::Sagittal:
        return Orientation::Sagittal;
    default:
        return Orientation::Axial; // an oblique viewport starts axial; shift-drag turns it
    }
}

} // namespace

Viewport::Viewport(int number, QWidget* parent)
    : QFrame(parent), number_(number), column_(new QVBoxLayout(this)), title_(new QLabel(this)),
      link_(new QToolButton(this)) {
    setObjectName(QStringLiteral("viewport%1").arg(number));
    setAcceptDrops(true);
    setFrameShape(QFrame::Box);
    setLineWidth(1);
    column_->setContentsMargins(1, 1, 1, 1);
    column_->setSpacing(0);
    auto* header = new QHBoxLayout;
    header->setContentsMargins(4, 0, 2, 0);
    header->addWidget(title_, 1);
    header->addWidget(link_);
    column_->addLayout(header);
    title_->setObjectName(QStringLiteral("viewportTitle"));
    link_->setObjectName(QStringLiteral("viewportLink"));
    link_->setCheckable(true);
    link_->setAutoRaise(true);
    link_->setToolTip(tr("Link this viewport's scrolling, crosshair, window, zoom and pan with "
                         "the other linked viewports (Ctrl+L)"));
    connect(link_, &QToolButton::clicked, this, [this](bool on) {
        if (on != (linkGroup_ != 0)) {
            toggleLink();
        }
    });
    show(nullptr, ViewportView::Axial);
}

QWidget* Viewport::content() const {
    if (slice_ != nullptr) {
        return slice_;
    }
    if (volume_ != nullptr) {
        return volume_;
    }
    if (stack_ != nullptr) {
        return stack_;
    }
    return empty_;
}

void Viewport::setNumber(int number) {
    number_ = number;
    setObjectName(QStringLiteral("viewport%1").arg(number));
    updateHeader();
}

void Viewport::clearContent() {
    if (QWidget* shown = content()) {
        column_->removeWidget(shown);
        shown->deleteLater();
    }
    slice_ = nullptr;
    volume_ = nullptr;
    stack_ = nullptr;
    empty_ = nullptr;
}

void Viewport::show(SeriesSession* session, ViewportView view) {
    clearContent();
    session_ = session;
    view_ = view;
    if (session_ == nullptr) {
        auto* hint = new QLabel(tr("Drop a series here"), this);
        hint->setAlignment(Qt::AlignCenter);
        hint->setStyleSheet(QStringLiteral("color: grey; background: black"));
        empty_ = hint;
    } else if (session_->stack()) {
        view_ = ViewportView::Stack;
        stack_ = new StackView(this);
        stack_->setStack(session_->stack());
    } else if (view == ViewportView::Volume3D) {
        volume_ = new VolumeView(this);
        volume_->setVolume(session_->volume());
    } else {
        slice_ = new SliceView(sliceOrientation(view), session_->cursor(), this);
        slice_->setVolume(session_->volume());
    }
    QWidget* shown = content();
    shown->installEventFilter(this);
    shown->setAcceptDrops(false); // drops land on the viewport
    column_->addWidget(shown, 1);
    updateHeader();
    emit contentChanged();
}

void Viewport::setLinkGroup(int group) {
    group = std::max(0, group);
    if (group == linkGroup_) {
        return;
    }
    linkGroup_ = group;
    if (group != 0) {
        lastGroup_ = group;
    }
    updateHeader();
    emit linkGroupChanged(group);
}

void Viewport::toggleLink() {
    setLinkGroup(linkGroup_ == 0 ? lastGroup_ : 0);
}

void Viewport::setActive(bool active) {
    active_ = active;
    setStyleSheet(active ? QStringLiteral("lucent--Viewport { border: 1px solid #e0a030; }")
                         : QString());
}

void Viewport::updateHeader() {
    QString text = QStringLiteral("%1").arg(number_);
    if (session_ != nullptr) {
        text += QStringLiteral("  %1  ·  %2").arg(session_->title(), viewportViewTitle(view_));
    }
    title_->setText(text);
    title_->setToolTip(session_ != nullptr ? session_->path() : QString());
    link_->setChecked(linkGroup_ != 0);
    link_->setText(linkGroup_ != 0 ? tr("Linked %1").arg(linkGroup_) : tr("Link"));
}

void Viewport::dragEnterEvent(QDragEnterEvent* event) {
    if (event->mimeData() != nullptr && draggedSeries(*event->mimeData())) {
        event->acceptProposedAction();
    }
}

void Viewport::dropEvent(QDropEvent* event) {
    if (event->mimeData() == nullptr) {
        return;
    }
    if (const auto series = draggedSeries(*event->mimeData())) {
        event->acceptProposedAction();
        emit seriesDropped(series->path, series->series);
    }
}

bool Viewport::eventFilter(QObject* watched, QEvent* event) {
    if (watched == content() &&
        (event->type() == QEvent::MouseButtonPress || event->type() == QEvent::FocusIn)) {
        emit pressed();
    }
    return QFrame::eventFilter(watched, event);
}

} // namespace lucent
