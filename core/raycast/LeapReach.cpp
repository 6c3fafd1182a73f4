#include "core/raycast/LeapReach.h"

#include <algorithm>

namespace lucent {

std::vector<std::uint8_t> leapReach(const std::vector<std::uint8_t>& leapable, glm::ivec3 cells) {
    // Chessboard distance to the nearest cell that cannot be leapt: two
    // raster passes over the 3x3x3 neighbourhood (exact for this metric).
    constexpr int kFar = 255;
    std::vector<std::uint8_t> d(leapable.size());
    for (std::size_t n = 0; n < d.size(); ++n) {
        d[n] = leapable[n] != 0 ? kFar : 0;
    }
    const int nx = cells.x, ny = cells.y, nz = cells.z;
    auto index = [&](int x, int y, int z) { return std::size_t(x + nx * (y + ny * z)); };
    // Neighbours before (forward) or after (backward) a cell in raster order.
    auto relax = [&](int x, int y, int z, int sign) {
        int best = d[index(x, y, z)];
        if (best == 0) {
            return;
        }
        for (int dz = -1; dz <= 1; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const int order = dz != 0 ? dz : dy != 0 ? dy : dx;
                    if (order != sign) {
                        continue;
                    }
                    const int a = x + dx, b = y + dy, c = z + dz;
                    if (a >= 0 && b >= 0 && c >= 0 && a < nx && b < ny && c < nz) {
                        best = std::min(best, d[index(a, b, c)] + 1);
                    }
                }
            }
        }
        d[index(x, y, z)] = std::uint8_t(best);
    };
    for (int z = 0; z < nz; ++z) {
        for (int y = 0; y < ny; ++y) {
            for (int x = 0; x < nx; ++x) {
                relax(x, y, z, -1);
            }
        }
    }
    for (int z = nz - 1; z >= 0; --z) {
        for (int y = ny - 1; y >= 0; --y) {
            for (int x = nx - 1; x >= 0; --x) {
                relax(x, y, z, 1);
            }
        }
    }
    for (std::uint8_t& v : d) {
        v = v == 0 ? 0 : std::uint8_t(std::min(v - 1, kFar - 1));
    }
    return d;
}

} // namespace lucent
