#include "ui/volume/SurfacePanel.h"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include "core/formats/MeshFiles.h"
#include "core/scene/SurfaceDisplay.h"
#include "core/tf/VolumeHistogram.h"
#include "ui/volume/IsoHistogram.h"
#include "ui/volume/SurfaceJob.h"
#include "ui/volume/VolumeView.h"

namespace lucent {
namespace {

constexpr double kBoneHu = 300.0;

} // namespace

SurfacePanel::SurfacePanel(VolumeView* view, QWidget* parent) : QWidget(parent), view_(view) {
    histogram_ = new IsoHistogram(this);
    iso_ = new QDoubleSpinBox(this);
    iso_->setDecimals(1);
    iso_->setRange(-1e6, 1e6);
    iso_->setValue(kBoneHu);
    iso_->setToolTip(tr("A voxel at or above this value is inside (HU for CT)"));
    radius_ = new QDoubleSpinBox(this);
    radius_->setRange(0.0, 100.0);
    radius_->setDecimals(1);
    radius_->setValue(5.0);
    radius_->setSuffix(tr(" mm"));
    radius_->setSpecialValueText(tr("none"));
    radius_->setToolTip(tr("Radius of the balls of the method of spheres (0: no field)"));
    smooth_ = new QSpinBox(this);
    smooth_->setRange(0, 100);
    smooth_->setSpecialValueText(tr("off"));
    smooth_->setToolTip(tr("Windowed-sinc smoothing iterations (keeps the volume)"));
    largest_ = new QSpinBox(this);
    largest_->setRange(0, 1000);
    largest_->setSpecialValueText(tr("all"));
    largest_->setToolTip(tr("Keep only the largest parts (specks give extreme SVR values)"));
    compute_ = new QPushButton(tr("Compute"), this);
    export_ = new QPushButton(tr("Export..."), this);
    clear_ = new QPushButton(tr("Clear"), this);
    colourByField_ = new QCheckBox(tr("Colour by SVR"), this);
    colourByField_->setChecked(true);
    showVolume_ = new QCheckBox(tr("Show the volume"), this);
    showVolume_->setChecked(true);
    progress_ = new QProgressBar(this);
    progress_->setRange(0, 1000);
    progress_->setVisible(false);
    status_ = new QLabel(this);
    status_->setWordWrap(true);
    status_->setTextInteractionFlags(Qt::TextSelectableByMouse);

    auto* form = new QFormLayout;
    form->addRow(tr("Iso value"), iso_);
    form->addRow(histogram_);
    form->addRow(tr("Smoothing"), smooth_);
    form->addRow(tr("Keep largest"), largest_);
    form->addRow(tr("SVR radius"), radius_);
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(compute_);
    buttons->addWidget(export_);
    buttons->addWidget(clear_);
    auto* column = new QVBoxLayout(this);
    column->setContentsMargins(0, 0, 0, 0);
    column->addLayout(form);
    column->addLayout(buttons);
    column->addWidget(progress_);
    column->addWidget(colourByField_);
    column->addWidget(showVolume_);
    column->addWidget(status_);
    column->addStretch(1);

    connect(histogram_, &IsoHistogram::isoValueChosen, iso_, &QDoubleSpinBox::setValue);
    connect(iso_, &QDoubleSpinBox::valueChanged, histogram_, &IsoHistogram::setIsoValue);
    connect(compute_, &QPushButton::clicked, this, &SurfacePanel::computeOrCancel);
    connect(export_, &QPushButton::clicked, this, &SurfacePanel::exportDialog);
    connect(clear_, &QPushButton::clicked, this, &SurfacePanel::clear);
    connect(colourByField_, &QCheckBox::toggled, this, &SurfacePanel::showResult);
    connect(showVolume_, &QCheckBox::toggled, this, &SurfacePanel::showResult);
    connect(view_, &VolumeView::volumeChanged, this, &SurfacePanel::volumeChanged);
    volumeChanged();
}

SurfacePanel::~SurfacePanel() = default;

bool SurfacePanel::computing() const {
    return job_ && job_->running();
}

QString SurfacePanel::status() const {
    return status_->text();
}

void SurfacePanel::setStatus(const QString& text) {
    status_->setText(text);
}

void SurfacePanel::volumeChanged() {
    job_.reset();
    clear();
    const auto& volume = view_->volume();
    const bool any = volume && !volume->empty();
    compute_->setEnabled(any);
    if (!any) {
        histogram_->setHistogram({});
        return;
    }
    histogram_->setHistogram(computeHistogram(*volume, 128));
    const auto [lo, hi] = volume->valueRange();
    iso_->setRange(lo, hi);
    iso_->setValue(volume->modality == "CT" && kBoneHu > lo && kBoneHu < hi ? kBoneHu
                                                                            : 0.5 * (lo + hi));
    histogram_->setIsoValue(iso_->value());
}

void SurfacePanel::computeOrCancel() {
    if (computing()) {
        job_->cancel();
        setStatus(tr("Cancelling..."));
        return;
    }
    const auto& volume = view_->volume();
    if (!volume || volume->empty()) {
        return;
    }
    SurfaceRequest request;
    request.iso = iso_->value();
    request.clip = view_->clipBox();
    request.keepLargest = std::size_t(largest_->value());
    request.minComponentVoxels = largest_->value() == 0 ? 10.0 : 0.0; // specks out
    request.smoothIterations = smooth_->value();
    request.svrRadius = radius_->value();
    job_ = std::make_unique<SurfaceJob>(volume, request);
    connect(job_.get(), &SurfaceJob::progress, this, [this](double fraction, const QString& step) {
        progress_->setValue(int(fraction * 1000.0));
        progress_->setFormat(step + " %p%");
    });
    connect(job_.get(), &SurfaceJob::finished, this, &SurfacePanel::finished);
    progress_->setValue(0);
    progress_->setVisible(true);
    compute_->setText(tr("Cancel"));
    setStatus(tr("Computing..."));
    job_->start();
}

void SurfacePanel::finished(std::shared_ptr<const SurfaceResult> result, const QString& error,
                            bool cancelled) {
    progress_->setVisible(false);
    compute_->setText(tr("Compute"));
    if (!result) {
        setStatus(cancelled ? tr("Cancelled.") : tr("No surface: %1").arg(error));
        emit computed(false);
        return;
    }
    result_ = std::move(result);
    resultRadius_ = result_->svr ? result_->svr->radius : 0.0;
    const MeshReport& m = result_->report;
    QString text = tr("%L1 triangles, %L2 mm², %L3 cm³, %4, %5 part(s) (%6 dropped); %7 ms")
                       .arg(m.triangles)
                       .arg(m.area, 0, 'f', 0)
                       .arg(m.volume / 1000.0, 0, 'f', 1)
                       .arg(m.closedManifold() ? tr("closed") : tr("NOT closed"))
                       .arg(m.components)
                       .arg(result_->componentsDropped)
                       .arg(result_->extractMs + result_->cleanupMs + result_->svrMs, 0, 'f', 0);
    if (result_->svr) {
        const auto [lo, hi] = surfaceFieldRange(*result_->svr);
        text += tr("\nSVR at R = %1 mm: %2 to %3 /mm (5th to 95th percentile), whole %4 /mm; "
                   "h_max/R = %5")
                    .arg(resultRadius_)
                    .arg(lo, 0, 'g', 3)
                    .arg(hi, 0, 'g', 3)
                    .arg(result_->svr->totalRatio, 0, 'g', 3)
                    .arg(result_->svr->longestEdgeOverRadius, 0, 'f', 2);
    }
    for (const std::string& w : result_->warnings) {
        text += "\n" + tr("Warning: %1").arg(QString::fromStdString(w));
    }
    setStatus(text);
    showResult();
    emit computed(true);
}

void SurfacePanel::showResult() {
    if (!result_) {
        view_->setSurfaceDisplay(nullptr, 0.0);
        return;
    }
    auto display = std::make_shared<SurfaceDisplay>();
    display->mesh = std::shared_ptr<const TriangleMesh>(result_, &result_->mesh);
    if (result_->svr && colourByField_->isChecked()) {
        auto field = std::make_shared<std::vector<float>>(result_->svr->svr.begin(),
                                                          result_->svr->svr.end());
        display->field = std::move(field);
        std::tie(display->fieldLo, display->fieldHi) = surfaceFieldRange(*result_->svr);
    }
    display->showVolume = showVolume_->isChecked();
    view_->setSurfaceDisplay(std::move(display), resultRadius_);
}

void SurfacePanel::clear() {
    if (computing()) {
        job_->cancel();
    }
    result_.reset();
    setStatus(QString());
    view_->setSurfaceDisplay(nullptr, 0.0);
}

bool SurfacePanel::exportTo(const QString& file) {
    if (!result_) {
        setStatus(tr("Nothing to export: compute a surface first."));
        return false;
    }
    try {
        writeMesh(result_->mesh, file.toStdString(), meshFormatOf(file.toStdString()),
                  surfaceFileContent(*result_, iso_->value()));
    } catch (const std::exception& e) {
        setStatus(tr("Export failed: %1").arg(QString::fromUtf8(e.what())));
        return false;
    }
    setStatus(status_->text() + "\n" + tr("Exported to %1").arg(file));
    return true;
}

void SurfacePanel::exportDialog() {
    const QString file = QFileDialog::getSaveFileName(
        this, tr("Export surface"), QString(),
        tr("STL for printing (*.stl);;PLY with SVR (*.ply);;VTK for Slicer and ParaView (*.vtk);;"
           "OBJ (*.obj)"));
    if (!file.isEmpty()) {
        (void)exportTo(file);
    }
}

} // namespace lucent
