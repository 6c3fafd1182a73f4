#pragma once
// The curved MPR window: the straightened or stretched reformation along a
// path clicked on an MPR view (true millimetres both ways, with a scale
// bar), the cross-section at the cursor's place along the path, a slab
// across the cut and, when straightened, the cut's turn around the path.
// Grey levels follow the MPR views' window; moving along the path moves
// their crosshair to the same point.

#include <QImage>
#include <QWidget>

#include <memory>
#include <vector>

#include "core/mpr/CurvedReformat.h"

class QComboBox;
class QDoubleSpinBox;
class QSpinBox;

namespace lucent {

class MprCursor;
class CurvedImagePane;

class CurvedMprView : public QWidget {
    Q_OBJECT

public:
    enum class Kind { Straightened, Stretched };

    explicit CurvedMprView(MprCursor* cursor, QWidget* parent = nullptr);
    ~CurvedMprView() override;

    // Throws std::invalid_argument naming what is wrong with the path.
    void setPath(std::shared_ptr<const Volume> volume, const std::vector<glm::dvec3>& points,
                 const glm::dvec3& up);
    void setKind(Kind kind);
    void setRotation(double degrees);
    void setSlab(double thicknessMm, SlabMode mode);
    // Where the cross-section is: arc length along the path, mm.
    void setArc(double s);
    double arc() const { return arc_; }

    const Centerline& centerline() const { return centerline_; }
    const CurvedImage& reformation() const { return reformation_; }
    QImage reformationImage() const; // windowed grey, one pixel a reformation pixel
    QImage crossSectionImage() const;
    QComboBox* kindBox() const { return kind_; }

private:
    void rebuild();
    void updateCrossSection();
    QImage toGrey(const std::vector<float>& values, int width, int height) const;
    void setArcFromRow(int row);

    MprCursor* cursor_;
    std::shared_ptr<const Volume> volume_;
    Centerline centerline_;
    glm::dvec3 up_{0.0, 0.0, 1.0};
    CurvedImage reformation_;
    QImage grey_; // reformation_ in the window
    std::vector<float> crossSection_;
    int crossSize_ = 160;
    double arc_ = 0.0;
    double pixelSize_ = 0.5;

    QComboBox* kind_;
    QSpinBox* rotation_;
    QDoubleSpinBox* slab_;
    QComboBox* slabMode_;
    CurvedImagePane* curved_;
    CurvedImagePane* across_;
};

} // namespace lucent
