#pragma once
// Scissors through the 3D view: a polygon, circle or rectangle drawn on the rendering cuts a
// segment along the view's rays, as the Segment Editor's Scissors effect in the 3D view. A
// voxel is cut when its centre projects inside the shape (or outside it, for "outside"), with
// the view's own projection (core/scene/ImageProjection.h): perspective as VolumeView draws,
// or any other 3 x 4 projection (orthographic: a last row of 0, 0, 0, 1). Voxels at or
// behind the eye project nowhere: they are outside every shape.

#include <vector>

#include <glm/glm.hpp>

#include "core/scene/ImageProjection.h"
#include "core/segmentation/SegmentMask.h"
#include "core/volume/Volume.h"

namespace lucent {

// A shape in view pixels: x to the right, y down, pixel (x, y) spanning [x, x + 1] x
// [y, y + 1], as widget coordinates are.
class ScreenShape {
public:
    enum class Kind { Polygon, Circle, Rectangle };
    // Closed by the last point back to the first; inside by the even-odd rule (a freehand
    // outline that crosses itself keeps the parts drawn an odd number of times round).
    static ScreenShape polygon(std::vector<glm::dvec2> points);
    static ScreenShape circle(const glm::dvec2& centre, double radius);
    static ScreenShape rectangle(const glm::dvec2& corner, const glm::dvec2& opposite);

    Kind kind() const { return kind_; }
    const std::vector<glm::dvec2>& points() const { return points_; } // polygon; 2 corners
    glm::dvec2 centre() const { return centre_; }
    double radius() const { return radius_; }
    // Whether p lies inside: the one test every voxel's projection goes through.
    bool contains(const glm::dvec2& p) const;
    // Whether the shape encloses anything (three points or more, a radius, an area).
    bool enclosesArea() const;

private:
    Kind kind_ = Kind::Polygon;
    std::vector<glm::dvec2> points_;
    glm::dvec2 centre_{0.0};
    double radius_ = 0.0;
};

// Where a view of `viewSize` pixels with `projection` shows LPS point p (ImageProjection's
// fractions times the size); nothing at or behind the eye.
std::optional<glm::dvec2> projectToView(const ImageProjection& projection,
                                        const glm::dvec2& viewSize, const glm::dvec3& lps);

enum class ScissorsSide { Inside, Outside };

// The voxels of `grid` whose centre (grid.toPatient(i, j, k)) projects inside the shape
// (Inside) or not inside it (Outside), as projectToView and ScreenShape::contains say for each
// (the projection is composed with the grid's matrix once; the tests check the mask against
// every voxel centre of the real CT projected on its own). A polygon is first sorted into
// view cells so that only voxels projecting near its outline run the full test.
SegmentMask scissorsMask(const VolumeGeometry& grid, const ImageProjection& projection,
                         const glm::dvec2& viewSize, const ScreenShape& shape, ScissorsSide side);

// The Scissors effect's operations on a segment: erase or fill the voxels inside or outside.
enum class ScissorsOperation { EraseInside, EraseOutside, FillInside, FillOutside };
SegmentMask applyScissors(const SegmentMask& segment, const VolumeGeometry& grid,
                          const ImageProjection& projection, const glm::dvec2& viewSize,
                          const ScreenShape& shape, ScissorsOperation operation);

} // namespace lucent
