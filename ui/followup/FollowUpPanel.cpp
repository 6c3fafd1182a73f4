#include "ui/followup/FollowUpPanel.h"

#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include "core/followup/FollowUpCollection.h"
#include "core/followup/FollowUpText.h"
#include "core/report/MeasurementArchive.h"
#include "core/store/StudyStore.h"
#include "ui/theme/Theme.h"

namespace lucent {

namespace {

// A store only where one was made: showing the panel makes none.
bool storeExists(const QString& folder) {
    return !folder.isEmpty() &&
           QFileInfo::exists(QDir(folder).filePath(QStringLiteral("index.sqlite")));
}

} // namespace

FollowUpPanel::FollowUpPanel(QWidget* parent)
    : QWidget(parent), grid_(new QTableWidget(this)),
      export_(new QPushButton(tr("Export CSV..."), this)), status_(new QLabel(this)) {
    grid_->setObjectName(QStringLiteral("followUpTable"));
    grid_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    grid_->setSelectionBehavior(QAbstractItemView::SelectRows);
    grid_->setSelectionMode(QAbstractItemView::SingleSelection);
    grid_->verticalHeader()->hide();
    grid_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    status_->setObjectName(QStringLiteral("followUpStatus"));
    status_->setWordWrap(true);
    export_->setToolTip(tr("Save the follow-up table as a CSV file"));
    connect(export_, &QPushButton::clicked, this, &FollowUpPanel::exportClicked);
    connect(grid_, &QTableWidget::cellClicked, this, [this](int row, int) { cellClicked(row); });

    auto* buttons = new QHBoxLayout;
    buttons->addStretch(1);
    buttons->addWidget(export_);
    auto* column = new QVBoxLayout(this);
    column->setContentsMargins(2, 2, 2, 2);
    column->addWidget(status_);
    column->addWidget(grid_, 1);
    column->addLayout(buttons);
    showTable();
}

FollowUpPanel::~FollowUpPanel() = default;

void FollowUpPanel::setStoreFolder(const QString& folder) {
    archive_.reset();
    store_.reset();
    folder_ = folder;
    refresh();
}

void FollowUpPanel::showPatient(const QString& patientId) {
    patientId_ = patientId;
    refresh();
}

void FollowUpPanel::refresh() {
    table_ = {};
    QString problem;
    if (patientId_.isEmpty()) {
        problem = tr("No patient open");
    } else if (!storeExists(folder_)) {
        problem = tr("No study store: measurements are followed over the studies kept there");
    } else {
        try {
            if (!archive_) {
                store_ = std::make_unique<StudyStore>(folder_.toStdString());
                archive_ = std::make_unique<MeasurementArchive>(*store_);
            }
            const FollowUpSources sources =
                collectFollowUp(*store_, *archive_, patientId_.toStdString());
            table_ = assessRecist(sources.timepoints);
            QStringList lines;
            for (const std::string& p : sources.problems) {
                lines << QString::fromStdString(p);
            }
            problem = lines.join('\n');
        } catch (const std::exception& e) {
            problem = QString::fromUtf8(e.what());
        }
    }
    status_->setText(problem.isEmpty() ? tr("%1: %2 timepoint(s), %3 tracked lesion(s)")
                                             .arg(patientId_)
                                             .arg(table_.timepoints.size())
                                             .arg(table_.lesions.size())
                                       : problem);
    showTable();
}

void FollowUpPanel::showTable() {
    const FollowUpGrid grid = followUpGrid(table_);
    const std::vector<std::string>& header = grid.rows.front();
    grid_->clear();
    grid_->setColumnCount(static_cast<int>(header.size()));
    grid_->setRowCount(static_cast<int>(grid.rows.size()) - 1);
    QStringList labels;
    for (const std::string& h : header) {
        labels << QString::fromStdString(h);
    }
    grid_->setHorizontalHeaderLabels(labels);
    const std::size_t lesions = table_.lesions.size();
    QFont summary = grid_->font();
    summary.setBold(true);
    for (std::size_t r = 1; r < grid.rows.size(); ++r) {
        const std::size_t t0 = FollowUpGrid::kLabelColumns;
        for (std::size_t c = 0; c < grid.rows[r].size(); ++c) {
            auto* item = new QTableWidgetItem(QString::fromStdString(grid.rows[r][c]));
            if (r > lesions) {
                item->setFont(summary);
                if (c >= t0 && table_.timepoints[c - t0].response == RecistResponse::PD &&
                    r == lesions + 4) { // the response row
                    item->setForeground(statusColour(StatusTone::Error, palette()));
                }
            } else if (c >= t0 && table_.lesions[r - 1].at[c - t0]) {
                const LesionObservation& o = *table_.lesions[r - 1].at[c - t0];
                item->setToolTip(tr("Long axis %1 mm, short axis %2 mm\nSeries %3")
                                     .arg(o.longAxisMm, 0, 'f', 1)
                                     .arg(o.shortAxisMm, 0, 'f', 1)
                                     .arg(QString::fromStdString(o.where.seriesUid)));
            }
            grid_->setItem(static_cast<int>(r) - 1, static_cast<int>(c), item);
        }
    }
    export_->setEnabled(!table_.timepoints.empty());
}

void FollowUpPanel::cellClicked(int row) {
    if (row < 0 || static_cast<std::size_t>(row) >= table_.lesions.size()) {
        return;
    }
    const LesionRow& lesion = table_.lesions[static_cast<std::size_t>(row)];
    std::vector<LesionLocation> where;
    for (const std::optional<LesionObservation>& o : lesion.at) {
        if (o) {
            where.push_back(o->where);
        }
    }
    emit lesionActivated(QString::fromStdString(lesion.trackingUid), where);
}

std::vector<LesionChoice> FollowUpPanel::earlierLesions(const std::string& seriesUid) const {
    std::string date;
    try {
        date = store_ ? studyDateOf(*store_, seriesUid) : std::string();
    } catch (const std::exception&) {
        // The index cannot be read: every lesion is offered, as for an unknown date.
    }
    std::vector<LesionChoice> out;
    for (const LesionRow* row : lesionsBefore(table_, date)) {
        out.push_back({row->trackingUid, row->name, row->role, row->lymphNode,
                       table_.timepoints[row->firstTimepoint].studyDate});
    }
    return out;
}

bool FollowUpPanel::exportCsv(const QString& file, QString* error) const {
    QFile out(file);
    const std::string csv = followUpCsv(table_);
    if (!out.open(QIODevice::WriteOnly | QIODevice::Truncate) ||
        out.write(csv.data(), static_cast<qint64>(csv.size())) != static_cast<qint64>(csv.size()) ||
        !out.flush()) {
        if (error != nullptr) {
            *error = tr("%1: cannot write the table (%2)").arg(file, out.errorString());
        }
        return false;
    }
    return true;
}

void FollowUpPanel::exportClicked() {
    const QString file = QFileDialog::getSaveFileName(
        this, tr("Export Follow-up Table"),
        QDir::home().filePath(QStringLiteral("recist-%1.csv").arg(patientId_)),
        tr("CSV files (*.csv)"));
    QString error;
    if (!file.isEmpty() && !exportCsv(file, &error)) {
        status_->setText(error);
    }
}

} // namespace lucent
