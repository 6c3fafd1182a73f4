#include "ui/mpr/MeasurementList.h"

#include <QAction>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QMenu>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include "ui/mpr/MeasurementNavigation.h"

namespace lucent {

MeasurementList::MeasurementList(MprCursor* cursor, QWidget* parent)
    : QWidget(parent), cursor_(cursor), table_(new QTableWidget(0, ColumnCount, this)),
      delete_(new QPushButton(tr("Delete"), this)), clear_(new QPushButton(tr("Clear all"), this)),
      notShown_(new QLabel(this)) {
    notShown_->setObjectName(QStringLiteral("measurementsNotShown"));
    notShown_->setWordWrap(true);
    notShown_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    table_->setObjectName(QStringLiteral("measurementTable"));
    table_->setHorizontalHeaderLabels(
        {tr("Kind"), tr("Name"), tr("Value"), tr("Plane"), tr("Slice"), tr("Lesion")});
    table_->setSelectionBehavior(QAbstractItemView::SelectRows);
    table_->setSelectionMode(QAbstractItemView::SingleSelection);
    table_->setEditTriggers(QAbstractItemView::DoubleClicked | QAbstractItemView::EditKeyPressed |
                            QAbstractItemView::SelectedClicked);
    table_->verticalHeader()->hide();
    table_->horizontalHeader()->setStretchLastSection(true);
    table_->horizontalHeader()->setDefaultSectionSize(80);
    table_->horizontalHeader()->setSectionResizeMode(Value, QHeaderView::ResizeToContents);
    delete_->setToolTip(tr("Delete the selected measurement (Del)"));
    clear_->setToolTip(tr("Delete every measurement of the series you may edit"));

    auto* remove = new QAction(tr("Delete measurement"), table_);
    remove->setShortcuts({QKeySequence(QKeySequence::Delete), QKeySequence(Qt::Key_Backspace)});
    remove->setShortcutContext(Qt::WidgetShortcut);
    table_->addAction(remove);
    connect(remove, &QAction::triggered, this, &MeasurementList::deleteSelected);
    connect(delete_, &QPushButton::clicked, this, &MeasurementList::deleteSelected);
    connect(clear_, &QPushButton::clicked, this, [this] {
        if (measurements_ != nullptr) {
            measurements_->clear();
        }
    });
    connect(table_, &QTableWidget::cellClicked, this, [this](int row, int) { rowClicked(row); });
    connect(table_, &QTableWidget::cellChanged, this, &MeasurementList::cellEdited);
    table_->setContextMenuPolicy(Qt::CustomContextMenu);
    connect(table_, &QTableWidget::customContextMenuRequested, this, [this](const QPoint& at) {
        const std::uint64_t id = idAt(table_->rowAt(at.y()));
        if (id == 0) {
            return;
        }
        QMenu* menu = contextMenu(id);
        menu->setAttribute(Qt::WA_DeleteOnClose);
        menu->popup(table_->viewport()->mapToGlobal(at));
    });
    connect(table_, &QTableWidget::itemSelectionChanged, this, [this] {
        const std::uint64_t id = idAt(table_->currentRow());
        const SeriesMeasurements* m = measurements_;
        delete_->setEnabled(m != nullptr && m->find(id) != nullptr && !m->find(id)->readOnly);
    });

    auto* buttons = new QHBoxLayout;
    buttons->addWidget(delete_);
    buttons->addWidget(clear_);
    auto* column = new QVBoxLayout(this);
    column->setContentsMargins(2, 2, 2, 2);
    column->addWidget(table_, 1);
    column->addWidget(notShown_);
    column->addLayout(buttons);
    // The dock may be narrower than the buttons' text: they share what it has.
    delete_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
    clear_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
    refresh();
}

void MeasurementList::setMeasurements(SeriesMeasurements* measurements) {
    if (measurements_ != nullptr) {
        disconnect(measurements_, nullptr, this, nullptr);
    }
    measurements_ = measurements;
    if (measurements != nullptr) {
        connect(measurements, &SeriesMeasurements::changed, this, &MeasurementList::refresh);
        connect(measurements, &SeriesMeasurements::selectionChanged, this,
                &MeasurementList::showSelection);
    }
    refresh();
}

std::uint64_t MeasurementList::idAt(int row) const {
    const QTableWidgetItem* item = row >= 0 ? table_->item(row, Kind) : nullptr;
    return item != nullptr ? item->data(Qt::UserRole).toULongLong() : 0;
}

void MeasurementList::refresh() {
    refreshing_ = true;
    table_->setRowCount(0);
    QStringList notShown;
    if (measurements_ != nullptr) {
        for (const std::string& item : measurements_->notShown()) {
            notShown << QString::fromStdString(item);
        }
    }
    notShown_->setText(
        notShown.isEmpty()
            ? QString()
            : tr("Not shown (other reports): %1").arg(notShown.join(QStringLiteral("; "))));
    notShown_->setVisible(!notShown.isEmpty());
    if (measurements_ != nullptr) {
        const std::shared_ptr<const Volume> volume = measurements_->volume();
        for (const Measurement& m : measurements_->measurements()) {
            const int row = table_->rowCount();
            table_->insertRow(row);
            const std::optional<int> slice =
                volume ? measurementSlice(m, volume->geometry()) : std::nullopt;
            const QString cells[ColumnCount] = {
                QString::fromLatin1(measurementKindName(m.kind)),
                QString::fromStdString(m.label),
                QString::fromStdString(measurementValueText(m)).replace('\n', ' '),
                measurementPlaneName(m),
                slice ? QString::number(*slice) : QString(),
                QString::fromStdString(lesionMarkText(m.lesion))};
            for (int c = 0; c < ColumnCount; ++c) {
                auto* item = new QTableWidgetItem(cells[c]);
                Qt::ItemFlags flags = Qt::ItemIsSelectable | Qt::ItemIsEnabled;
                const bool editable = c == Name || (c == Value && m.kind == MeasurementKind::Arrow);
                if (editable && !m.readOnly) {
                    flags |= Qt::ItemIsEditable;
                }
                item->setFlags(flags);
                if (m.readOnly) {
                    item->setForeground(palette().color(QPalette::Disabled, QPalette::Text));
                    item->setToolTip(tr("Read from a structured report: cannot be edited"));
                }
                table_->setItem(row, c, item);
            }
            table_->item(row, Kind)->setData(Qt::UserRole, QVariant::fromValue(m.id));
        }
    }
    clear_->setEnabled(measurements_ != nullptr && !measurements_->measurements().empty());
    refreshing_ = false;
    showSelection();
}

QMenu* MeasurementList::contextMenu(std::uint64_t id) {
    auto* menu = new QMenu(this);
    if (measurements_ != nullptr) {
        addLesionActions(*menu, *measurements_, id,
                         choices_ ? choices_(measurements_->seriesUid())
                                  : std::vector<LesionChoice>());
    }
    return menu;
}

void MeasurementList::showSelection() {
    const std::uint64_t id = measurements_ != nullptr ? measurements_->selected() : 0;
    int row = -1;
    for (int r = 0; r < table_->rowCount(); ++r) {
        row = idAt(r) == id && id != 0 ? r : row;
    }
    if (row < 0) {
        table_->clearSelection();
        table_->setCurrentCell(-1, -1);
    } else if (table_->currentRow() != row) {
        table_->setCurrentCell(row, Kind);
    }
    const Measurement* m = measurements_ != nullptr ? measurements_->find(id) : nullptr;
    delete_->setEnabled(m != nullptr && !m->readOnly);
}

void MeasurementList::rowClicked(int row) {
    const std::uint64_t id = idAt(row);
    if (measurements_ == nullptr || measurements_->find(id) == nullptr) {
        return;
    }
    measurements_->select(id);
    showMeasurement(*cursor_, *measurements_->find(id));
}

void MeasurementList::cellEdited(int row, int column) {
    if (refreshing_ || (column != Name && column != Value) || measurements_ == nullptr) {
        return;
    }
    const std::uint64_t id = idAt(row);
    const std::string text = table_->item(row, column)->text().trimmed().toStdString();
    // After the edit has ended: the edit rebuilds the rows, the edited item with them.
    // A refused one (read-only, unchanged) puts the stored text back.
    QMetaObject::invokeMethod(
        this,
        [this, id, text, column] {
            const Measurement* m = measurements_ != nullptr ? measurements_->find(id) : nullptr;
            if (m == nullptr) {
                return;
            }
            bool done = false;
            if (column == Name) {
                done = measurements_->rename(id, text);
            } else if (m->text != text) { // an arrow's text
                Measurement arrow = *m;
                arrow.text = text;
                done = measurements_->change(arrow);
            }
            if (!done) {
                refresh();
            }
        },
        Qt::QueuedConnection);
}

void MeasurementList::deleteSelected() {
    const std::uint64_t id = idAt(table_->currentRow());
    if (measurements_ != nullptr && id != 0) {
        measurements_->remove(id);
    }
}

} // namespace lucent
