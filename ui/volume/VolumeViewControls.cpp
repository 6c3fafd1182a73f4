#include "ui/volume/VolumeViewControls.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QEvent>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QSpinBox>
#include <QStandardPaths>
#include <QThread>
#include <QToolButton>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/quality/QualityChoice.h"
#include "render/RenderDevice.h"
#include "ui/volume/RotatingMip.h"
#include "ui/volume/VolumeView.h"

namespace lucent {

namespace {

constexpr RenderMode kModes[] = {RenderMode::Dvr, RenderMode::Mip, RenderMode::MinIp,
                                 RenderMode::Average, RenderMode::Isosurface};
const char* const kModeLabels[] = {"DVR", "MIP", "MinIP", "Average", "Isosurface"};

enum QualityIndex { kManual, kFast, kBalanced, kBest, kTarget };

struct MeasuringCancelled {};

} // namespace

// One front being measured in the background; the thread owns nothing else.
struct VolumeViewControls::Measurement {
    std::string key;
    std::atomic<bool> cancel{false};
    std::optional<MeasuredFront> front;
    std::string note; // the GL context failed and the CPU measured instead, or an error
};

VolumeViewControls::VolumeViewControls(VolumeView* view, QWidget* parent)
    : QWidget(parent), view_(view) {
    presets_ = new QComboBox(this);
    for (const auto& name : presetNames()) {
        presets_->addItem(QString::fromStdString(name));
    }
    modes_ = new QComboBox(this);
    for (const char* label : kModeLabels) {
        modes_->addItem(tr(label));
    }
    iso_ = new QDoubleSpinBox(this);
    iso_->setRange(-100000.0, 100000.0);
    iso_->setValue(view->isoValue());
    iso_->setEnabled(false);
    auto* reset = new QPushButton(tr("Reset view"), this);
    quality_ = new QComboBox(this);
    quality_->addItems({tr("Manual"), tr("Fast (%1 ms)").arg(kFastBudgetMs),
                        tr("Balanced (%1 ms)").arg(kBalancedBudgetMs),
                        tr("Best (%1 ms)").arg(kBestBudgetMs), tr("Target time")});
    quality_->setToolTip(tr("Sampling chosen from this volume's measured speed/accuracy front: "
                            "the most accurate setting within the time per frame"));
    targetMs_ = new QSpinBox(this);
    targetMs_->setRange(1, 60000);
    targetMs_->setValue(100);
    targetMs_->setSuffix(tr(" ms"));
    targetMs_->setEnabled(false);
    qualityStatus_ = new QLabel(this);
    qualityStatus_->setWordWrap(true);
    cacheDir_ = QStandardPaths::writableLocation(QStandardPaths::CacheLocation);

    auto* form = new QFormLayout(this);
    form->setContentsMargins(4, 4, 4, 4);
    form->addRow(tr("Preset"), presets_);
    auto* modeRow = new QHBoxLayout;
    modeRow->addWidget(modes_, 1);
    modeRow->addWidget(iso_);
    form->addRow(tr("Mode"), modeRow);
    auto* qualityRow = new QHBoxLayout;
    qualityRow->addWidget(quality_, 1);
    qualityRow->addWidget(targetMs_);
    form->addRow(tr("Quality"), qualityRow);
    form->addRow(qualityStatus_);
    const char* const axes[] = {"Clip i", "Clip j", "Clip k"};
    for (int axis = 0; axis < 3; ++axis) {
        auto* row = new QHBoxLayout;
        for (int end = 0; end < 2; ++end) {
            auto* s = new QSlider(Qt::Horizontal, this);
            clip_[static_cast<std::size_t>(2 * axis + end)] = s;
            row->addWidget(s);
            connect(s, &QSlider::valueChanged, this, &VolumeViewControls::applyClip);
        }
        form->addRow(tr(axes[axis]), row);
    }
    auto* handles = new QCheckBox(tr("Clip box handles in the view (B)"), this);
    handles->setObjectName(QStringLiteral("clipHandles"));
    form->addRow(handles);
    connect(handles, &QCheckBox::toggled, view_, &VolumeView::setClipHandlesShown);
    connect(view_, &VolumeView::clipHandlesShownChanged, handles, &QCheckBox::setChecked);
    auto* rotating = new QToolButton(this);
    rotating->setDefaultAction(view_->rotatingMip()->action());
    rotating->setToolButtonStyle(Qt::ToolButtonTextOnly);
    auto* viewRow = new QHBoxLayout;
    viewRow->addWidget(reset, 1);
    viewRow->addWidget(rotating, 1);
    form->addRow(viewRow);

    connect(presets_, &QComboBox::activated, this, [this](int index) {
        try {
            view_->setTransferFunction(loadPreset(presets_->itemText(index).toStdString()));
        } catch (const std::exception& e) {
            presets_->setToolTip(QString::fromStdString(e.what()));
        }
    });
    connect(view_, &VolumeView::transferFunctionChanged, this, [this](const TransferFunction& tf) {
        const QSignalBlocker blocker(presets_);
        presets_->setCurrentIndex(presets_->findText(QString::fromStdString(tf.name)));
    });
    connect(modes_, &QComboBox::currentIndexChanged, this, [this](int index) {
        const RenderMode mode = kModes[std::clamp(index, 0, 4)];
        iso_->setEnabled(mode == RenderMode::Isosurface);
        view_->setMode(mode);
        updateQuality(); // each mode has its own front
    });
    // The view's mode set elsewhere (the rotating MIP, a PET series opening in MIP).
    connect(view_, &VolumeView::modeChanged, this, [this](RenderMode mode) {
        const auto index = std::find(std::begin(kModes), std::end(kModes), mode) - kModes;
        if (index != modes_->currentIndex()) {
            modes_->setCurrentIndex(static_cast<int>(index)); // iso and quality follow
        }
    });
    connect(quality_, &QComboBox::currentIndexChanged, this, [this](int index) {
        targetMs_->setEnabled(index == kTarget);
        updateQuality();
    });
    connect(targetMs_, &QSpinBox::valueChanged, this, [this] {
        if (quality_->currentIndex() == kTarget) {
            updateQuality();
        }
    });
    // Shading on or off is another front; the choice follows the TF.
    connect(view_, &VolumeView::transferFunctionChanged, this, &VolumeViewControls::updateQuality);
    connect(view_, &VolumeView::backendChanged, this, &VolumeViewControls::updateQuality);
    view_->installEventFilter(this);
    connect(iso_, &QDoubleSpinBox::valueChanged, view_, &VolumeView::setIsoValue);
    connect(reset, &QPushButton::clicked, view_, &VolumeView::resetCamera);
    connect(view_, &VolumeView::volumeChanged, this, &VolumeViewControls::volumeChanged);
    // Faces dragged in the view move the sliders (without sending the box back).
    connect(view_, &VolumeView::clipBoxChanged, this, [this](const ClipBox& clip) {
        for (int axis = 0; axis < 3; ++axis) {
            for (int end = 0; end < 2; ++end) {
                QSlider* s = clipSlider(axis, end);
                const double value = end == 0 ? clip.lo[axis] : clip.hi[axis];
                const QSignalBlocker blocker(s);
                s->setValue(int(
                    std::lround(std::clamp(value, double(s->minimum()), double(s->maximum())))));
            }
        }
    });
    volumeChanged();
}

VolumeViewControls::~VolumeViewControls() {
    if (thread_) {
        measuring_->cancel = true;
        thread_->wait();
    }
}

QSlider* VolumeViewControls::clipSlider(int axis, int end) const {
    return clip_.at(static_cast<std::size_t>(2 * axis + end));
}

void VolumeViewControls::volumeChanged() {
    const auto& volume = view_->volume();
    const glm::ivec3 dims = volume ? volume->dims() : glm::ivec3(1);
    for (int axis = 0; axis < 3; ++axis) {
        for (int end = 0; end < 2; ++end) {
            QSlider* s = clipSlider(axis, end);
            const QSignalBlocker blocker(s);
            s->setRange(0, std::max(0, dims[axis] - 1));
            s->setValue(end == 0 ? 0 : dims[axis] - 1);
            s->setEnabled(volume != nullptr);
        }
    }
    const QSignalBlocker blocker(presets_);
    presets_->setCurrentIndex(
        presets_->findText(QString::fromStdString(view_->transferFunction().name)));
    updateQuality();
}

void VolumeViewControls::applyClip() {
    ClipBox clip;
    for (int axis = 0; axis < 3; ++axis) {
        const int first = clipSlider(axis, 0)->value();
        const int last = clipSlider(axis, 1)->value();
        clip.lo[axis] = std::min(first, last);
        clip.hi[axis] = std::max(first, last);
    }
    view_->setClipBox(clip);
}

} // namespace lucent

