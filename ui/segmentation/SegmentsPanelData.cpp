// SegmentsPanel: the statistics table and its CSV, and labelmap NIfTI export and import.
#include <QApplication>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <exception>

#include "core/formats/Nifti.h"
#include "core/formats/NiftiWrite.h"
#include "core/segmentation/Labelmap.h"
#include "core/segmentation/SegmentStatistics.h"
#include "ui/segmentation/SegmentationSession.h"
#include "ui/segmentation/SegmentsPanel.h"

namespace lucent {
namespace {

QString shown(double value, int decimals) {
    return std::isnan(value) ? QStringLiteral("-") : QString::number(value, 'f', decimals);
}

std::filesystem::path pathOf(const QString& file) {
    return std::filesystem::path(file.toStdU16String());
}

} // namespace

QWidget* SegmentsPanel::makeDataControls() {
    auto* box = new QGroupBox(tr("Statistics and files"), this);
    auto* column = new QVBoxLayout(box);
    statistics_ = new QTableWidget(0, 10, box);
    statistics_->setHorizontalHeaderLabels(
        {tr("Segment"), tr("Voxels"), tr("Volume mL"), tr("Mean"), tr("SD"), tr("Min"), tr("Max"),
         tr("Median"), tr("Surface cm²"), tr("Largest diameter mm")});
    statistics_->verticalHeader()->hide();
    statistics_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    statistics_->setMinimumHeight(90);
    column->addWidget(statistics_);
    auto* row = new QHBoxLayout;
    auto* compute = new QPushButton(tr("Compute"), box);
    connect(compute, &QPushButton::clicked, this, [this] { computeStatistics(); });
    auto* csv = new QPushButton(tr("CSV..."), box);
    csv->setToolTip(tr("Export the statistics as CSV"));
    connect(csv, &QPushButton::clicked, this, [this] {
        const QString file = QFileDialog::getSaveFileName(this, tr("Export statistics"), QString(),
                                                          tr("CSV (*.csv)"));
        if (!file.isEmpty()) {
            exportStatisticsCsv(file);
        }
    });
    auto* save = new QPushButton(tr("Export NIfTI..."), box);
    connect(save, &QPushButton::clicked, this, [this] {
        const QString file = QFileDialog::getSaveFileName(this, tr("Export labelmap"), QString(),
                                                          tr("NIfTI (*.nii.gz *.nii)"));
        if (!file.isEmpty()) {
            exportLabelmap(file);
        }
    });
    auto* open = new QPushButton(tr("Import NIfTI..."), box);
    connect(open, &QPushButton::clicked, this, [this] {
        const QString file = QFileDialog::getOpenFileName(this, tr("Import labelmap"), QString(),
                                                          tr("NIfTI (*.nii.gz *.nii)"));
        if (!file.isEmpty()) {
            importLabelmap(file);
        }
    });
    for (QPushButton* b : {compute, csv, save, open}) {
        row->addWidget(b);
    }
    column->addLayout(row);
    return box;
}

std::vector<NamedStatistics> SegmentsPanel::computeStatistics() {
    std::vector<NamedStatistics> rows;
    if (!session_) {
        say(tr("The active viewport shows no volume"));
        return rows;
    }
    QApplication::setOverrideCursor(Qt::WaitCursor);
    for (const Segment& s : session_->segmentation().segments()) {
        rows.push_back({s.name, segmentStatistics(*s.mask, *session_->volume())});
    }
    QApplication::restoreOverrideCursor();
    statistics_->setRowCount(static_cast<int>(rows.size()));
    for (int r = 0; r < static_cast<int>(rows.size()); ++r) {
        const SegmentStatistics& s = rows[static_cast<std::size_t>(r)].statistics;
        const QStringList cells{QString::fromStdString(rows[static_cast<std::size_t>(r)].name),
                                QString::number(s.voxels),
                                shown(s.volumeMl, 3),
                                shown(s.mean, 1),
                                shown(s.standardDeviation, 1),
                                shown(s.minimum, 0),
                                shown(s.maximum, 0),
                                shown(s.median, 0),
                                shown(s.surfaceAreaCm2, 2),
                                shown(s.largestDiameterMm, 1)};
        for (int c = 0; c < cells.size(); ++c) {
            statistics_->setItem(r, c, new QTableWidgetItem(cells[c]));
        }
    }
    return rows;
}

bool SegmentsPanel::exportStatisticsCsv(const QString& path) {
    if (!session_) {
        say(tr("The active viewport shows no volume"));
        return false;
    }
    const std::string csv = statisticsCsv(computeStatistics());
    QFile file(path);
    if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate) ||
        file.write(csv.data(), static_cast<qint64>(csv.size())) !=
            static_cast<qint64>(csv.size())) {
        say(tr("Cannot write %1: %2").arg(path, file.errorString()));
        return false;
    }
    say(tr("Statistics written to %1").arg(path));
    return true;
}

bool SegmentsPanel::exportLabelmap(const QString& path) {
    if (!session_ || session_->segmentation().segments().empty()) {
        say(tr("Not written: %1: no segment to export").arg(path));
        return false;
    }
    try {
        writeNifti(pathOf(path), labelmapOf(session_->segmentation()));
    } catch (const std::exception& e) {
        say(tr("Cannot write %1: %2").arg(path, QString::fromUtf8(e.what())));
        return false;
    }
    say(tr("Labelmap written to %1").arg(path));
    return true;
}

bool SegmentsPanel::importLabelmap(const QString& path) {
    if (!session_) {
        say(tr("Not imported: %1: the active viewport shows no volume").arg(path));
        return false;
    }
    try {
        const Volume labels = readNifti(pathOf(path));
        const VolumeGeometry& grid = session_->segmentation().geometry();
        const VolumeGeometry& theirs = labels.geometry();
        // The same voxels in the same place: dims, and the first and last voxel centres
        // within a tenth of a voxel (NIfTI keeps floats).
        const double slack = 0.1 * std::min({grid.spacing.x, grid.spacing.y, grid.spacing.z});
        const glm::dvec3 last(grid.dims - 1);
        if (theirs.dims != grid.dims ||
            glm::length(theirs.toPatient(glm::dvec3(0.0)) - grid.toPatient(glm::dvec3(0.0))) >
                slack ||
            glm::length(theirs.toPatient(last) - grid.toPatient(last)) > slack) {
            say(tr("Not imported: %1 lies on another grid than the series").arg(path));
            return false;
        }
        const std::vector<std::uint32_t> ids =
            lucent::importLabelmap(session_->segmentation(), labels);
        session_->notifyChanged();
        say(tr("Imported %1 segments from %2").arg(ids.size()).arg(QFileInfo(path).fileName()));
    } catch (const std::exception& e) {
        say(tr("Cannot import %1: %2").arg(path, QString::fromUtf8(e.what())));
        return false;
    }
    return true;
}

} // namespace lucent
