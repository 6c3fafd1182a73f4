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

// The leapable cells as bits, a row of cells along x in whole 64-bit words;
// bits past the end of a row are set (beyond the grid is leapable).
struct CellBits {
    glm::ivec3 n{0};
    std::size_t rowWords = 0, rows = 0;
    std::uint64_t pastEnd = 0; // the bits of a row's last word beyond the grid
    std::vector<std::uint64_t> words;

    explicit CellBits(glm::ivec3 cells)
        : n(cells), rowWords((std::size_t(cells.x) + 63) / 64),
          rows(std::size_t(cells.y) * std::size_t(cells.z)), words(rowWords * rows, 0) {
        const int used = cells.x % 64;
        pastEnd = used == 0 ? 0 : ~((std::uint64_t(1) << used) - 1);
    }
    std::uint64_t* row(std::size_t r) { return words.data() + r * rowWords; }
    const std::uint64_t* row(std::size_t r) const { return words.data() + r * rowWords; }
};

// out = the cells whose 3x3x3 neighbourhood is leapable in `in`: along x by
// shifts, then along y and z by rows (beyond the grid is leapable).
void erode(const CellBits& in, CellBits& scratch, CellBits& out) {
    const std::size_t w = in.rowWords;
    const std::ptrdiff_t rows = std::ptrdiff_t(in.rows);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::uint64_t* e = in.row(std::size_t(r));
        std::uint64_t* to = scratch.row(std::size_t(r));
        for (std::size_t i = 0; i < w; ++i) {
            const std::uint64_t before = i > 0 ? e[i - 1] >> 63 : 1;
            const std::uint64_t after = i + 1 < w ? e[i + 1] << 63 : std::uint64_t(1) << 63;
            to[i] = e[i] & ((e[i] << 1) | before) & ((e[i] >> 1) | after);
        }
        to[w - 1] |= in.pastEnd;
    }
    const int ny = in.n.y, nz = in.n.z;
    // Along y into out, then along z into scratch, swapped back.
    const auto alongRows = [w](const CellBits& from, CellBits& to, int length, int rowStride) {
        const std::ptrdiff_t rows = std::ptrdiff_t(from.rows);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            const int along = int(r / rowStride % length);
            const std::uint64_t* here = from.row(std::size_t(r));
            const std::uint64_t* before = along > 0 ? here - std::ptrdiff_t(rowStride * w) : here;
            const std::uint64_t* after =
                along + 1 < length ? here + std::ptrdiff_t(rowStride * w) : here;
            std::uint64_t* row = to.row(std::size_t(r));
            for (std::size_t i = 0; i < w; ++i) {
                row[i] = here[i] & before[i] & after[i];
            }
        }
    };
    alongRows(scratch, out, ny, 1);
    alongRows(out, scratch, nz, ny);
    out.words.swap(scratch.words);
}

} // namespace

std::vector<std::uint8_t> leapReachWithin(const std::vector<std::uint8_t>& leapable,
                                          glm::ivec3 cells, int cap) {
    CellBits bits(cells), scratch(cells), next(cells);
    const std::size_t nx = std::size_t(cells.x);
    for (std::size_t r = 0; r < bits.rows; ++r) {
        std::uint64_t* row = bits.row(r);
        for (std::size_t x = 0; x < nx; ++x) {
            row[x / 64] |= std::uint64_t(leapable[r * nx + x] != 0 ? 1 : 0) << (x % 64);
        }
        row[bits.rowWords - 1] |= bits.pastEnd;
    }
    std::vector<std::uint8_t> reach(leapable.size(), 0);
    // After k erosions a cell is set where every cell within k of it is leapable.
    for (int k = 1; k <= cap; ++k) {
        erode(bits, scratch, next);
        std::swap(bits.words, next.words);
        bool any = false;
        const std::ptrdiff_t rows = std::ptrdiff_t(bits.rows);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            const std::uint64_t* row = bits.row(std::size_t(r));
            std::uint8_t* out = reach.data() + std::size_t(r) * nx;
            for (std::size_t i = 0; i < bits.rowWords; ++i) {
                const std::uint64_t word = row[i] & ~(i + 1 == bits.rowWords ? bits.pastEnd : 0);
                const std::size_t x0 = i * 64, count = std::min<std::size_t>(64, nx - x0);
                if (word == 0) {
                    continue;
                }
                any = true;
                if (word == ~std::uint64_t(0)) { // the common case inside empty space
                    for (std::size_t b = 0; b < 64; ++b) {
                        ++out[x0 + b];
                    }
                    continue;
                }
                for (std::size_t b = 0; b < count; ++b) {
                    out[x0 + b] = std::uint8_t(out[x0 + b] + ((word >> b) & 1));
                }
            }
        }
        if (!any) {
            break;
        }
    }
    return reach;
}

} // namespace lucent
