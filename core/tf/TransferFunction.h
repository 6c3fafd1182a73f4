#pragma once

// Transfer functions: piecewise-linear opacity and colour over the data value
// (HU for CT), shading parameters, the JSON file format, presets, and the tables
// the ray casters use (a baked lookup table and a pre-integration table).
//
// Opacity convention: an opacity point's opacity is the opacity of a segment of
// length dt_ref (one voxel of the volume's smallest spacing). A sample taken with
// step dt is corrected to a' = 1 - (1 - a)^(dt / dt_ref) (see DESIGN.md).
//
// JSON format (one object; keys are exact, an unknown key is an error):
//
//   {
//     "name": "ct-bone",                      optional string
//     "modality": "CT",                       optional: "CT", "MR" or ""
//     "opacity": [[value, opacity], ...],     required, >= 1 point, values strictly
//                                             increasing, opacity in [0, 1]
//     "colour": [[value, r, g, b], ...],      required, >= 1 point, values strictly
//                                             increasing, r, g, b in [0, 1]
//     "shading": {                            optional object, every key optional
//       "enabled": true, "ambient": 0.1, "diffuse": 0.9,
//       "specular": 0.2, "specular_power": 10
//     }
//   }
//
// Between points the functions are linear; beyond the first and last point they
// are constant. Presets live in resources/presets/<name>.json (see its README.md).

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

// Opacity per dt_ref (one voxel of the smallest spacing), in [0, 1].
struct OpacityPoint {
    double value = 0.0;
    double opacity = 0.0;
    bool operator==(const OpacityPoint&) const = default;
};

// Colour, rgb in [0, 1], not premultiplied.
struct ColourPoint {
    double value = 0.0;
    glm::dvec3 rgb{0.0};
    bool operator==(const ColourPoint&) const = default;
};

// Phong shading parameters (the ray caster's lighting model).
struct Shading {
    bool enabled = true;
    double ambient = 0.1;
    double diffuse = 0.9;
    double specular = 0.2;
    double specularPower = 10.0;
    bool operator==(const Shading&) const = default;
};

// A transfer-function file or preset that cannot be read: the message names the
// source (file name or preset name) and, where there is one, the field.
class TransferFunctionError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Piecewise linear between points; constant beyond the first/last point.
class TransferFunction {
public:
    std::string name;
    std::string modality;              // "CT", "MR" or empty
    std::vector<OpacityPoint> opacity; // sorted by value (validate() enforces)
    std::vector<ColourPoint> colour;   // sorted by value (validate() enforces)
    Shading shading;

    // 0 (opacity) or black (colour) when the list is empty.
    double opacityAt(double value) const;
    glm::dvec3 colourAt(double value) const;

    // Largest opacity over [lo, hi] (the bounds may come in either order). Exact for
    // piecewise-linear functions: the endpoints and the points inside the interval.
    // The empty-space test for bricks: a brick is empty when this is 0.
    double maxOpacity(double lo, double hi) const;

    // Throws std::invalid_argument naming the field ("opacity[2]", "colour",
    // "shading.ambient", ...): empty lists, unsorted or duplicate values, opacity or
    // rgb outside [0, 1], NaN or infinite numbers, negative shading terms, an
    // unknown modality.
    void validate() const;

    bool operator==(const TransferFunction&) const = default;
};

// --- JSON --------------------------------------------------------------------

// Parses and validates. Throws TransferFunctionError whose message starts with
// sourceName and names the field (or the JSON syntax error's line and column).
TransferFunction parseTransferFunction(std::string_view json, const std::string& sourceName);
// Reads a file (the path is the source name in errors).
TransferFunction readTransferFunction(const std::filesystem::path& path);
// Validates, then writes atomically (a temporary file renamed over the target).
// Throws std::invalid_argument for an invalid function, TransferFunctionError when
// the file cannot be written.
void writeTransferFunction(const TransferFunction& tf, const std::filesystem::path& path);
// The JSON text: one point per line, numbers in the shortest form that reads back
// to the same double (a round trip is exact).
std::string toJson(const TransferFunction& tf);

