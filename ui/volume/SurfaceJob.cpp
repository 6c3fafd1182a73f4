#include "ui/volume/SurfaceJob.h"

#include <QMetaObject>
#include <QPointer>
#include <QThread>

namespace lucent {

SurfaceJob::SurfaceJob(std::shared_ptr<const Volume> volume, SurfaceRequest request,
                       QObject* parent)
    : QObject(parent), volume_(std::move(volume)), request_(std::move(request)) {}

SurfaceJob::~SurfaceJob() {
    cancelled_ = true;
    if (thread_) {
        thread_->wait();
    }
}

bool SurfaceJob::running() const {
    return thread_ && thread_->isRunning();
}

void SurfaceJob::start() {
    thread_.reset(QThread::create([this] {
        std::shared_ptr<const SurfaceResult> result;
        QString error;
        bool cancelled = false;
        try {
            result = std::make_shared<const SurfaceResult>(
                makeSurface(*volume_, request_, [this](double fraction, const char* step) {
                    emit progress(fraction, QString::fromUtf8(step)); // queued to the panel
                    return !cancelled_.load();
                }));
        } catch (const SurfaceCancelled&) {
            cancelled = true;
        } catch (const std::exception& e) {
            error = QString::fromUtf8(e.what());
        }
        // Delivered on this object's thread (the panel's) once the work is done.
        QMetaObject::invokeMethod(
            this, [this, result, error, cancelled] { emit finished(result, error, cancelled); },
            Qt::QueuedConnection);
    }));
    thread_->start();
}

} // namespace lucent
