#include "app/bench/VolPackAnchor.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "core/scene/ViewFrame.h"

#ifdef LUCENT_HAVE_VOLPACK
#include <volpack.h>

namespace lucent::bench {

namespace {

constexpr int kNormalField = 0; // shading: the colour table's row
constexpr int kColourField = 1; // shading: the weight table's row (VolPack: one byte)
constexpr int kScalarField = 2; // classification
constexpr int kColourBins = 256;
constexpr int kMaterials = 4; // red, green and blue scaled by the diffuse term; white specular
constexpr int kNormalCodes = VP_NORM_MAX + 1;

void check(vpContext* c, vpResult r, const char* call) {
    if (r != VP_OK) {
        throw std::runtime_error(std::string("VolPack: ") + call +
                                 " failed: " + vpGetErrorString(vpGetError(c)));
    }
}

// The volume axis most parallel to the view (VolPack's choice of principal axis).
int principalAxis(const VolumeGeometry& g, const glm::dvec3& forward) {
    int best = 0;
    for (int a = 1; a < 3; ++a) {
        if (std::abs(glm::dot(forward, g.direction[a])) >
            std::abs(glm::dot(forward, g.direction[best]))) {
            best = a;
        }
    }
    return best;
}

} // namespace

void VolPackAnchor::ContextDeleter::operator()(vpContext* c) const {
    vpDestroyContext(c);
}

VolPackAnchor::VolPackAnchor(const Volume& volume, const TransferFunction& tf,
                             const Camera& firstView, int width, int height)
    : volume_(volume), shading_(tf.shading), width_(width), height_(height),
      context_(vpCreateContext()) {
    if (!context_) {
        throw std::runtime_error("VolPack: vpCreateContext failed");
    }
    const glm::ivec3 n = volume.dims();
    if (std::max({n.x, n.y, n.z}) > VP_MAX_VOLUME_DIM) {
        throw std::runtime_error("VolPack: a volume side over " +
                                 std::to_string(VP_MAX_VOLUME_DIM) + " voxels");
    }
    axis_ = principalAxis(volume.geometry(),
                          makeViewFrame(volume.geometry(), firstView, width, height).forward);
    const auto [lo, hi] = volume.valueRange();
    scalarOffset_ = -std::floor(lo);
    tableSize_ = int(std::min(65536.0, std::floor(hi) + scalarOffset_ + 1.0));
    // The colour bins span the values that can be seen, up to the ramp's last point.
    double seen = hi;
    for (int s = tableSize_ - 1; s >= 0; --s) {
        if (tf.opacityAt(s - scalarOffset_) > 0.0) {
            seen = s - scalarOffset_;
        }
    }
    colourLo_ = std::max(lo, seen - 1.0);
    const double colourHi = tf.colour.empty() ? hi : std::min(hi, tf.colour.back().value);
    colourStep_ = std::max(colourHi - colourLo_, 1.0) / kColourBins;
    vpContext* c = context_.get();
    static_assert(sizeof(Voxel) == 6);
    check(c, vpSetVolumeSize(c, n.x, n.y, n.z), "vpSetVolumeSize");
    check(c, vpSetVoxelSize(c, sizeof(Voxel), 3, 2, 1), "vpSetVoxelSize");
    check(c, vpSetVoxelField(c, kNormalField, 2, offsetof(Voxel, normal), VP_NORM_MAX),
          "vpSetVoxelField(normal)");
    check(c, vpSetVoxelField(c, kColourField, 1, offsetof(Voxel, colour), kColourBins - 1),
          "vpSetVoxelField(colour)");
    check(c, vpSetVoxelField(c, kScalarField, 2, offsetof(Voxel, scalar), tableSize_ - 1),
          "vpSetVoxelField(scalar)");
    classify(tf);
    colourTable_.assign(std::size_t(kNormalCodes) * kMaterials * 3, 0.0f);
    check(c,
          vpSetLookupShader(c, 3, kMaterials, kNormalField, colourTable_.data(),
                            int(colourTable_.size() * sizeof(float)), kColourField,
                            weightTable_.data(), int(weightTable_.size() * sizeof(float))),
          "vpSetLookupShader");
    normals_.resize(kNormalCodes, glm::dvec3(0.0));
    for (int code = 2; code < kNormalCodes; ++code) { // 0 and 1: the zero vector
        check(c, vpNormal(code, &normals_[code].x, &normals_[code].y, &normals_[code].z),
              "vpNormal");
    }
    rgb_.assign(std::size_t(width) * std::size_t(height) * 3, 0);
    check(c, vpSetImage(c, rgb_.data(), width, height, width * 3, VP_RGB), "vpSetImage");
    check(c, vpSetd(c, VP_MAX_RAY_OPACITY, 0.99), "vpSetd(VP_MAX_RAY_OPACITY)"); // Lucent's
}

VolPackAnchor::~VolPackAnchor() = default;

// Voxels (normal code, colour bin, scalar), the opacity and weight tables, vpClassifyVolume.
void VolPackAnchor::classify(const TransferFunction& tf) {
    const VolumeGeometry& g = volume_.geometry();
    const glm::ivec3 n = g.dims;
    voxels_.assign(g.voxelCount(), Voxel{});
    visitVoxels(volume_, [&](auto v) {
        const auto at = [&](int i, int j, int k) {
            return double(v[volume_.linearIndex(
                std::clamp(i, 0, n.x - 1), std::clamp(j, 0, n.y - 1), std::clamp(k, 0, n.z - 1))]);
        };
        for (int k = 0; k < n.z; ++k) {
            for (int j = 0; j < n.y; ++j) {
                for (int i = 0; i < n.x; ++i) {
                    const std::size_t index = volume_.linearIndex(i, j, k);
                    // Central differences in mm, turned into LPS.
                    const glm::dvec3 d((at(i + 1, j, k) - at(i - 1, j, k)) / (2.0 * g.spacing.x),
                                       (at(i, j + 1, k) - at(i, j - 1, k)) / (2.0 * g.spacing.y),
                                       (at(i, j, k + 1) - at(i, j, k - 1)) / (2.0 * g.spacing.z));
                    const glm::dvec3 lps = g.direction * d;
                    const double len = glm::length(lps);
                    const int code =
                        len > 1e-6 ? vpNormalIndex(lps.x / len, lps.y / len, lps.z / len) : 0;
                    const double value = double(v[index]);
                    const double s =
                        std::clamp(std::round(value + scalarOffset_), 0.0, double(tableSize_ - 1));
                    const double bin = std::clamp(std::floor((value - colourLo_) / colourStep_),
                                                  0.0, double(kColourBins - 1));
                    voxels_[index] = {std::uint16_t(code), std::uint8_t(bin), 0, std::uint16_t(s)};
                }
            }
        }
    });
    const double minSpacing = std::min({g.spacing.x, g.spacing.y, g.spacing.z});
    const double unitRatio = g.spacing[axis_] / minSpacing; // VolPack's unit / Lucent's
    opacityTable_.resize(std::size_t(tableSize_));
    for (int s = 0; s < tableSize_; ++s) {
        opacityTable_[std::size_t(s)] =
            float(1.0 - std::pow(1.0 - tf.opacityAt(double(s) - scalarOffset_), unitRatio));
    }
    weightTable_.resize(std::size_t(kColourBins) * kMaterials);
    for (int bin = 0; bin < kColourBins; ++bin) {
        const glm::dvec3 rgb = tf.colourAt(binValue(bin));
        float* w = &weightTable_[std::size_t(bin) * kMaterials];
        w[0] = float(rgb.r);
        w[1] = float(rgb.g);
        w[2] = float(rgb.b);
        w[3] = 1.0f;
    }
    vpContext* c = context_.get();
    const int voxelBytes = int(sizeof(Voxel));
    check(c,
          vpSetRawVoxels(c, voxels_.data(), int(voxels_.size() * sizeof(Voxel)), voxelBytes,
                         voxelBytes * n.x, voxelBytes * n.x * n.y),
          "vpSetRawVoxels");
    check(c,
          vpSetClassifierTable(c, 0, kScalarField, opacityTable_.data(),
                               int(opacityTable_.size() * sizeof(float))),
          "vpSetClassifierTable");
    check(c, vpSetd(c, VP_MIN_VOXEL_OPACITY, 0.0), "vpSetd(VP_MIN_VOXEL_OPACITY)");
    check(c, vpClassifyVolume(c), "vpClassifyVolume");
}

// Lucent's headlight (RayKernel::shade): colour * (ambient + diffuse |n.v|) + specular
// |n.v|^p, as VolPack's lookup shader sums it: material m's colour for this normal times
// the scalar's weight for m (red, green, blue, 1). Table entries are 0..255.
void VolPackAnchor::fillShadeTable(const glm::dvec3& forward) {
    for (int code = 0; code < kNormalCodes; ++code) {
        double diffuse = 1.0, specular = 0.0; // the zero normal: the colour unshaded
        if (shading_.enabled && code >= 2) {
            const double ndotl = std::min(1.0, std::abs(glm::dot(normals_[code], forward)));
            diffuse = shading_.ambient + shading_.diffuse * ndotl;
            specular = shading_.specular * std::pow(ndotl, shading_.specularPower);
        }
        float* row = &colourTable_[std::size_t(code) * kMaterials * 3];
        std::fill(row, row + kMaterials * 3, 0.0f);
        for (int m = 0; m < 3; ++m) {
            row[3 * m + m] = float(255.0 * diffuse);
        }
        std::fill(row + 9, row + 12, float(255.0 * specular));
    }
}

ImageRGBA8 VolPackAnchor::render(const Camera& camera) {
    const VolumeGeometry& g = volume_.geometry();
    const ViewFrame f = makeViewFrame(g, camera, width_, height_);
    const glm::dvec3 target =
        volumeCentre(g) + f.right * camera.panRight + f.up * camera.panUp; // as makeViewFrame
    // Eye coordinates: x right, y up, z away from the viewer (VolPack composites
    // from the near plane, z = -depth, on). Object coordinates: voxel index minus
    // half the side, over the longest side.
    const glm::dmat3 view = glm::transpose(glm::dmat3(f.right, f.up, f.forward));
    const glm::dvec3 side(g.dims);
    const double longest = std::max({side.x, side.y, side.z});
    const glm::dmat3 linear =
        view * g.direction *
        glm::dmat3(glm::dvec3(g.spacing.x, 0, 0), glm::dvec3(0, g.spacing.y, 0),
                   glm::dvec3(0, 0, g.spacing.z)) *
        longest;
    const glm::dvec3 shift = view * (g.toPatient(side * 0.5) - target);
    vpMatrix4 model;
    for (int r = 0; r < 3; ++r) {
        for (int col = 0; col < 3; ++col) {
            model[r][col] = linear[col][r];
        }
        model[r][3] = shift[r];
        model[3][r] = 0.0;
    }
    model[3][3] = 1.0;
    const double halfHeight = f.tanHalfFov * glm::length(target - f.eye);
    const double halfWidth = halfHeight * f.aspect;
    const double depth = 2.0 * volumeRadius(g); // the volume lies within +-radius
    vpContext* c = context_.get();
    check(c, vpCurrentMatrix(c, VP_PROJECT), "vpCurrentMatrix(VP_PROJECT)");
    check(c, vpIdentityMatrix(c), "vpIdentityMatrix");
    check(c,
          vpWindow(c, VP_PARALLEL, -halfWidth, halfWidth, -halfHeight, halfHeight, -depth, depth),
          "vpWindow");
    check(c, vpCurrentMatrix(c, VP_MODEL), "vpCurrentMatrix(VP_MODEL)");
    check(c, vpSetMatrix(c, model), "vpSetMatrix");
    fillShadeTable(f.forward);
    check(c, vpRenderClassifiedVolume(c), "vpRenderClassifiedVolume");
    // VolPack's rows run from the bottom of the window (y = -1) up.
    ImageRGBA8 out = ImageRGBA8::filled(width_, height_, 255);
    for (int y = 0; y < height_; ++y) {
        const std::uint8_t* src = &rgb_[std::size_t(height_ - 1 - y) * std::size_t(width_) * 3];
        for (int x = 0; x < width_; ++x) {
            std::copy(src + 3 * x, src + 3 * x + 3, out.at(x, y));
        }
    }
    return out;
}

int VolPackAnchor::lastAxis() const {
    int axis = -1;
    vpGeti(context_.get(), VP_VIEW_AXIS, &axis);
    return axis;
}

} // namespace lucent::bench

#else // built without libvolpack1-dev: the anchor fails, saying so

namespace lucent::bench {

void VolPackAnchor::ContextDeleter::operator()(vpContext*) const {}

VolPackAnchor::VolPackAnchor(const Volume& volume, const TransferFunction&, const Camera&,
                             int width, int height)
    : volume_(volume), width_(width), height_(height) {
    throw std::runtime_error("not built: libvolpack1-dev missing (the VolPack anchor: "
                             "packaging/install-deps.sh installs it; then run cmake again)");
}

VolPackAnchor::~VolPackAnchor() = default;

ImageRGBA8 VolPackAnchor::render(const Camera&) {
    return {};
}

int VolPackAnchor::lastAxis() const {
    return -1;
}

} // namespace lucent::bench

#endif
