#pragma once
// The Surface panel of the 3D dock: the isosurface of the volume shown in the
// 3D view (iso value over the volume's histogram), its clean-up, the method
// of spheres' surface-to-volume field for a radius (computed on a thread of
// its own, with progress and cancel), how it is shown (coloured by the field
// or plain; with the volume or alone) and its export (STL, PLY, VTK, OBJ).

#include <QWidget>

#include <memory>

#include "core/surface/SurfacePipeline.h"

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSpinBox;

namespace lucent {

class IsoHistogram;
class SurfaceJob;
class VolumeView;

class SurfacePanel : public QWidget {
    Q_OBJECT

public:
    explicit SurfacePanel(VolumeView* view, QWidget* parent = nullptr);
    ~SurfacePanel() override;

    QDoubleSpinBox* isoValue() const { return iso_; }
    QDoubleSpinBox* radius() const { return radius_; }
    QSpinBox* smoothing() const { return smooth_; }
    QSpinBox* keepLargest() const { return largest_; }
    QPushButton* computeButton() const { return compute_; }
    QCheckBox* colourByField() const { return colourByField_; }
    QCheckBox* showVolume() const { return showVolume_; }
    QProgressBar* progressBar() const { return progress_; }
    // What the last computation gave (triangles, area, volume, closed, SVR), or why none.
    QString status() const;
    bool computing() const;
    // The surface shown, or null.
    const std::shared_ptr<const SurfaceResult>& result() const { return result_; }

    // Writes the surface (with its field) to `file`; false with status() saying why.
    bool exportTo(const QString& file);

public slots:
    // Starts a computation, or cancels the one running.
    void computeOrCancel();
    void clear();

signals:
    void computed(bool ok);

private:
    void volumeChanged();
    void finished(std::shared_ptr<const SurfaceResult> result, const QString& error,
                  bool cancelled);
    void showResult();
    void exportDialog();
    void setStatus(const QString& text);

    VolumeView* view_;
    IsoHistogram* histogram_ = nullptr;
    QDoubleSpinBox* iso_ = nullptr;
    QDoubleSpinBox* radius_ = nullptr;
    QSpinBox* smooth_ = nullptr;
    QSpinBox* largest_ = nullptr;
    QPushButton* compute_ = nullptr;
    QPushButton* export_ = nullptr;
    QPushButton* clear_ = nullptr;
    QCheckBox* colourByField_ = nullptr;
    QCheckBox* showVolume_ = nullptr;
    QProgressBar* progress_ = nullptr;
    QLabel* status_ = nullptr;
    std::unique_ptr<SurfaceJob> job_;
    std::shared_ptr<const SurfaceResult> result_;
    double resultRadius_ = 0.0;
};

} // namespace lucent
