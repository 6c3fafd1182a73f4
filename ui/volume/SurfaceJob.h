#pragma once
// One surface computation (core/surface/SurfacePipeline.h) on a thread of its
// own, so that the Surface panel stays responsive: progress comes back as a
// signal, cancel() stops it at the next check, and finished() hands over the
// result or the reason there is none. Deleting the job cancels and waits.

#include <QObject>
#include <QString>

#include <atomic>
#include <memory>

#include "core/surface/SurfacePipeline.h"

class QThread;

namespace lucent {

class SurfaceJob : public QObject {
    Q_OBJECT

public:
    SurfaceJob(std::shared_ptr<const Volume> volume, SurfaceRequest request,
               QObject* parent = nullptr);
    ~SurfaceJob() override;

    void start();
    void cancel() { cancelled_ = true; }
    bool running() const;

signals:
    void progress(double fraction, const QString& step);
    // result is null when it failed or was cancelled; `error` says why (empty
    // when cancelled).
    void finished(std::shared_ptr<const lucent::SurfaceResult> result, const QString& error,
                  bool cancelled);

private:
    std::shared_ptr<const Volume> volume_;
    SurfaceRequest request_;
    std::atomic<bool> cancelled_{false};
    std::unique_ptr<QThread> thread_;
};

} // namespace lucent
