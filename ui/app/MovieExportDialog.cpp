#include "ui/app/MovieExportDialog.h"

#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QStandardPaths>

#include "core/movie/MovieFrames.h"
#include "core/movie/MovieWriter.h"
#include "render/RenderDevice.h"

namespace lucent {
namespace {

constexpr int kDefaultTurntableFrames = 72;

QSpinBox* spinBox(int lo, int hi, int value, QWidget* parent) {
    auto* box = new QSpinBox(parent);
    box->setRange(lo, hi);
    box->setValue(value);
    return box;
}

// 4:2:0 movies need even sides: the view's size rounded down to even.
int evenSide(int side) {
    return std::clamp(side - side % 2, 16, 4096);
}

} // namespace

MovieExportDialog::MovieExportDialog(std::shared_ptr<const Volume> volume,
                                     const RenderDescription& start, const WindowLevel& window,
                                     QWidget* parent)
    : BackgroundExportDialog(parent), volume_(std::move(volume)), start_(start), window_(window),
      kind_(new QComboBox(this)), frames_(spinBox(0, 10000, kDefaultTurntableFrames, this)),
      degrees_(new QDoubleSpinBox(this)), axis_(new QComboBox(this)),
      width_(spinBox(16, 4096, evenSide(start.width), this)),
      height_(spinBox(16, 4096, evenSide(start.height), this)), fps_(spinBox(1, 120, 25, this)),
      output_(new QLineEdit(this)) {
    setWindowTitle(tr("Export movie"));
    kind_->addItems({tr("Turntable of the 3D view"), tr("Cine through the slices")});
    degrees_->setRange(-3600.0, 3600.0);
    degrees_->setValue(360.0);
    degrees_->setSuffix(tr(" degrees"));
    axis_->addItems({tr("i (columns)"), tr("j (rows)"), tr("k (slices)")});
    axis_->setCurrentIndex(2);
    width_->setSingleStep(2);
    height_->setSingleStep(2);
    const QString movies = QStandardPaths::writableLocation(QStandardPaths::MoviesLocation);
    output_->setText(QDir(movies.isEmpty() ? QDir::homePath() : movies)
                         .filePath(QStringLiteral("lucent-movie.mp4")));
    output_->setPlaceholderText(tr("a file ending in .mp4, .webm or .gif"));

    auto* browse = new QPushButton(tr("&Browse..."), this);
    auto* where = new QHBoxLayout;
    where->addWidget(output_, 1);
    where->addWidget(browse);
    auto* size = new QHBoxLayout;
    size->addWidget(width_);
    size->addWidget(new QLabel(QStringLiteral("x"), this));
    size->addWidget(height_);
    size->addStretch(1);
    auto* form = new QFormLayout(this);
    form->addRow(tr("Movie"), kind_);
    form->addRow(tr("Frames"), frames_);
    form->addRow(tr("Turn"), degrees_);
    form->addRow(tr("Along axis"), axis_);
    form->addRow(tr("Size (pixels)"), size);
    form->addRow(tr("Frames per second"), fps_);
    form->addRow(tr("To"), where);
    addExportRows(form);
    kindChanged();
    connect(kind_, &QComboBox::currentIndexChanged, this, &MovieExportDialog::kindChanged);
    connect(browse, &QPushButton::clicked, this, &MovieExportDialog::browse);
}

void MovieExportDialog::kindChanged() {
    const bool cine = kind_->currentIndex() == 1;
    degrees_->setEnabled(!cine);
    axis_->setEnabled(cine);
    // A cine shows every slice unless told how many frames.
    frames_->setSpecialValueText(cine ? tr("every slice") : QString());
    frames_->setMinimum(cine ? 0 : 1);
    frames_->setValue(cine ? 0 : kDefaultTurntableFrames);
}

void MovieExportDialog::browse() {
    const QString chosen = QFileDialog::getSaveFileName(
        this, tr("Export movie to"), output_->text(),
        tr("MP4, H.264 (*.mp4);;WebM, VP9 (*.webm);;Animated GIF (*.gif)"));
    if (!chosen.isEmpty()) {
        output_->setText(chosen);
    }
}

void MovieExportDialog::start() {
    if (!volume_) {
        return;
    }
    const std::string target = output_->text().trimmed().toStdString();
    const MovieSettings settings{width_->value(), height_->value(), fps_->value()};
    std::unique_ptr<MovieWriter> writer;
    try { // format, size and folder, before any frame is rendered
        writer = std::make_unique<MovieWriter>(target, settings);
    } catch (const MovieError& e) {
        status()->setText(QString::fromStdString(e.what()));
        return;
    }
    const bool cine = kind_->currentIndex() == 1;
    const IndexAxis axis = IndexAxis(axis_->currentIndex());
    const int frameCount = frames_->value();
    const double degrees = degrees_->value();
    RenderDescription first = start_;
    first.volume = volume_.get();
    first.width = settings.width;
    first.height = settings.height;
    // The writer goes with the job: an unfinished movie's temporary file is
    // removed before the outcome is reported.
    startJob(tr("Rendering..."), [this, writer = std::move(writer), cine, axis, frameCount, degrees,
                                  first, settings, volume = volume_, window = window_,
                                  target](std::stop_token stop) mutable {
        std::unique_ptr<RenderDevice> device;
        std::unique_ptr<Renderer> renderer;
        std::unique_ptr<MovieFrames> frames;
        if (cine) {
            frames = std::make_unique<CineFrames>(*volume, axis, frameCount, window, settings.width,
                                                  settings.height);
        } else {
            // This thread's own context: the GPU where it can be had, else the CPU.
            device = RenderDevice::open(RendererKind::Gl);
            renderer = device->openRenderer(*volume).renderer;
            frames = std::make_unique<TurntableFrames>(*renderer, first, degrees, frameCount);
        }
        const bool ok = writeMovie(*frames, *writer, [this, &stop](int doneFrames, int total) {
            reportProgress(doneFrames, total);
            return !stop.stop_requested();
        });
        return ExportOutcome{ok, ok ? tr("Wrote %1: %2 frames, %3 x %4")
                                          .arg(QString::fromStdString(target))
                                          .arg(writer->framesWritten())
                                          .arg(settings.width)
                                          .arg(settings.height)
                                    : tr("Cancelled; nothing was written.")};
    });
}

} // namespace lucent
