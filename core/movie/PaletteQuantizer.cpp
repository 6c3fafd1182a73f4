#include "core/movie/PaletteQuantizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace lucent {
namespace {

constexpr int kBits = 6; // per channel in the histogram
constexpr int kLevels = 1 << kBits;

// One occupied histogram cell: its pixel count and the sums of their colours.
struct Cell {
    std::array<int, 3> key{}; // 6-bit channel values
    double count = 0.0;
    std::array<double, 3> sum{};
};

struct Box {
    std::size_t begin = 0, end = 0; // a range of cells
    double error = 0.0;             // squared distance of its pixels from its mean
    int axis = 0;                   // the channel of largest spread
};

std::array<double, 3> meanOf(const std::vector<Cell>& cells, std::size_t begin, std::size_t end) {
    double n = 0.0;
    std::array<double, 3> s{};
    for (std::size_t c = begin; c < end; ++c) {
        n += cells[c].count;
        for (int k = 0; k < 3; ++k) {
            s[k] += cells[c].sum[k];
        }
    }
    for (double& v : s) {
        v /= std::max(n, 1.0);
    }
    return s;
}

void measure(const std::vector<Cell>& cells, Box& box) {
    const std::array<double, 3> mean = meanOf(cells, box.begin, box.end);
    std::array<double, 3> spread{};
    for (std::size_t c = box.begin; c < box.end; ++c) {
        for (int k = 0; k < 3; ++k) {
            const double d = cells[c].sum[k] / cells[c].count - mean[k];
            spread[k] += cells[c].count * d * d;
        }
    }
    box.error = box.end - box.begin > 1 ? spread[0] + spread[1] + spread[2] : 0.0;
    box.axis = int(std::max_element(spread.begin(), spread.end()) - spread.begin());
}

// Splits `box` at the pixel median along its axis into itself and the returned box.
Box split(std::vector<Cell>& cells, Box& box) {
    const auto first = cells.begin() + std::ptrdiff_t(box.begin);
    const auto last = cells.begin() + std::ptrdiff_t(box.end);
    const int axis = box.axis;
    std::sort(first, last,
              [axis](const Cell& a, const Cell& b) { return a.key[axis] < b.key[axis]; });
    const double total =
        std::accumulate(first, last, 0.0, [](double n, const Cell& c) { return n + c.count; });
    double seen = 0.0;
    std::size_t cut = box.begin + 1;
    for (std::size_t c = box.begin; c + 1 < box.end; ++c) {
        seen += cells[c].count;
        cut = c + 1;
        if (seen >= 0.5 * total) {
            break;
        }
    }
    Box upper{cut, box.end};
    box.end = cut;
    measure(cells, box);
    measure(cells, upper);
    return upper;
}

} // namespace

PalettedImage quantizeToPalette(const ImageRGBA8& image, int maxColours) {
    if (image.empty() || image.pixels.size() != 4 * image.pixelCount()) {
        throw std::invalid_argument("quantizeToPalette: empty image or short pixel buffer");
    }
    maxColours = std::clamp(maxColours, 1, 256);
    auto cellOf = [](const std::uint8_t* p) {
        constexpr int shift = 8 - kBits;
        return ((p[0] >> shift) * kLevels + (p[1] >> shift)) * kLevels + (p[2] >> shift);
    };
    std::vector<int> cellIndex(std::size_t(kLevels) * kLevels * kLevels, -1);
    std::vector<Cell> cells;
    for (std::size_t n = 0; n < image.pixelCount(); ++n) {
        const std::uint8_t* p = image.pixels.data() + 4 * n;
        int& index = cellIndex[std::size_t(cellOf(p))];
        if (index < 0) {
            index = int(cells.size());
            constexpr int shift = 8 - kBits;
            cells.push_back({{p[0] >> shift, p[1] >> shift, p[2] >> shift}, 0.0, {}});
        }
        Cell& cell = cells[std::size_t(index)];
        cell.count += 1.0;
        for (int k = 0; k < 3; ++k) {
            cell.sum[k] += p[k];
        }
    }

    std::vector<Box> boxes{{0, cells.size()}};
    measure(cells, boxes.front());
    while (int(boxes.size()) < maxColours) {
        const auto worst =
            std::max_element(boxes.begin(), boxes.end(),
                             [](const Box& a, const Box& b) { return a.error < b.error; });
        if (worst->error <= 0.0) {
            break; // every box is one cell or one colour
        }
        Box upper = split(cells, *worst);
        boxes.push_back(upper);
    }

    PalettedImage out;
    out.width = image.width;
    out.height = image.height;
    for (const Box& box : boxes) {
        const std::array<double, 3> mean = meanOf(cells, box.begin, box.end);
        out.palette.push_back({std::uint8_t(std::lround(mean[0])),
                               std::uint8_t(std::lround(mean[1])),
                               std::uint8_t(std::lround(mean[2]))});
    }
    // Each occupied cell to the palette entry nearest its mean colour.
    std::vector<std::uint8_t> entryOfCell(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) {
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t e = 0; e < out.palette.size(); ++e) {
            double d = 0.0;
            for (int k = 0; k < 3; ++k) {
                const double diff = cells[c].sum[k] / cells[c].count - out.palette[e][k];
                d += diff * diff;
            }
            if (d < best) {
                best = d;
                entryOfCell[c] = std::uint8_t(e);
            }
        }
    }
    // cellIndex still points at each cell's slot from before the sort: map through the keys.
    std::vector<int> slotOfKey(cellIndex.size(), -1);
    for (std::size_t c = 0; c < cells.size(); ++c) {
        const std::array<int, 3>& k = cells[c].key;
        slotOfKey[std::size_t((k[0] * kLevels + k[1]) * kLevels + k[2])] = int(c);
    }
    out.indices.resize(image.pixelCount());
    for (std::size_t n = 0; n < image.pixelCount(); ++n) {
        out.indices[n] =
            entryOfCell[std::size_t(slotOfKey[std::size_t(cellOf(image.pixels.data() + 4 * n))])];
    }
    return out;
}

} // namespace lucent
