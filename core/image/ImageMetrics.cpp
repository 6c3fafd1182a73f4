#include "core/image/ImageMetrics.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace lucent {

namespace {

std::string sizeText(const ImageRGBA8& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

void checkPair(const ImageRGBA8& a, const ImageRGBA8& b, const char* what) {
    for (const ImageRGBA8* image : {&a, &b}) {
        if (image->width < 0 || image->height < 0 ||
            image->pixels.size() != 4 * image->pixelCount()) {
            throw std::invalid_argument(std::string(what) + ": a " + sizeText(*image) +
                                        " image must hold " +
                                        std::to_string(4 * image->pixelCount()) + " bytes, not " +
                                        std::to_string(image->pixels.size()));
        }
    }
    if (a.width != b.width || a.height != b.height) {
        throw std::invalid_argument(std::string(what) + ": image sizes differ: " + sizeText(a) +
                                    " and " + sizeText(b));
    }
    if (a.empty()) {
        throw std::invalid_argument(std::string(what) + ": the images are empty (" + sizeText(a) +
                                    ")");
    }
}

constexpr int kRadius = kSsimWindow / 2;

// The normalised 1-D Gaussian (sigma 1.5); its outer product with itself is
// the normalised 11x11 window of Wang et al.
std::array<double, kSsimWindow> gaussian1d() {
    constexpr double sigma = 1.5;
    std::array<double, kSsimWindow> g{};
    double sum = 0.0;
    for (int i = 0; i < kSsimWindow; ++i) {
        const double d = i - kRadius;
        g[static_cast<std::size_t>(i)] = std::exp(-(d * d) / (2.0 * sigma * sigma));
        sum += g[static_cast<std::size_t>(i)];
    }
    for (double& v : g) {
        v /= sum;
    }
    return g;
}

std::vector<double> luminance(const ImageRGBA8& image) {
    std::vector<double> y(image.pixelCount());
    const auto n = static_cast<std::ptrdiff_t>(y.size());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const std::uint8_t* p = image.pixels.data() + 4 * i;
        y[static_cast<std::size_t>(i)] = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
    }
    return y;
}

// Per-position local statistics: the five window-weighted sums
// E[x], E[y], E[x^2], E[y^2], E[xy].
constexpr std::size_t kMoments = 5;

} // namespace

double psnr(const ImageRGBA8& a, const ImageRGBA8& b) {
    checkPair(a, b, "psnr");
    const int h = a.height;
    const auto rowBytes = static_cast<std::size_t>(a.width) * 4;
    // Squared errors summed per row in integers: exact, and the total does not
    // depend on how rows are spread over threads.
    std::vector<std::uint64_t> rowSums(static_cast<std::size_t>(h), 0);
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* pa = a.at(0, y);
        const std::uint8_t* pb = b.at(0, y);
        std::uint64_t sum = 0;
        for (std::size_t i = 0; i < rowBytes; i += 4) {
            for (std::size_t c = 0; c < 3; ++c) {
                const int d = int(pa[i + c]) - int(pb[i + c]);
                sum += static_cast<std::uint64_t>(d * d);
            }
        }
        rowSums[static_cast<std::size_t>(y)] = sum;
    }
    const std::uint64_t total = std::accumulate(rowSums.begin(), rowSums.end(), std::uint64_t{0});
    if (total == 0) {
        return std::numeric_limits<double>::infinity();
    }
    const double mse = static_cast<double>(total) / (3.0 * static_cast<double>(a.pixelCount()));
    return 10.0 * std::log10(255.0 * 255.0 / mse);
}

double ssim(const ImageRGBA8& a, const ImageRGBA8& b) {
    checkPair(a, b, "ssim");
    if (a.width < kSsimWindow || a.height < kSsimWindow) {
        throw std::invalid_argument("ssim: images must be at least " + std::to_string(kSsimWindow) +
                                    "x" + std::to_string(kSsimWindow) + ", not " + sizeText(a));
    }
    const std::array<double, kSsimWindow> g = gaussian1d();
    const std::vector<double> ya = luminance(a);
    const std::vector<double> yb = luminance(b);
    const int w = a.width;
    const int h = a.height;
    const int vw = w - kSsimWindow + 1; // valid region
    const int vh = h - kSsimWindow + 1;

    // Horizontal pass over every image row, valid columns only, into one
    // plane per moment: E[a], E[b], E[a^2], E[b^2], E[ab].
    const auto vws = static_cast<std::size_t>(vw);
    std::vector<std::vector<double>> planes(kMoments,
                                            std::vector<double>(vws * static_cast<std::size_t>(h)));
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; ++y) {
        const std::size_t in = static_cast<std::size_t>(y) * static_cast<std::size_t>(w);
        const double* ra = ya.data() + in;
        const double* rb = yb.data() + in;
        const std::size_t out = static_cast<std::size_t>(y) * vws;
        for (std::size_t x = 0; x < vws; ++x) {
            std::array<double, kMoments> m{};
            for (std::size_t t = 0; t < kSsimWindow; ++t) {
                const double pa = ra[x + t];
                const double pb = rb[x + t];
                m[0] += g[t] * pa;
                m[1] += g[t] * pb;
                m[2] += g[t] * (pa * pa);
                m[3] += g[t] * (pb * pb);
                m[4] += g[t] * (pa * pb);
            }
            for (std::size_t k = 0; k < kMoments; ++k) {
                planes[k][out + x] = m[k];
            }
        }
    }

    // Vertical pass and the SSIM map, summed per row so the result does not
    // depend on the number of threads.
    constexpr double L = 255.0;
    constexpr double C1 = (0.01 * L) * (0.01 * L);
    constexpr double C2 = (0.03 * L) * (0.03 * L);
    std::vector<double> rowSums(static_cast<std::size_t>(vh), 0.0);
    // Per-thread rows of window sums, allocated here: nothing may throw
    // inside the parallel region.
    const int threads = std::max(1, omp_get_max_threads());
    std::vector<double> scratch(static_cast<std::size_t>(threads) * kMoments * vws);
#pragma omp parallel num_threads(threads)
    {
        double* mine =
            scratch.data() + static_cast<std::size_t>(omp_get_thread_num()) * kMoments * vws;
        const std::array<double*, kMoments> m = {mine, mine + vws, mine + 2 * vws, mine + 3 * vws,
                                                 mine + 4 * vws};
#pragma omp for schedule(static)
        for (int y = 0; y < vh; ++y) {
            for (std::size_t k = 0; k < kMoments; ++k) {
                double* acc = m[k];
                std::fill(acc, acc + vws, 0.0);
                for (std::size_t t = 0; t < kSsimWindow; ++t) {
                    const double* src = planes[k].data() + (static_cast<std::size_t>(y) + t) * vws;
                    for (std::size_t x = 0; x < vws; ++x) {
                        acc[x] += g[t] * src[x];
                    }
                }
            }
            double sum = 0.0;
            for (std::size_t x = 0; x < vws; ++x) {
                const double muA = m[0][x];
                const double muB = m[1][x];
                const double varA = m[2][x] - muA * muA;
                const double varB = m[3][x] - muB * muB;
                const double cov = m[4][x] - muA * muB;
                sum += ((2.0 * muA * muB + C1) * (2.0 * cov + C2)) /
                       ((muA * muA + muB * muB + C1) * (varA + varB + C2));
            }
            rowSums[static_cast<std::size_t>(y)] = sum;
        }
    }
    const double total = std::accumulate(rowSums.begin(), rowSums.end(), 0.0);
    return total / (static_cast<double>(vw) * static_cast<double>(vh));
}

} // namespace lucent
