#include "core/segmentation/ScissorsCut.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace lucent {
namespace {

enum Cell : std::uint8_t { kOut = 0, kIn = 1, kNearEdge = 2 };

// A polygon sorted into square cells over its bounding box (one cell of margin round it):
// cells an edge passes through, or lies next to, are kNearEdge; every other cell lies
// wholly inside or wholly outside, as its centre does.
class PolygonCells {
public:
    explicit PolygonCells(const ScreenShape& shape) : shape_(shape) {
        const auto& pts = shape.points();
        glm::dvec2 lo = pts.front(), hi = pts.front();
        for (const glm::dvec2& p : pts) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        cell_ = std::max(1.0, std::max(hi.x - lo.x, hi.y - lo.y) / 2048.0);
        perCell_ = 1.0 / cell_;
        lo_ = lo - cell_;
        nx_ = int(std::floor((hi.x + cell_ - lo_.x) / cell_)) + 1;
        ny_ = int(std::floor((hi.y + cell_ - lo_.y) / cell_)) + 1;
        cells_.assign(std::size_t(nx_) * std::size_t(ny_), kOut);
        for (std::size_t e = 0; e < pts.size(); ++e) {
            markEdge(pts[e], pts[(e + 1) % pts.size()]);
        }
        classifyRuns();
    }

    bool contains(const glm::dvec2& p) const {
        // A point on a cell's side may be looked up in either cell: both are near-edge
        // cells, or lie on the same side, as edges mark the cells round theirs too.
        const double fx = std::floor((p.x - lo_.x) * perCell_);
        const double fy = std::floor((p.y - lo_.y) * perCell_);
        if (!(fx >= 0.0 && fy >= 0.0 && fx < nx_ && fy < ny_)) {
            return false; // more than a cell away from the bounding box
        }
        const std::uint8_t c = cells_[std::size_t(fx) + std::size_t(nx_) * std::size_t(fy)];
        return c == kNearEdge ? shape_.contains(p) : c == kIn;
    }

private:
    void mark(int cx0, int cx1, int cy) {
        if (cy < 0 || cy >= ny_) {
            return;
        }
        for (int cx = std::max(cx0, 0); cx <= std::min(cx1, nx_ - 1); ++cx) {
            cells_[std::size_t(cx) + std::size_t(nx_) * std::size_t(cy)] = kNearEdge;
        }
    }

    // Marks, row by row, the cells the edge passes through and one cell round them.
    void markEdge(const glm::dvec2& a, const glm::dvec2& b) {
        const int r0 = int(std::floor((std::min(a.y, b.y) - lo_.y) / cell_));
        const int r1 = int(std::floor((std::max(a.y, b.y) - lo_.y) / cell_));
        for (int r = r0; r <= r1; ++r) {
            double x0 = std::min(a.x, b.x), x1 = std::max(a.x, b.x);
            if (a.y != b.y) {
                const double y0 = lo_.y + r * cell_, y1 = y0 + cell_;
                const double t0 = std::clamp((y0 - a.y) / (b.y - a.y), 0.0, 1.0);
                const double t1 = std::clamp((y1 - a.y) / (b.y - a.y), 0.0, 1.0);
                const double xa = a.x + (b.x - a.x) * t0, xb = a.x + (b.x - a.x) * t1;
                x0 = std::min(xa, xb);
                x1 = std::max(xa, xb);
            }
            const int c0 = int(std::floor((x0 - lo_.x) / cell_)) - 1;
            const int c1 = int(std::floor((x1 - lo_.x) / cell_)) + 1;
            for (int dr = -1; dr <= 1; ++dr) {
                mark(c0, c1, r + dr);
            }
        }
    }

    // A run of cells with no edge near them lies all on one side: its first centre says.
    void classifyRuns() {
        for (int cy = 0; cy < ny_; ++cy) {
            std::uint8_t* row = cells_.data() + std::size_t(nx_) * std::size_t(cy);
            for (int cx = 0; cx < nx_;) {
                if (row[cx] == kNearEdge) {
                    ++cx;
                    continue;
                }
                const glm::dvec2 centre = lo_ + (glm::dvec2(cx, cy) + 0.5) * cell_;
                const std::uint8_t side = shape_.contains(centre) ? kIn : kOut;
                for (; cx < nx_ && row[cx] != kNearEdge; ++cx) {
                    row[cx] = side;
                }
            }
        }
    }

    const ScreenShape& shape_;
    glm::dvec2 lo_{0.0};
    double cell_ = 1.0, perCell_ = 1.0;
    int nx_ = 0, ny_ = 0;
    std::vector<std::uint8_t> cells_;
};

} // namespace

ScreenShape ScreenShape::polygon(std::vector<glm::dvec2> points) {
    ScreenShape s;
    s.kind_ = Kind::Polygon;
    s.points_ = std::move(points);
    return s;
}

ScreenShape ScreenShape::circle(const glm::dvec2& centre, double radius) {
    ScreenShape s;
    s.kind_ = Kind::Circle;
    s.centre_ = centre;
    s.radius_ = std::abs(radius);
    return s;
}