// --- Presets -----------------------------------------------------------------

// Where presets are searched, in order: $LUCENT_PRESET_DIR if set, the source
// tree's resources/presets, <prefix>/share/lucent/presets (prefix: the directory
// above the running executable's, then the install prefix). Directories that do
// not exist are left out.
std::vector<std::filesystem::path> presetDirectories();
// Loads <dir>/<name>.json from the first directory that has it. Throws
// TransferFunctionError listing the known names when there is none, or naming the
// file and field when it is malformed.
TransferFunction loadPreset(std::string_view name);
// The names of all presets found (file stems), sorted, without duplicates.
std::vector<std::string> presetNames();

// --- Tables ------------------------------------------------------------------

// `size` entries evenly over [lo, hi]: entry n at lo + n * (hi - lo) / (size - 1).
// rgba: colour NOT premultiplied, alpha = opacity per dt_ref (uncorrected).
struct TfTable {
    double lo = 0.0;
    double hi = 1.0;
    std::vector<glm::vec4> rgba;
    // Linear interpolation between entries, clamped to the ends.
    glm::vec4 lookup(double value) const;
};
// Throws std::invalid_argument for an invalid function, size < 2 or !(lo < hi).
TfTable bakeTable(const TransferFunction& tf, double lo, double hi, int size);

// Pre-integration (Engel, Kraus, Ertl 2001) of a ray segment of length
// dt = stepRatio * dt_ref along which the data value goes linearly from sf (front)
// to sb (back). The segment is integrated continuously with extinction
// tau(s) = -ln(1 - a(s)) per dt_ref and emission colour(s) * tau(s):
//   alpha = 1 - exp(-stepRatio * int_0^1 tau(s(u)) du)
//   rgb   = int_0^1 colour(s(u)) stepRatio tau(s(u)) exp(-stepRatio int_0^u tau) du
// which for sf == sb is exactly alpha = 1 - (1 - a)^stepRatio and rgb = colour * alpha
// (the corrected sample of the ordinary ray caster). Result: rgb premultiplied.
//
// Accuracy: the segment is split at every breakpoint it crosses, so a(s) and
// colour(s) are linear on each piece; the optical depth of each piece and sub-step is
// integrated in closed form (the integral of -ln(1 - a) for linear a), so alpha is
// exact up to rounding. Each piece is cut into sub-steps of optical depth <= 0.25
// (2 to 64 per piece); a sub-step's emission is placed at its centroid, found with
// Simpson's rule on the opacity accumulated within the sub-step (exact where that is
// quadratic, e.g. thin sub-steps with linearly varying extinction); the linear colour
// integrates exactly at the centroid. sf == sb takes the closed form directly. Against a 4e5-step
// brute-force integral over random segments of every preset the largest difference
// was 2e-5 (rgb or alpha, absolute); the tests check 1e-4. Cost: a 256 x 256 table
// takes ~10-50 ms on two cores with -O2. Validates its arguments on every call (the
// double-precision reference; renderers use the table).
glm::dvec4 preintegrateSegment(const TransferFunction& tf, double sf, double sb, double stepRatio);

// table[i + size * j] for sf = value(i), sb = value(j), value(n) = lo + n * (hi - lo) /
// (size - 1); rgb premultiplied, alpha the segment's opacity. Built in double
// precision, rows in parallel (OpenMP), stored as float.
struct PreintegrationTable {
    double lo = 0.0;
    double hi = 1.0;
    int size = 0;
    double stepRatio = 1.0;
    std::vector<glm::vec4> rgba;
    // Bilinear interpolation, clamped to the table's range.
    glm::vec4 lookup(double front, double back) const;
};
// Throws std::invalid_argument for an invalid function, size < 2, !(lo < hi) or a
// stepRatio that is not finite and > 0.
PreintegrationTable buildPreintegrationTable(const TransferFunction& tf, double lo, double hi,
                                             int size, double stepRatio);

} // namespace lucent
