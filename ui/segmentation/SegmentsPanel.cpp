#include "ui/segmentation/SegmentsPanel.h"

#include <QButtonGroup>
#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QKeyEvent>
#include <QLabel>
#include <QPushButton>
#include <QSlider>
#include <QTabWidget>
#include <QTableWidget>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>

#include "core/segmentation/SegmentCodes.h"
#include "ui/segmentation/SegmentEditor.h"
#include "ui/segmentation/SegmentationSession.h"
#include "ui/segmentation/ThresholdHistogram.h"

namespace lucent {
namespace {

enum Column { Shown, Colour, Name, Kind, Locked, Columns };

QIcon swatch(const std::array<std::uint8_t, 3>& c) {
    QPixmap pixmap(14, 14);
    pixmap.fill(QColor(c[0], c[1], c[2]));
    return QIcon(pixmap);
}

} // namespace

SegmentsPanel::SegmentsPanel(SegmentEditor* editor, QWidget* parent)
    : QWidget(parent), editor_(editor), previewTimer_(new QTimer(this)) {
    auto* column = new QVBoxLayout(this);
    series_ = new QLabel(this);
    series_->setWordWrap(true);
    column->addWidget(series_);
    column->addWidget(makeListControls());
    column->addWidget(makeEffects(), 1);
    column->addWidget(makeDataControls());

    previewTimer_->setSingleShot(true);
    previewTimer_->setInterval(150); // a threshold for every spin step would lag
    connect(previewTimer_, &QTimer::timeout, this, &SegmentsPanel::updateThresholdPreview);
    connect(editor_, &SegmentEditor::activeSessionChanged, this, &SegmentsPanel::showSession);
    connect(editor_, &SegmentEditor::message, this, &SegmentsPanel::message);
    showSession(editor_->activeSession());
}

QWidget* SegmentsPanel::makeListControls() {
    auto* box = new QWidget(this);
    auto* column = new QVBoxLayout(box);
    column->setContentsMargins(0, 0, 0, 0);
    segments_ = new QTableWidget(0, Columns, box);
    segments_->setHorizontalHeaderLabels(
        {tr("Shown"), tr("Colour"), tr("Name"), tr("Kind"), tr("Locked")});
    segments_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    segments_->horizontalHeader()->setSectionResizeMode(Name, QHeaderView::Stretch);
    segments_->verticalHeader()->hide();
    segments_->setSelectionBehavior(QAbstractItemView::SelectRows);
    segments_->setSelectionMode(QAbstractItemView::SingleSelection);
    segments_->setMinimumHeight(120);
    connect(segments_, &QTableWidget::cellChanged, this, &SegmentsPanel::cellEdited);
    connect(segments_, &QTableWidget::itemSelectionChanged, this, &SegmentsPanel::rowChosen);
    column->addWidget(segments_);

    auto* buttons = new QHBoxLayout;
    auto* add = new QPushButton(tr("Add"), box);
    auto* remove = new QPushButton(tr("Remove"), box);
    undo_ = new QPushButton(tr("Undo"), box);
    redo_ = new QPushButton(tr("Redo"), box);
    connect(add, &QPushButton::clicked, this, [this] { addSegment(); });
    connect(remove, &QPushButton::clicked, this, [this] { removeActiveSegment(); });
    connect(undo_, &QPushButton::clicked, this, [this] { undo(); });
    connect(redo_, &QPushButton::clicked, this, [this] { redo(); });
    for (QPushButton* b : {add, remove, undo_, redo_}) {
        buttons->addWidget(b);
    }
    column->addLayout(buttons);

    // How the views draw the segments.
    auto* look = new QHBoxLayout;
    auto* fill = new QCheckBox(tr("Fill"), box);
    auto* outline = new QCheckBox(tr("Outline"), box);
    auto* opacity = new QSlider(Qt::Horizontal, box);
    opacity->setRange(5, 100);
    const SegmentDisplay& shown = editor_->display();
    fill->setChecked(shown.fill);
    outline->setChecked(shown.outline);
    opacity->setValue(static_cast<int>(shown.fillOpacity * 100));
    opacity->setToolTip(tr("The fill's opacity"));
    const auto apply = [this, fill, outline, opacity] {
        editor_->setDisplay({fill->isChecked(), outline->isChecked(), opacity->value() / 100.0});
    };
    connect(fill, &QCheckBox::toggled, this, apply);
    connect(outline, &QCheckBox::toggled, this, apply);
    connect(opacity, &QSlider::valueChanged, this, apply);
    look->addWidget(fill);
    look->addWidget(outline);
    look->addWidget(opacity, 1);
    column->addLayout(look);
    return box;
}

void SegmentsPanel::showSession(SegmentationSession* session) {
    if (session == session_) {
        return;
    }
    if (session_) {
        session_->setPreview(std::nullopt);
        disconnect(session_, nullptr, this, nullptr);
    }
    session_ = session;
    updating_ = true;
    preview_->setChecked(false);
    updating_ = false;
    if (session_) {
        connect(session_, &SegmentationSession::segmentsChanged, this, &SegmentsPanel::fillTable);
        connect(session_, &SegmentationSession::activeSegmentChanged, this,
                &SegmentsPanel::selectActive);
        const Volume& volume = *session_->volume();
        series_->setText(QString::fromStdString(volume.modality + " " + volume.description));
        if (histogramOf_ != &volume) { // the same series in another viewport: kept
            histogram_->setHistogram(computeHistogram(volume, 256));
            histogramOf_ = &volume;
        }
    } else {
        series_->setText(tr("The active viewport shows no volume"));
        histogram_->setHistogram({});
        histogramOf_ = nullptr;
    }
    fillTable();
}

void SegmentsPanel::fillRow(int row, const Segment& segment) {
    const QVariant id = QVariant::fromValue(segment.id);
    auto* shown = new QTableWidgetItem;
    shown->setFlags(Qt::ItemIsUserCheckable | Qt::ItemIsEnabled | Qt::ItemIsSelectable);
    shown->setCheckState(segment.visible ? Qt::Checked : Qt::Unchecked);
    shown->setData(Qt::UserRole, id);
    segments_->setItem(row, Shown, shown);
    auto* colour = new QToolButton(segments_);
    colour->setIcon(swatch(segment.colour));
    colour->setToolTip(tr("Choose the colour"));
    connect(colour, &QToolButton::clicked, this, [this, sid = segment.id, c = segment.colour] {
        const QColor chosen = QColorDialog::getColor(QColor(c[0], c[1], c[2]), this);
        if (chosen.isValid() && session_) {
            session_->setColour(sid, {static_cast<std::uint8_t>(chosen.red()),
                                      static_cast<std::uint8_t>(chosen.green()),
                                      static_cast<std::uint8_t>(chosen.blue())});
        }
    });
    segments_->setCellWidget(row, Colour, colour);
    auto* name = new QTableWidgetItem(QString::fromStdString(segment.name));
    name->setData(Qt::UserRole, id);
    segments_->setItem(row, Name, name);
    auto* kind = new QComboBox(segments_);
    int current = -1;
    for (const SegmentKind& k : segmentKinds()) {
        if (k.type == segment.type && k.category == segment.category) {
            current = kind->count();
        }
        kind->addItem(QString::fromUtf8(k.name.data(), static_cast<int>(k.name.size())));
    }
    if (current < 0) { // codes from elsewhere (a SEG read): shown, not in the table
        kind->addItem(QString::fromStdString(segment.type.meaning));
        current = kind->count() - 1;
    }
    kind->setCurrentIndex(current);
    connect(kind, &QComboBox::activated, this, [this, sid = segment.id](int index) {
        if (session_ && index < static_cast<int>(segmentKinds().size())) {
            session_->setKind(sid, segmentKinds()[static_cast<std::size_t>(index)]);
        }
    });
    segments_->setCellWidget(row, Kind, kind);
    auto* locked = new QTableWidgetItem;
    locked->setFlags(Qt::ItemIsUserCheckable | Qt::ItemIsEnabled | Qt::ItemIsSelectable);
    locked->setCheckState(segment.locked ? Qt::Checked : Qt::Unchecked);
    locked->setData(Qt::UserRole, id);
    segments_->setItem(row, Locked, locked);
}

void SegmentsPanel::fillTable() {
    updating_ = true;
    segments_->clearContents();
    other_->clear();
    const std::vector<Segment> none;
    const std::vector<Segment>& list = session_ ? session_->segmentation().segments() : none;
    segments_->setRowCount(static_cast<int>(list.size()));
    for (int row = 0; row < static_cast<int>(list.size()); ++row) {
        const Segment& segment = list[static_cast<std::size_t>(row)];
        fillRow(row, segment);
        other_->addItem(QString::fromStdString(segment.name), QVariant::fromValue(segment.id));
        if (segment.id == session_->activeSegment()) {
            segments_->selectRow(row);
        }
    }
    undo_->setEnabled(session_ && session_->segmentation().canUndo());
    redo_->setEnabled(session_ && session_->segmentation().canRedo());
    undo_->setToolTip(session_ ? QString::fromStdString(session_->segmentation().undoText())
                               : QString());
    redo_->setToolTip(session_ ? QString::fromStdString(session_->segmentation().redoText())
                               : QString());
    updating_ = false;
}

void SegmentsPanel::selectActive() {
    updating_ = true;
    for (int row = 0; row < segments_->rowCount(); ++row) {
        const QTableWidgetItem* item = segments_->item(row, Name);
        if (session_ && item != nullptr &&
            item->data(Qt::UserRole).value<std::uint32_t>() == session_->activeSegment()) {
            segments_->selectRow(row);
        }
    }
    updating_ = false;
}

void SegmentsPanel::cellEdited(int row, int column) {
    QTableWidgetItem* item = segments_->item(row, column);
    if (updating_ || !session_ || item == nullptr) {
        return;
    }
    const auto id = item->data(Qt::UserRole).value<std::uint32_t>();
    // Each change rebuilds the table: run it after this signal has returned.
    if (column == Name && !item->text().trimmed().isEmpty()) {
        QTimer::singleShot(0, this, [this, id, text = item->text().trimmed()] {
            if (session_) {
                session_->rename(id, text);
            }
        });
    } else if (column == Shown || column == Locked) {
        const bool on = item->checkState() == Qt::Checked;
        QTimer::singleShot(0, this, [this, id, on, column] {
            if (session_) {
                if (column == Shown) {
                    session_->setVisible(id, on);
                } else {
                    session_->setLocked(id, on);
                }
            }
        });
    }
}

void SegmentsPanel::rowChosen() {
    const QList<QTableWidgetItem*> chosen = segments_->selectedItems();
    if (updating_ || !session_ || chosen.isEmpty()) {
        return;
    }
    const int row = chosen.front()->row();
    if (QTableWidgetItem* item = segments_->item(row, Name)) {
        session_->setActiveSegment(item->data(Qt::UserRole).value<std::uint32_t>());
        if (preview_->isChecked()) {
            previewTimer_->start();
        }
    }
}

void SegmentsPanel::say(const QString& text) {
    message_ = text;
    emit message(text, 6000);
}

namespace {

// Ctrl+Z undoes, Ctrl+Y and Ctrl+Shift+Z redo: 0 for another key.
int undoKey(const QKeyEvent* key) {
    const QKeyCombination combination = key->keyCombination();
    if (combination == QKeyCombination(Qt::ControlModifier, Qt::Key_Z)) {
        return -1;
    }
    if (combination == QKeyCombination(Qt::ControlModifier, Qt::Key_Y) ||
        combination == QKeyCombination(Qt::ControlModifier | Qt::ShiftModifier, Qt::Key_Z)) {
        return 1;
    }
    return 0;
}

} // namespace

bool SegmentsPanel::event(QEvent* event) {
    // Within the panel the keys are the segments' (the window's Edit > Undo would otherwise
    // take them): the shortcut is overridden, and the key comes here as a key press.
    if (event->type() == QEvent::ShortcutOverride && undoKey(static_cast<QKeyEvent*>(event)) != 0) {
        event->accept();
        return true;
    }
    return QWidget::event(event);
}

void SegmentsPanel::keyPressEvent(QKeyEvent* event) {
    if (const int key = undoKey(event); key != 0) {
        key < 0 ? undo() : redo();
        event->accept();
        return;
    }
    QWidget::keyPressEvent(event);
}

bool SegmentsPanel::addSegment() {
    if (!session_) {
        say(tr("The active viewport shows no volume"));
        return false;
    }
    session_->addSegment();
    return true;
}

bool SegmentsPanel::removeActiveSegment() {
    if (!session_ || session_->active() == nullptr) {
        say(tr("No segment chosen"));
        return false;
    }
    return session_->removeSegment(session_->activeSegment());
}

bool SegmentsPanel::undo() {
    if (!session_ || !session_->segmentation().canUndo()) {
        say(tr("Nothing to undo"));
        return false;
    }
    say(tr("Undo %1").arg(QString::fromStdString(session_->segmentation().undoText())));
    return session_->undo();
}

bool SegmentsPanel::redo() {
    if (!session_ || !session_->segmentation().canRedo()) {
        say(tr("Nothing to redo"));
        return false;
    }
    say(tr("Redo %1").arg(QString::fromStdString(session_->segmentation().redoText())));
    return session_->redo();
}

} // namespace lucent
