#pragma once

#include "core/image/Image.h"

namespace lucent {

// Image error metrics for comparing renderings (CPU against GPU, a frame
// against a baseline). Both take two images of the same size and throw
// std::invalid_argument naming both sizes when they differ, or when an
// image's pixel buffer does not hold width * height * 4 bytes.

// Peak signal-to-noise ratio in dB over the R, G and B channels of every
// pixel (alpha is ignored), peak value 255:
//   MSE = sum((a - b)^2) / (3 * width * height),  PSNR = 10 log10(255^2 / MSE).
// Identical colour channels give +infinity. Throws std::invalid_argument for
// empty images.
double psnr(const ImageRGBA8& a, const ImageRGBA8& b);

// Structural similarity (Wang, Bovik, Sheikh, Simoncelli 2004) on luminance
// Y = 0.299 R + 0.587 G + 0.114 B (Rec. 601 luma, kept in double, not rounded;
// alpha is ignored). Local statistics use an 11x11 Gaussian window, sigma 1.5,
// normalised to sum 1; K1 = 0.01, K2 = 0.03, L = 255. The result is the mean
// of the SSIM map over every position where the whole window lies inside the
// image (the "valid" region, as in Wang's reference ssim_index.m; no
// downsampling). Identical images give exactly 1. Throws
// std::invalid_argument for images smaller than 11x11.
double ssim(const ImageRGBA8& a, const ImageRGBA8& b);

// Window side of ssim(): images must be at least this wide and tall.
inline constexpr int kSsimWindow = 11;

} // namespace lucent
