#pragma once

#include <filesystem>

#include "core/image/Image.h"

namespace lucent {

// Reads a PNG of any colour type and bit depth (grey, grey + alpha, palette,
// RGB, RGBA; 1 to 16 bits; interlaced or not) as 8-bit RGBA. Grey becomes
// R = G = B; palette entries and tRNS transparency are expanded; 16-bit
// samples are scaled to 8 bits with rounding; images without alpha get A =
// 255. Sample values are kept as stored: no gamma or colour-space correction.
// Throws LoadError (core/io/LoadControl.h) naming the file and the problem
// (missing, unreadable, not a PNG, corrupt or truncated, larger than
// kMaxPngSide on a side).
ImageRGBA8 readPng(const std::filesystem::path& file);

// Writes an 8-bit RGBA PNG. The file appears complete or not at all: the data
// goes to a temporary file in the same folder, renamed onto `file` when
// everything is written. Throws std::runtime_error naming the file (cannot
// create, write failed, empty or inconsistent image).
void writePng(const ImageRGBA8& image, const std::filesystem::path& file);

// readPng() refuses images wider or taller than this (a guard against
// headers that would make it allocate terabytes).
inline constexpr int kMaxPngSide = 1 << 15;

} // namespace lucent