namespace lucent {

QString VolumeViewControls::qualityStatus() const {
    return qualityStatus_->text();
}

void VolumeViewControls::setQualityCacheDir(const QString& dir) {
    cacheDir_ = dir;
}

bool VolumeViewControls::eventFilter(QObject* watched, QEvent* event) {
    if (watched == view_ && event->type() == QEvent::Resize &&
        quality_->currentIndex() != kManual) {
        updateQuality();
    }
    return QWidget::eventFilter(watched, event);
}

void VolumeViewControls::setQualityStatus(const QString& text) {
    qualityStatus_->setText(text);
    qualityStatus_->setVisible(!text.isEmpty());
}

void VolumeViewControls::updateQuality() {
    const int level = quality_->currentIndex();
    if (level == kManual || !view_->volume()) {
        if (chosenByQuality_) {
            drag_ = {};
            view_->setInteractiveQuality(drag_);
            view_->setSampling(manualSampling_);
            chosenByQuality_ = false;
        }
        setQualityStatus({});
        return;
    }
    if (view_->backend() == VolumeView::Backend::Remote) {
        setQualityStatus(tr("The render server chooses its own sampling."));
        return;
    }
    const std::string backend = view_->backend() == VolumeView::Backend::Gpu ? "gl" : "cpu";
    const RenderDescription d = view_->description();
    const std::string key = frontKey(d, backend);
    auto known = fronts_.find(key);
    if (known == fronts_.end() && !cacheDir_.isEmpty()) {
        if (std::optional<MeasuredFront> cached = loadFront(cacheDir_.toStdString(), key)) {
            known = fronts_.emplace(key, std::move(*cached)).first;
        }
    }
    if (known != fronts_.end()) {
        applyFront(known->second);
        return;
    }
    if (measuring_) {
        // Another volume, backend or mode than the one measured: that one is
        // cancelled, and measuringFinished() asks again.
        measuring_->cancel = measuring_->key != key;
        return;
    }
    startMeasuring(d, backend);
}

void VolumeViewControls::startMeasuring(const RenderDescription& description,
                                        const std::string& backend) {
    setQualityStatus(tr("Measuring the speed/accuracy front of this volume (once)..."));
    auto m = std::make_shared<Measurement>();
    m->key = frontKey(description, backend);
    measuring_ = m;
    // The thread keeps the volume alive: the view may load another meanwhile.
    const std::shared_ptr<const Volume> volume = view_->volume();
    thread_.reset(QThread::create([m, volume, description, backend] {
        const auto tick = [&](std::size_t, std::size_t) {
            if (m->cancel) {
                throw MeasuringCancelled{};
            }
        };
        try {
            const std::unique_ptr<Renderer> cpu =
                RenderDevice::open(RendererKind::Cpu)->openRenderer(*volume).renderer;
            const QualityRender reference = [&](const RenderDescription& d) {
                return cpu->render(d);
            };
            if (backend == "gl") {
                // A context of its own on this thread: the same GPU ray caster as the view's.
                try {
                    const std::unique_ptr<RenderDevice> device =
                        RenderDevice::open(RendererKind::Gl);
                    RenderDevice::Opened gl;
                    if (device->kind() == RendererKind::Gl) {
                        gl = device->openRenderer(*volume);
                    }
                    const std::string why = device->kind() == RendererKind::Gl
                                                ? gl.fallbackReason
                                                : device->fallbackReason();
                    if (why.empty()) {
                        m->front = measureQuickFront(
                            description, backend,
                            [&](const RenderDescription& d) { return gl.renderer->render(d); },
                            reference, tick);
                        return;
                    }
                    m->note = "measured on the CPU (" + why + ")";
                } catch (const MeasuringCancelled&) {
                    throw;
                } catch (const std::exception& e) {
                    m->note = std::string("measured on the CPU (GL failed: ") + e.what() + ")";
                }
            }
            m->front = measureQuickFront(description, backend, reference, reference, tick);
            // A GL key measured on the CPU: kept for this session only.
        } catch (const MeasuringCancelled&) {
        } catch (const std::exception& e) {
            m->note = e.what();
        }
    }));
    connect(thread_.get(), &QThread::finished, this, &VolumeViewControls::measuringFinished);
    thread_->start();
}

void VolumeViewControls::measuringFinished() {
    thread_->wait();
    thread_.reset();
    const std::shared_ptr<Measurement> m = std::move(measuring_);
    if (m->front) {
        if (m->note.empty() && !cacheDir_.isEmpty()) {
            try {
                saveFront(cacheDir_.toStdString(), *m->front);
            } catch (const std::exception& e) {
                m->note = e.what();
            }
        }
        fronts_.emplace(m->key, std::move(*m->front));
    } else if (!m->cancel) {
        setQualityStatus(
            tr("Could not measure the front: %1").arg(QString::fromStdString(m->note)));
        return;
    }
    updateQuality();
    if (!m->note.empty() && fronts_.count(m->key)) {
        setQualityStatus(qualityStatus_->text() + " (" + QString::fromStdString(m->note) + ")");
    }
}

void VolumeViewControls::applyFront(const MeasuredFront& front) {
    static constexpr double kBudgets[] = {0.0, kFastBudgetMs, kBalancedBudgetMs, kBestBudgetMs};
    const int level = quality_->currentIndex();
    const double budget = level == kTarget ? double(targetMs_->value()) : kBudgets[level];
    const RenderDescription d = view_->description();
    const TimeModel time = front.timeModel(d.width, d.height);
    const QualityChoice choice =
        chooseQuality(front.points, budget, d.transferFunction.shading.enabled, time);
    if (!chosenByQuality_) {
        manualSampling_ = view_->sampling();
        chosenByQuality_ = true;
    }
    const InteractiveQuality drag =
        chooseInteractive(front.points, choice.setting, std::min(kFastBudgetMs, budget), time, 2);
    drag_ = drag;
    view_->setInteractiveQuality(drag);
    SamplingSettings s = view_->sampling();
    const RenderDescription chosen = choice.setting.applyTo(d);
    s.step = chosen.sampling.step;
    s.interpolation = chosen.sampling.interpolation;
    s.classification = chosen.sampling.classification;
    s.preintegrate = chosen.sampling.preintegrate;
    s.brickSize = chosen.sampling.brickSize;
    const SamplingSettings& now = view_->sampling();
    if (s.step != now.step || s.interpolation != now.interpolation ||
        s.classification != now.classification || s.preintegrate != now.preintegrate ||
        s.brickSize != now.brickSize) {
        view_->setSampling(s);
    }
    QString status = QString::fromStdString(describeChoice(choice)) +
                     tr("; dragging: step x%1 at half size").arg(drag.stepFactor);
    if (!choice.message.empty()) {
        status += " (" + QString::fromStdString(choice.message) + ")";
    }
    setQualityStatus(status);
    Q_EMIT qualityChosen(status);
}

} // namespace lucent
