#include "ui/app/ViewLayout.h"

#include <QEvent>
#include <QFocusEvent>
#include <QMouseEvent>
#include <QSplitter>
#include <QVBoxLayout>

namespace lucent {

namespace {

void equalSizes(QSplitter* splitter) {
    splitter->setSizes(QList<int>(splitter->count(), 1000)); // scaled to fit
}

// Focus that the user moved (Tab, a click), not the window's first focus.
bool movedFocusHere(const QEvent* event) {
    if (event->type() != QEvent::FocusIn) {
        return false;
    }
    const Qt::FocusReason reason = static_cast<const QFocusEvent*>(event)->reason();
    return reason == Qt::TabFocusReason || reason == Qt::BacktabFocusReason ||
           reason == Qt::MouseFocusReason;
}

} // namespace

ViewLayout::ViewLayout(const std::array<QWidget*, kViewCount>& views, QWidget* parent)
    : QWidget(parent), views_(views), rows_(new QSplitter(Qt::Vertical, this)),
      top_(new QSplitter(Qt::Horizontal, rows_)), bottom_(new QSplitter(Qt::Horizontal, rows_)) {
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(rows_);
    for (QSplitter* s : {rows_, top_, bottom_}) {
        s->setHandleWidth(2);
        s->setChildrenCollapsible(false);
    }
    rows_->addWidget(top_);
    rows_->addWidget(bottom_);
    for (QWidget* view : views_) {
        view->installEventFilter(this);
    }
    place(arrangement_);
}

void ViewLayout::setArrangement(Arrangement arrangement) {
    restoreTo_.reset();
    arrangement_ = arrangement;
    place(arrangement_);
    emit arrangementChanged(arrangement_);
}

void ViewLayout::maximize(QWidget* view) {
    const int index = indexOf(view);
    if (index < 0) {
        return;
    }
    const std::optional<Arrangement> before =
        arrangement_ == Arrangement::Single ? restoreTo_ : arrangement_;
    setActiveView(view);
    setArrangement(Arrangement::Single);
    restoreTo_ = before;
}

void ViewLayout::restore() {
    setArrangement(restoreTo_.value_or(Arrangement::Grid2x2));
}

void ViewLayout::setActiveView(QWidget* view) {
    const int index = indexOf(view);
    if (index < 0 || index == activeIndex_) {
        return;
    }
    activeIndex_ = index;
    if (arrangement_ == Arrangement::Single) {
        place(arrangement_);
    }
    emit activeViewChanged(views_[activeIndex_]);
}

QString ViewLayout::name(Arrangement arrangement) {
    switch (arrangement) {
    case Arrangement::Grid2x2:
        return QStringLiteral("2x2");
    case Arrangement::Row1x3:
        return QStringLiteral("1x3");
    case Arrangement::Single:
        return QStringLiteral("1x1");
    }
    return {};
}

std::optional<ViewLayout::Arrangement> ViewLayout::fromName(const QString& name) {
    for (const Arrangement a : {Arrangement::Grid2x2, Arrangement::Row1x3, Arrangement::Single}) {
        if (ViewLayout::name(a) == name) {
            return a;
        }
    }
    return std::nullopt;
}

bool ViewLayout::eventFilter(QObject* watched, QEvent* event) {
    const int index = indexOf(watched);
    if (index >= 0) {
        if (event->type() == QEvent::MouseButtonPress || movedFocusHere(event)) {
            setActiveView(views_[index]);
        } else if (event->type() == QEvent::MouseButtonDblClick &&
                   static_cast<QMouseEvent*>(event)->button() == Qt::LeftButton &&
                   !watched->property("keepsDoubleClick").toBool()) {
            if (arrangement_ == Arrangement::Single) {
                restore();
            } else {
                maximize(views_[index]);
            }
            return true; // not a second press for the view
        }
    }
    return QWidget::eventFilter(watched, event);
}

int ViewLayout::indexOf(const QObject* view) const {
    for (int n = 0; n < kViewCount; ++n) {
        if (views_[n] == view) {
            return n;
        }
    }
    return -1;
}

void ViewLayout::place(Arrangement arrangement) {
    // Row1x3 puts the three MPR views in the top row; the others keep 2x2's places.
    const bool row = arrangement == Arrangement::Row1x3;
    for (int n = 0; n < kViewCount; ++n) {
        QSplitter* splitter = (n < 2 || (row && n == 2)) ? top_ : bottom_;
        splitter->insertWidget(splitter == top_ ? n : n - (row ? 3 : 2), views_[n]);
    }
    std::array<bool, kViewCount> visible{};
    for (int n = 0; n < kViewCount; ++n) {
        visible[n] = arrangement == Arrangement::Grid2x2 ||
                     (arrangement == Arrangement::Row1x3 && n < 3) || n == activeIndex_;
    }
    for (int n = 0; n < kViewCount; ++n) {
        views_[n]->setVisible(visible[n]);
    }
    for (QSplitter* splitter : {top_, bottom_}) {
        bool any = false;
        for (int n = 0; n < splitter->count(); ++n) {
            any = any || !splitter->widget(n)->isHidden();
        }
        splitter->setVisible(any);
        equalSizes(splitter);
    }
    equalSizes(rows_);
}

} // namespace lucent
