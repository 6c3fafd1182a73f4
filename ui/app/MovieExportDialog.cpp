#include "ui/app/MovieExportDialog.h"

#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
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
    : QDialog(parent), volume_(std::move(volume)), start_(start), window_(window),
      kind_(new QComboBox(this)), frames_(spinBox(0, 10000, kDefaultTurntableFrames, this)),
      degrees_(new QDoubleSpinBox(this)), axis_(new QComboBox(this)),
      width_(spinBox(16, 4096, evenSide(start.width), this)),
      height_(spinBox(16, 4096, evenSide(start.height), this)), fps_(spinBox(1, 120, 25, this)),
      output_(new QLineEdit(this)), bar_(new QProgressBar(this)), status_(new QLabel(this)),
      export_(new QPushButton(tr("&Export"), this)), close_(new QPushButton(tr("Close"), this)) {
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
    status_->setWordWrap(true);
    export_->setDefault(true);

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
    form->addRow(bar_);
    form->addRow(status_);
    auto* buttons = new QHBoxLayout;
    buttons->addStretch(1);
    buttons->addWidget(export_);
    buttons->addWidget(close_);
    form->addRow(buttons);
    kindChanged();
    connect(kind_, &QComboBox::currentIndexChanged, this, &MovieExportDialog::kindChanged);
    connect(browse, &QPushButton::clicked, this, &MovieExportDialog::browse);
    connect(export_, &QPushButton::clicked, this, &MovieExportDialog::start);
    connect(close_, &QPushButton::clicked, this, [this] {
        if (running_) {
            worker_.request_stop();
            status_->setText(tr("Cancelling..."));
        } else {
            reject();
        }
    });
}

MovieExportDialog::~MovieExportDialog() {
    worker_.request_stop();
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
    if (running_ || !volume_) {
        return;
    }
    const std::string target = output_->text().trimmed().toStdString();
    const MovieSettings settings{width_->value(), height_->value(), fps_->value()};
    std::unique_ptr<MovieWriter> writer;
    try { // format, size and folder, before any frame is rendered
        writer = std::make_unique<MovieWriter>(target, settings);
    } catch (const MovieError& e) {
        status_->setText(QString::fromStdString(e.what()));
        return;
    }
    running_ = true;
    export_->setEnabled(false);
    close_->setText(tr("Cancel"));
    status_->setText(tr("Rendering..."));
    bar_->setRange(0, 0);
    const bool cine = kind_->currentIndex() == 1;
    const IndexAxis axis = IndexAxis(axis_->currentIndex());
    const int frameCount = frames_->value();
    const double degrees = degrees_->value();
    RenderDescription first = start_;
    first.volume = volume_.get();
    first.width = settings.width;
    first.height = settings.height;
    worker_ = std::jthread([this, writer = std::move(writer), cine, axis, frameCount, degrees,
                            first, settings, volume = volume_, window = window_,
                            target](std::stop_token stop) mutable {
        bool ok = false;
        QString message;
        try {
            std::unique_ptr<RenderDevice> device;
            std::unique_ptr<Renderer> renderer;
            std::unique_ptr<MovieFrames> frames;
            if (cine) {
                frames = std::make_unique<CineFrames>(*volume, axis, frameCount, window,
                                                      settings.width, settings.height);
            } else {
                // This thread's own context: the GPU where it can be had, else the CPU.
                device = RenderDevice::open(RendererKind::Gl);
                renderer = device->openRenderer(*volume).renderer;
                frames = std::make_unique<TurntableFrames>(*renderer, first, degrees, frameCount);
            }
            ok = writeMovie(*frames, *writer, [this, &stop](int doneFrames, int total) {
                QMetaObject::invokeMethod(
                    this,
                    [this, doneFrames, total] {
                        bar_->setRange(0, total);
                        bar_->setValue(doneFrames);
                        emit progressed(doneFrames, total);
                    },
                    Qt::QueuedConnection);
                return !stop.stop_requested();
            });
            message = ok ? tr("Wrote %1: %2 frames, %3 x %4")
                               .arg(QString::fromStdString(target))
                               .arg(writer->framesWritten())
                               .arg(settings.width)
                               .arg(settings.height)
                         : tr("Cancelled; nothing was written.");
        } catch (const std::exception& e) {
            message = QString::fromStdString(e.what());
        }
        writer.reset(); // an unfinished movie's temporary file goes before done() reports
        QMetaObject::invokeMethod(
            this, [this, ok, message] { done(ok, message); }, Qt::QueuedConnection);
    });
}

void MovieExportDialog::done(bool ok, const QString& message) {
    running_ = false;
    worker_.join();
    export_->setEnabled(true);
    close_->setText(tr("Close"));
    status_->setText(message);
    if (!ok) {
        bar_->setRange(0, 1);
        bar_->setValue(0);
    }
    emit exportFinished(ok, message);
}

} // namespace lucent
