#pragma once
// The series' histogram (log counts) with the threshold's range shaded over it: a press
// moves the nearer end of the range, a drag carries it along. For the Segments panel.

#include <QWidget>

#include "core/tf/VolumeHistogram.h"

namespace lucent {

class ThresholdHistogram : public QWidget {
    Q_OBJECT

public:
    explicit ThresholdHistogram(QWidget* parent = nullptr);
    void setHistogram(VolumeHistogram histogram);
    const VolumeHistogram& histogram() const { return histogram_; }
    double lower() const { return lo_; }
    double upper() const { return hi_; }
    QSize sizeHint() const override { return {220, 56}; }

public slots:
    void setRange(double lo, double hi);

signals:
    void rangeChosen(double lo, double hi);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;

private:
    double valueAt(double x) const;
    double xOf(double value) const;

    VolumeHistogram histogram_;
    double lo_ = 0.0;
    double hi_ = 0.0;
    bool draggingUpper_ = false;
};

} // namespace lucent
