#pragma once
// The volume's histogram (log counts) as a strip with the iso value marked: a
// click or drag sets the iso value. For the Surface panel.

#include <QWidget>

#include "core/tf/VolumeHistogram.h"

namespace lucent {

class IsoHistogram : public QWidget {
    Q_OBJECT

public:
    explicit IsoHistogram(QWidget* parent = nullptr);
    void setHistogram(VolumeHistogram histogram);
    double isoValue() const { return iso_; }
    QSize sizeHint() const override { return {200, 48}; }

public slots:
    void setIsoValue(double value);

signals:
    void isoValueChosen(double value);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;

private:
    double valueAt(double x) const;

    VolumeHistogram histogram_;
    double iso_ = 0.0;
};

} // namespace lucent
