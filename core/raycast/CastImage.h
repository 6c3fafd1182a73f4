#pragma once
// The CPU ray caster's image loop: tiles over threads, packets of neighbouring
// rays within a tile, and no rays at all for pixels whose rays cannot meet the
// volume. Private to core/raycast.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/image/Image.h"
#include "core/raycast/RaySetup.h"
#include "core/scene/ViewFrame.h"

namespace lucent {

constexpr int kTile = 16;
// Rays go in packets of 2 x 4 pixels: neighbours along both image axes read
// the same cache lines (measured on the Philips CT, AMD Zen 3: 4 x 2 was 12%
// faster than 8 x 1; 2 x 4 is 4-5% faster than 4 x 2 and than 1 x 8).
constexpr int kPacket = 8;
constexpr int kPacketColumns = 2, kPacketRows = kPacket / kPacketColumns;

// kernel: anything with RayOutput cast(origin, direction, unit direction), or
// with castPacket over up to kPacket neighbouring rays. Pixels outside
// pixelsOfBox(clip box) get the background without a ray (and premultiplied
// 0): every pixel of `image` and `premultiplied` is written. `projection`, when
// given (sized like the image), receives each ray's RayOutput::projection.
template <class Kernel>
void castImage(const Kernel& kernel, const VolumeGeometry& g, const ViewFrame& frame,
               const RenderDescription& desc, ImageRGBA8& image,
               std::vector<glm::vec4>& premultiplied, std::size_t& samples,
               std::vector<glm::vec2>* projection = nullptr) {
    const glm::dmat3 toIndexLinear = glm::inverse(glm::dmat3(
        g.direction[0] * g.spacing.x, g.direction[1] * g.spacing.y, g.direction[2] * g.spacing.z));
    const glm::dvec3 origin = g.toIndex(frame.eye);
    const int tilesX = (desc.width + kTile - 1) / kTile;
    const int tilesY = (desc.height + kTile - 1) / kTile;
    const PixelRect covered =
        pixelsOfBox(g, frame, glm::max(desc.clip.lo, glm::dvec3(0.0)),
                    glm::min(desc.clip.hi, glm::dvec3(g.dims - 1)), desc.width, desc.height);
    std::uint8_t background[3];
    for (int ch = 0; ch < 3; ++ch) {
        background[ch] =
            static_cast<std::uint8_t>(std::clamp(desc.background[ch], 0.0, 1.0) * 255.0 + 0.5);
    }
    std::size_t total = 0;
#pragma omp parallel for schedule(dynamic) reduction(+ : total)
    for (int tile = 0; tile < tilesX * tilesY; ++tile) {
        const int x0 = (tile % tilesX) * kTile, y0 = (tile / tilesX) * kTile;
        const int xEnd = std::min(x0 + kTile, desc.width);
        const int yEnd = std::min(y0 + kTile, desc.height);
        for (int y1 = y0; y1 < yEnd; y1 += kPacketRows) {
            for (int x1 = x0; x1 < xEnd; x1 += kPacketColumns) {
                glm::ivec2 pixel[kPacket];
                int count = 0;
                for (int c = 0; c < kPacket; ++c) {
                    const glm::ivec2 p(x1 + c % kPacketColumns, y1 + c / kPacketColumns);
                    if (p.x < xEnd && p.y < yEnd) {
                        pixel[count++] = p;
                    }
                }
                if (x1 + kPacketColumns - 1 < covered.x0 || x1 > covered.x1 ||
                    y1 + kPacketRows - 1 < covered.y0 || y1 > covered.y1) {
                    for (int c = 0; c < count; ++c) {
                        std::uint8_t* px = image.at(pixel[c].x, pixel[c].y);
                        std::copy(background, background + 3, px);
                        px[3] = 255;
                        premultiplied[std::size_t(pixel[c].y) * desc.width + pixel[c].x] =
                            glm::vec4(0.0f);
                    }
                    continue;
                }
                glm::dvec3 d[kPacket], w[kPacket];
                RayOutput r[kPacket];
                // ViewFrame::rayDirection, its column and row terms computed once.
                double sx[kPacketColumns], sy[kPacketRows];
                for (int c = 0; c < kPacketColumns; ++c) {
                    sx[c] = frame.screenX(x1 + c, desc.width);
                }
                for (int c = 0; c < kPacketRows; ++c) {
                    sy[c] = frame.screenY(y1 + c, desc.height);
                }
                for (int c = 0; c < count; ++c) {
                    w[c] = frame.direction(sx[pixel[c].x - x1], sy[pixel[c].y - y1]);
                    d[c] = toIndexLinear * w[c];
                }
                if constexpr (requires { kernel.castPacket(origin, d, w, count, r); }) {
                    kernel.castPacket(origin, d, w, count, r);
                } else {
                    for (int c = 0; c < count; ++c) {
                        r[c] = kernel.cast(origin, d[c], w[c]);
                    }
                }
                for (int c = 0; c < count; ++c) {
                    const int x = pixel[c].x, y = pixel[c].y;
                    total += r[c].samples;
                    premultiplied[std::size_t(y) * desc.width + x] = glm::vec4(r[c].rgba);
                    if (projection != nullptr) {
                        (*projection)[std::size_t(y) * desc.width + x] = glm::vec2(r[c].projection);
                    }
                    const glm::dvec3 rgb =
                        glm::dvec3(r[c].rgba) + (1.0 - r[c].rgba.a) * desc.background;
                    std::uint8_t* px = image.at(x, y);
                    for (int ch = 0; ch < 3; ++ch) {
                        // Rounds as lround does for values >= 0, without a libm call.
                        px[ch] =
                            static_cast<std::uint8_t>(std::clamp(rgb[ch], 0.0, 1.0) * 255.0 + 0.5);
                    }
                    px[3] = 255;
                }
            }
        }
    }
    samples = total;
}

} // namespace lucent
