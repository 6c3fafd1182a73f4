#include "core/raycast/LeapReach.h"

#include <algorithm>
#include <cstddef>

namespace lucent {

std::vector<std::uint8_t> leapReach(const std::vector<std::uint8_t>& leapable, glm::ivec3 cells) {
    // Chessboard distance to the nearest cell that cannot be leapt: two
    // raster passes over the 3x3x3 neighbourhood (exact for this metric), on
    // a grid padded by one cell of "far away" (beyond the grid is no limit).
    constexpr int kFar = 255;
    const int px = cells.x + 2, py = cells.y + 2, pz = cells.z + 2;
    auto padded = [&](int x, int y, int z) { return std::size_t(x + px * (y + py * z)); };
    std::vector<std::uint8_t> d(std::size_t(px) * py * pz, kFar);
    std::size_t n = 0;
    for (int z = 1; z <= cells.z; ++z) {
        for (int y = 1; y <= cells.y; ++y) {
            for (int x = 1; x <= cells.x; ++x) {
                d[padded(x, y, z)] = leapable[n++] != 0 ? kFar : 0;
            }
        }
    }
    // The 13 neighbours before a cell in raster order.
    std::ptrdiff_t before[13];
    int count = 0;
    for (int dz = -1; dz <= 1; ++dz) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                if ((dz != 0 ? dz : dy != 0 ? dy : dx) < 0) {
                    before[count++] = dx + std::ptrdiff_t(px) * (dy + std::ptrdiff_t(py) * dz);
                }
            }
        }
    }
    auto relax = [&](std::size_t c, std::ptrdiff_t sign) {
        int best = d[c];
        if (best == 0) {
            return;
        }
        for (const std::ptrdiff_t o : before) {
            best = std::min(best, d[std::size_t(std::ptrdiff_t(c) + sign * o)] + 1);
        }
        d[c] = std::uint8_t(best);
    };
    for (int z = 1; z <= cells.z; ++z) {
        for (int y = 1; y <= cells.y; ++y) {
            for (int x = 1; x <= cells.x; ++x) {
                relax(padded(x, y, z), 1);
            }
        }
    }
    for (int z = cells.z; z >= 1; --z) {
        for (int y = cells.y; y >= 1; --y) {
            for (int x = cells.x; x >= 1; --x) {
                relax(padded(x, y, z), -1);
            }
        }
    }
    std::vector<std::uint8_t> reach(leapable.size());
    n = 0;
    for (int z = 1; z <= cells.z; ++z) {
        for (int y = 1; y <= cells.y; ++y) {
            for (int x = 1; x <= cells.x; ++x) {
                const int v = d[padded(x, y, z)];
                reach[n++] = std::uint8_t(v == 0 ? 0 : std::min(v - 1, kFar - 1));
            }
        }
    }
    return reach;
}

namespace {

// e and its neighbours one cell either way along an axis (beyond the grid
// counts as leapable): out = e & e[-1] & e[+1]. The grid as [outer][length][inner],
// the axis `length` cells long, `inner` cells apart.
void erodeAxis(const std::vector<std::uint8_t>& e, std::vector<std::uint8_t>& out,
               std::size_t inner, std::size_t length) {
    const std::ptrdiff_t outer = std::ptrdiff_t(e.size() / (inner * length));
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t o = 0; o < outer; ++o) {
        const std::uint8_t* line = e.data() + std::size_t(o) * length * inner;
        std::uint8_t* to = out.data() + std::size_t(o) * length * inner;
        if (inner == 1) { // along x: neighbours in the same row
            for (std::size_t a = 0; a < length; ++a) {
                const std::uint8_t before = a > 0 ? line[a - 1] : 1;
                const std::uint8_t after = a + 1 < length ? line[a + 1] : 1;
                to[a] = line[a] & before & after;
            }
            continue;
        }
        for (std::size_t a = 0; a < length; ++a) {
            const std::uint8_t* here = line + a * inner;
            const std::uint8_t* before = a > 0 ? here - inner : here;
            const std::uint8_t* after = a + 1 < length ? here + inner : here;
            std::uint8_t* row = to + a * inner;
            for (std::size_t i = 0; i < inner; ++i) {
                row[i] = here[i] & before[i] & after[i];
            }
        }
    }
}

} // namespace

std::vector<std::uint8_t> leapReachWithin(const std::vector<std::uint8_t>& leapable,
                                          glm::ivec3 cells, int cap) {
    std::vector<std::uint8_t> eroded(leapable.size()), scratch(leapable.size());
    for (std::size_t i = 0; i < leapable.size(); ++i) {
        eroded[i] = leapable[i] != 0 ? 1 : 0;
    }
    std::vector<std::uint8_t> reach(leapable.size(), 0);
    const std::size_t sx = 1, sy = std::size_t(cells.x), sz = sy * std::size_t(cells.y);
    // After k erosions a cell is 1 where every cell within k of it is leapable.
    for (int k = 1; k <= cap; ++k) {
        erodeAxis(eroded, scratch, sx, std::size_t(cells.x));
        erodeAxis(scratch, eroded, sy, std::size_t(cells.y));
        scratch.swap(eroded);
        erodeAxis(scratch, eroded, sz, std::size_t(cells.z));
        for (std::size_t i = 0; i < reach.size(); ++i) {
            reach[i] = std::uint8_t(reach[i] + eroded[i]);
        }
    }
    return reach;
}

} // namespace lucent