ScreenShape ScreenShape::rectangle(const glm::dvec2& corner, const glm::dvec2& opposite) {
    ScreenShape s;
    s.kind_ = Kind::Rectangle;
    s.points_ = {glm::min(corner, opposite), glm::max(corner, opposite)};
    return s;
}

bool ScreenShape::enclosesArea() const {
    switch (kind_) {
    case Kind::Circle:
        return radius_ > 0.0;
    case Kind::Rectangle:
        return points_[1].x > points_[0].x && points_[1].y > points_[0].y;
    case Kind::Polygon:
        break;
    }
    return points_.size() >= 3;
}

bool ScreenShape::contains(const glm::dvec2& p) const {
    switch (kind_) {
    case Kind::Circle: {
        const glm::dvec2 d = p - centre_;
        return glm::dot(d, d) <= radius_ * radius_;
    }
    case Kind::Rectangle:
        return p.x >= points_[0].x && p.x <= points_[1].x && p.y >= points_[0].y &&
               p.y <= points_[1].y;
    case Kind::Polygon:
        break;
    }
    // Even-odd: crossings of the ray from p towards +x.
    bool inside = false;
    for (std::size_t i = 0, j = points_.size() - 1; i < points_.size(); j = i++) {
        const glm::dvec2 &a = points_[i], &b = points_[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) {
            inside = !inside;
        }
    }
    return inside;
}

std::optional<glm::dvec2> projectToView(const ImageProjection& projection,
                                        const glm::dvec2& viewSize, const glm::dvec3& lps) {
    const std::optional<glm::dvec2> f = projectToImage(projection, lps);
    return f ? std::optional<glm::dvec2>(*f * viewSize) : std::nullopt;
}

SegmentMask scissorsMask(const VolumeGeometry& grid, const ImageProjection& projection,
                         const glm::dvec2& viewSize, const ScreenShape& shape, ScissorsSide side) {
    const glm::ivec3 d = grid.dims;
    SegmentMask out(d);
    if (!shape.enclosesArea()) {
        if (side == ScissorsSide::Outside) {
            out.invert();
        }
        return out;
    }
    std::optional<PolygonCells> cells;
    if (shape.kind() == ScreenShape::Kind::Polygon) {
        cells.emplace(shape);
    }
    const bool wantInside = side == ScissorsSide::Inside;
    // The projection composed with the grid's index-to-patient matrix: rows of (x w, y w, w)
    // in view pixels as linear functions of (i, j, k), each row's j and k terms summed once.
    const glm::dmat4 toPatient = grid.indexToPatient();
    double rows[3][4];
    for (int r = 0; r < 3; ++r) {
        const double scale = r == 0 ? viewSize.x : r == 1 ? viewSize.y : 1.0;
        const std::size_t at = std::size_t(4 * r);
        const glm::dvec4 row(projection[at], projection[at + 1], projection[at + 2],
                             projection[at + 3]);
        for (int c = 0; c < 4; ++c) {
            rows[r][c] = scale * glm::dot(row, toPatient[c]);
        }
    }
    std::vector<std::uint8_t> cut(out.size(), 0);
    const std::size_t slice = std::size_t(d.x) * std::size_t(d.y);
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = 0; k < d.z; ++k) {
        std::uint8_t* voxel = cut.data() + slice * std::size_t(k);
        for (int j = 0; j < d.y; ++j) {
            double base[3];
            for (int r = 0; r < 3; ++r) {
                base[r] = rows[r][1] * j + rows[r][2] * k + rows[r][3];
            }
            for (int i = 0; i < d.x; ++i, ++voxel) {
                const double w = base[2] + rows[2][0] * i;
                bool in = false;
                if (w > 1e-9) { // in front of the eye, as projectToImage
                    const glm::dvec2 p((base[0] + rows[0][0] * i) / w,
                                       (base[1] + rows[1][0] * i) / w);
                    in = cells ? cells->contains(p) : shape.contains(p);
                }
                *voxel = in == wantInside ? 1 : 0;
            }
        }
    }
    for (std::size_t n = 0; n < cut.size(); ++n) {
        if (cut[n] != 0) {
            out.set(n);
        }
    }
    return out;
}

SegmentMask applyScissors(const SegmentMask& segment, const VolumeGeometry& grid,
                          const ImageProjection& projection, const glm::dvec2& viewSize,
                          const ScreenShape& shape, ScissorsOperation operation) {
    const bool inside =
        operation == ScissorsOperation::EraseInside || operation == ScissorsOperation::FillInside;
    const SegmentMask cut = scissorsMask(grid, projection, viewSize, shape,
                                         inside ? ScissorsSide::Inside : ScissorsSide::Outside);
    SegmentMask out = segment;
    if (operation == ScissorsOperation::EraseInside ||
        operation == ScissorsOperation::EraseOutside) {
        out.subtract(cut);
    } else {
        out |= cut;
    }
    return out;
}

} // namespace lucent
