#include "render/GpuRayCaster.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "core/raycast/BrickVisibility.h"
#include "core/scene/ViewFrame.h"
#include "render/BrickStreamer.h"
#include "render/CastKey_p.h"
#include "render/GlError.h"
#include "render/GlObjects_p.h"
#include "render/GpuBudget.h"
#include "render/LeapTextures.h"
#include "render/OverlayTextures.h"
#include "render/RenderTarget.h"
#include "render/SceneTextures.h"
#include "render/SurfaceRenderer.h"

namespace lucent {

namespace {

constexpr int kTableSize = 4096; // as the CPU ray caster's float path
constexpr int kPreintegrationSize = 256;
constexpr int kCellSize = 8; // the finer leaping level, as on the CPU (BrickStreamer's cells)

// The specular power when it is a whole number the shader can multiply out, else 0.
int integerPower(const Shading& s) {
    const double p = s.specularPower;
    return p >= 1.0 && p <= 64.0 && p == std::floor(p) ? int(p) : 0;
}

int shaderMode(RenderMode m) {
    switch (m) {
    case RenderMode::Dvr:
        return 0;
    case RenderMode::Mip:
        return 1;
    case RenderMode::MinIp:
        return 2;
    case RenderMode::Average:
        return 3;
    case RenderMode::Isosurface:
        break;
    }
    return 4;
}

// What refining a brick is worth before its content: the projected size of a
// level-0 voxel at its nearest point to the eye, in pixels, weighed by how
// near the centre of the image it is (1 there, 1/2 at the image's edge).
double brickWorth(const VolumeGeometry& g, const ViewFrame& frame, int height, const glm::dvec3& lo,
                  const glm::dvec3& hi) {
    const glm::dvec3 centreIndex = 0.5 * (lo + hi);
    const glm::dvec3 centre = g.toPatient(centreIndex);
    const double radius = 0.5 * glm::length(g.toPatient(hi) - g.toPatient(lo));
    const double depth = std::max(glm::dot(centre - frame.eye, frame.forward) - radius, 1e-3);
    const double voxel = std::min({g.spacing.x, g.spacing.y, g.spacing.z});
    const double pixels = voxel / (2.0 * depth * frame.tanHalfFov) * double(height);
    const glm::dvec3 toCentre = centre - frame.eye;
    const double along = std::max(glm::dot(toCentre, frame.forward), 1e-3);
    const double x = glm::dot(toCentre, frame.right) / (along * frame.tanHalfFov * frame.aspect);
    const double y = glm::dot(toCentre, frame.up) / (along * frame.tanHalfFov);
    return pixels / (1.0 + x * x + y * y);
}

} // namespace

namespace {

// What a part of a volume changes in a render (nothing for a whole volume):
// the description in the part's indices, the whole volume's box that anchors
// the lattice, the open faces, the description's clip box.
struct PartFrame {
    RenderDescription local;
    glm::dvec3 boxLo{0.0}, boxHi{0.0};
    glm::ivec3 openHi{0};
    glm::dvec3 sceneClipLo{0.0}, sceneClipHi{0.0};
    bool empty = false; // the clip box leaves the part nothing
};

PartFrame partFrame(const std::optional<VolumePart>& part, const Volume& volume,
                    const RenderDescription& asked) {
    PartFrame f{asked};
    f.boxHi = glm::dvec3(volume.dims() - 1);
    if (!part) {
        return f;
    }
    const glm::dvec3 offset(part->offset), wholeHi(part->whole.dims - 1);
    f.boxLo = -offset;
    f.boxHi = wholeHi - offset;
    f.sceneClipLo = glm::max(asked.clip.lo, glm::dvec3(0.0)) - offset;
    f.sceneClipHi = glm::min(asked.clip.hi, wholeHi) - offset;
    f.local.clip.lo = glm::max(f.sceneClipLo, glm::dvec3(part->owned.lo) - offset);
    f.local.clip.hi = glm::min(f.sceneClipHi, glm::dvec3(part->owned.hi) - offset);
    f.local.background = glm::dvec3(0.0);
    f.local.volume = &volume;
    for (int a = 0; a < 3; ++a) {
        f.openHi[a] = part->sharedHi(a) && asked.clip.hi[a] >= double(part->owned.hi[a]) ? 1 : 0;
    }
    f.empty = glm::any(glm::lessThan(f.local.clip.hi, f.local.clip.lo));
    return f;
}

} // namespace

struct GpuRayCaster::State {
    const Volume& volume;
    GpuOptions options;
    std::size_t budget = 0;
    std::string budgetSource;

    double valueLo = 0.0, valueHi = 1.0;
    std::optional<VolumePart> part; // a part of a volume drawn alone (VolumePart.h)

    std::map<std::string, std::unique_ptr<ShaderProgram>> programs; // by their #defines
    std::array<std::unique_ptr<ShaderProgram>, 2> composite; // drawInPlace's: composite, stretch
    GlVertexArray vao;
    RenderTarget target;
    // The description whose frame the target holds, and that frame's statistics.
    std::optional<RenderDescription> inTarget;
    RenderStats inTargetStats;
    GpuFrameStats last;                      // the last frame's
    std::unique_ptr<BrickStreamer> streamer; // the bricks on the GPU
    SceneTextures scene;
    LeapTextures leaping;                          // distance maps, made with the #defines
    OverlayTextures overlay;                       // a fused render's second volume and its table
    std::shared_ptr<const SurfaceDisplay> surface; // drawn with the volume; null: none
    std::unique_ptr<SurfaceRenderer> surfaceRenderer;

    State(const Volume& v, GpuOptions o) : volume(v), options(o) {}

    std::size_t drawSurface(const RenderDescription& d) {
        if (!surfaceRenderer) {
            surfaceRenderer = std::make_unique<SurfaceRenderer>();
        }
        return surfaceRenderer->draw(*surface,
                                     makeViewFrame(volume.geometry(), d.camera, d.width, d.height),
                                     d.transferFunction.shading, d.width, d.height);
    }
};

GpuRayCaster::GpuRayCaster(const Volume& volume, GpuOptions options) {
    if (epoxy_gl_version() < 43) {
        throw GlError("the GPU ray caster needs OpenGL 4.3 or newer; the current context has " +
                      std::to_string(epoxy_gl_version() / 10) + "." +
                      std::to_string(epoxy_gl_version() % 10));
    }
    if (volume.empty()) {
        throw std::invalid_argument("the GPU ray caster was given an empty volume");
    }
    state_ = std::make_unique<State>(volume, options);
    State& s = *state_;
    const GpuBudget b = gpuBudget(options.budgetBytes);
    s.budget = b.bytes;
    s.budgetSource = b.source;
    const auto range = volume.valueRange();
    s.valueLo = range.first;
    s.valueHi = range.second;
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    s.vao = GlVertexArray(vao);
    checkGl("GPU ray caster setup");
}

GpuRayCaster::GpuRayCaster(const Volume& part, const VolumePart& where, GpuOptions options)
    : GpuRayCaster(part, options) {
    state_->part = where;
    state_->valueLo = where.valueRange.first;
    state_->valueHi = where.valueRange.second;
}

GpuRayCaster::~GpuRayCaster() = default;

bool GpuRayCaster::setSurface(std::shared_ptr<const SurfaceDisplay> surface) {
    if (state_->part) {
        throw std::logic_error("a part of a distributed render draws no surface");
    }
    if (surface) {
        checkSurfaceDisplay(*surface);
    }
    state_->surface = std::move(surface);
    state_->inTarget.reset(); // the kept frame shows the old one
    return true;
}

RenderResult GpuRayCaster::render(const RenderDescription& description) {
    return renderWithGpuStats(description).frame;
}

std::string GpuRayCaster::device() const {
    const auto text = [](GLenum name) {
        const GLubyte* s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

const GpuFrameStats& GpuRayCaster::lastFrame() const {
    return state_->last;
}

FrameDetails GpuRayCaster::frameDetails() const {
    const GpuFrameStats& g = state_->last;
    const auto fixed = [](double v) {
        char text[32];
        std::snprintf(text, sizeof text, "%.1f", v);
        return std::string(text);
    };
    const auto mib = [](std::size_t bytes) {
        char text[32];
        std::snprintf(text, sizeof text, "%.1f", double(bytes) / 1048576.0);
        return std::string(text);
    };
    std::string levels;
    for (std::size_t l = 0; l < g.bricksPerLevel.size(); ++l) {
        levels += (levels.empty() ? "" : ",") + std::to_string(l) + ":" +
                  std::to_string(g.bricksPerLevel[l]);
    }
    return {{"uploads", std::to_string(g.bricksUploaded)},
            {"upload_mib", mib(g.bytesUploaded)},
            {"resident", std::to_string(g.bricksResident)},
            {"pages", std::to_string(g.pagesShown)},
            {"levels", levels},
            {"pending", std::to_string(g.pending)},
            {"budget_mib", std::to_string(g.budgetBytes >> 20)},
            {"gradients", g.gradientsCached ? "cached" : "computed"},
            {"resident_mib", mib(g.residentBytes)},
            {"values_mib", mib(g.valueBytes)},
            {"gradients_mib", mib(g.gradientBytes)},
            {"page_table_kib", std::to_string((g.tableBytes + 1023) / 1024)},
            {"pool_mib", mib(g.poolBytes)},
            {"cast_ms", fixed(g.castMs)},
            {"read_ms", fixed(g.readMs)},
            {"convert_ms", fixed(g.convertMs)}};
}

GpuRenderResult GpuRayCaster::renderWithGpuStats(const RenderDescription& desc) {
    State& s = *state_;
    using Clock = std::chrono::steady_clock;
    const auto ms = [](Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration<double, std::milli>(b - a).count();
    };
    const Clock::time_point t0 = Clock::now();
    GpuRenderResult out = cast(desc, false);
    glFinish(); // the read back waits for the cast anyway; this splits the two
    const Clock::time_point t1 = Clock::now();
    RenderResult& r = out.frame;
    // A part's projections are composited from their values (and counts).
    const bool projecting =
        s.part && (desc.mode == RenderMode::Mip || desc.mode == RenderMode::MinIp ||
                   desc.mode == RenderMode::Average);
    s.target.read(r.premultiplied, r.stats.samples, projecting ? &r.projection : nullptr);
    s.inTargetStats = r.stats;
    const Clock::time_point t2 = Clock::now();
    r.image = ImageRGBA8::filled(desc.width, desc.height, 0);
    // Rows in parallel: at 1024x1024 a serial loop is a visible share of a GPU frame.
#pragma omp parallel for schedule(static)
    for (int y = 0; y < desc.height; ++y) {
        for (int x = 0; x < desc.width; ++x) {
            const glm::vec4 c = r.premultiplied[std::size_t(y) * desc.width + x];
            const glm::dvec3 rgb = glm::dvec3(c) + (1.0 - double(c.a)) * desc.background;
            std::uint8_t* px = r.image.at(x, y);
            for (int ch = 0; ch < 3; ++ch) {
                px[ch] = static_cast<std::uint8_t>(std::clamp(rgb[ch], 0.0, 1.0) * 255.0 + 0.5);
            }
            px[3] = 255;
        }
    }
    out.gpu.castMs = ms(t0, t1);
    out.gpu.readMs = ms(t1, t2);
    out.gpu.convertMs = ms(t2, Clock::now());
    s.last = out.gpu;
    return out;
}

RenderStats GpuRayCaster::drawInPlace(const RenderDescription& desc,
                                      const FramebufferTarget& target) {
    if (target.width < 1 || target.height < 1) {
        throw std::invalid_argument("drawInPlace: the target rectangle " +
                                    std::to_string(target.width) + "x" +
                                    std::to_string(target.height) + " is empty");
    }
    State& s = *state_;
    const bool newCast = !s.inTarget || !castkey::sameCast(*s.inTarget, desc);
    if (newCast) {
        s.inTargetStats = cast(desc, true).frame.stats;
    }
    for (const bool stretch : {false, true}) {
        auto& program = s.composite[stretch ? 1U : 0U];
        if (!program) {
            program = std::make_unique<ShaderProgram>("composite.vert", "composite.frag",
                                                      std::string("#define LUCENT_STRETCH ") +
                                                          (stretch ? "true" : "false") + "\n");
        }
    }
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    // Dithering would make the 8-bit target differ from the read back.
    const bool dither = glIsEnabled(GL_DITHER) == GL_TRUE;
    glDisable(GL_DITHER);
    glBindTextureUnit(0, s.target.colour());
    glBindSampler(0, 0);
    glBindSampler(1, 0);
    glBindVertexArray(s.vao.get());
    const auto pass = [&](GLuint framebuffer, int x, int y, int width, int height, bool stretch) {
        const ShaderProgram& p = *s.composite[stretch ? 1U : 0U];
        p.use();
        p.set("uFrame", 0);
        p.set("uShown", 1);
        p.set("uBackground", glm::vec3(desc.background));
        p.set("uOrigin", glm::ivec2(x, y));
        p.set("uSize", glm::ivec2(width, height));
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glViewport(x, y, width, height);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    if (target.width == s.target.width() && target.height == s.target.height()) {
        pass(target.framebuffer, target.x, target.y, target.width, target.height, false);
    } else {
        // Composited at the frame's size into 8 bits, then stretched: one
        // filtered fetch a pixel of the (larger) target.
        pass(s.target.shownFramebuffer(), 0, 0, s.target.width(), s.target.height(), false);
        glBindTextureUnit(1, s.target.shown());
        pass(target.framebuffer, target.x, target.y, target.width, target.height, true);
        glBindTextureUnit(1, 0);
    }
    // The framebuffer's owner (a QOpenGLWidget's painter) draws on after this.
    glBindVertexArray(0);
    glBindTextureUnit(0, 0);
    glUseProgram(0);
    if (dither) {
        glEnable(GL_DITHER);
    }
    checkGl("drawing the frame in place");
    if (newCast) {
        // Read after the draws are queued, so that the driver has the whole
        // frame when this waits for the cast.
        s.inTargetStats.samples = s.target.countedSamples();
    }
    return s.inTargetStats;
}

void clearFramebuffer(const FramebufferTarget& target, const glm::dvec3& colour) {
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
    glViewport(target.x, target.y, target.width, target.height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(target.x, target.y, target.width, target.height);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(float(colour.r), float(colour.g), float(colour.b), 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    checkGl("clearing the framebuffer");
}

GpuRenderResult GpuRayCaster::cast(const RenderDescription& asked, bool countRows) {
    asked.validate();
    State& s = *state_;
    // A part draws its owned box (in its own indices) over transparent black.
    const PartFrame part = partFrame(s.part, s.volume, asked);
    const RenderDescription& desc = part.local;
    if (part.empty) {
        // Nothing to cast: the target holds transparent black for the read back.
        s.target.resize(desc.width, desc.height);
        s.target.bindAndClear(countRows);
        s.inTarget.reset();
        return GpuRenderResult{};
    }
    if (desc.volume != nullptr && desc.volume != &s.volume) {
        throw std::invalid_argument("render description names another volume than this caster's");
    }
    const Volume* overlay = desc.overlay.volume;
    if (overlay != nullptr && (s.part || overlay->dims() != s.volume.dims())) {
        throw std::invalid_argument(s.part ? "a part of a distributed render draws no overlay"
                                           : "the overlay's grid is not this caster's volume's");
    }
    if (s.surface && !s.surface->showVolume) { // the surface alone: no bricks, no rays
        s.inTarget.reset();
        GpuRenderResult out;
        out.gpu.surfaceBytesUploaded = s.drawSurface(desc);
        s.target.resize(desc.width, desc.height);
        s.target.bindAndClear(countRows);
        s.surfaceRenderer->copyColourTo(s.target.colour());
        s.inTarget = desc;
        s.inTarget->volume = &s.volume;
        s.last = out.gpu;
        return out;
    }
    const SamplingSettings& sampling = desc.sampling;
    const bool cubic = sampling.interpolation == Interpolation::Cubic;
    const bool preintegrate = sampling.preintegrate && desc.mode == RenderMode::Dvr;
    const int brickSize = sampling.brickSize;
    GpuRenderResult out;
    if (!s.streamer) {
        s.streamer = std::make_unique<BrickStreamer>(s.volume, s.budget);
    }
    BrickStreamer& streamer = *s.streamer;

    // Table range: the voxels', or the coefficients' (a spline overshoots its samples).
    double tLo = s.valueLo, tHi = s.valueHi;
    if (cubic) {
        std::tie(tLo, tHi) = streamer.valueRange(true, brickSize);
    }
    std::tie(tLo, tHi) = tableRange(tLo, tHi);
    const auto visible =
        valueVisibility(desc, tLo, tHi, preintegrate ? kPreintegrationSize : kTableSize);

    // The bricks in view, each at the finest level the budget allows for it.
    const VolumeGeometry& g = s.volume.geometry();
    const ViewFrame frame =
        makeViewFrame(s.part ? s.part->whole : g, desc.camera, desc.width, desc.height);
    const bool shadedMode = desc.mode == RenderMode::Dvr || desc.mode == RenderMode::Isosurface;
    BrickRequest request;
    request.brickSize = brickSize;
    request.cubic = cubic;
    request.halfFloat = s.options.halfFloatCoefficients;
    request.shaded = shadedMode && desc.transferFunction.shading.enabled;
    request.gradientCache = s.options.gradientCache;
    request.gradientUnit = std::max(s.valueHi - s.valueLo, 1e-30) / 2.0 / 32767.0;
    request.visible = visible;
    request.decides = shadedMode;
    request.withNeighbours = preintegrate || desc.mode == RenderMode::Isosurface;
    request.clip = desc.clip;
    request.inView = [&](const glm::dvec3& lo, const glm::dvec3& hi) {
        return boxInView(g, frame, lo, hi);
    };
    request.worth = [&](const glm::dvec3& lo, const glm::dvec3& hi, double content) {
        return brickWorth(g, frame, desc.height, lo, hi) * content;
    };
    request.policy = s.options.lodPolicy;
    request.uploadCap = s.options.uploadBytesPerFrame;
    request.tight = s.options.tightBricks;
    BrickFrameStats bricks;
    const BrickTable& table = streamer.update(request, bricks);
    const BrickPool& pool = streamer.pool();
    const TexelFormat format = pool.format();
    out.gpu.bricksUploaded = bricks.bricksUploaded;
    out.gpu.bytesUploaded = bricks.bytesUploaded;
    out.gpu.gradientsCached = bricks.gradientsCached;
    out.gpu.bricksResident = pool.residentCount();
    out.gpu.valueBytes = bricks.valueBytes;
    out.gpu.gradientBytes = bricks.gradientBytes;
    out.gpu.tableBytes = bricks.tableBytes;
    out.gpu.residentBytes = bricks.valueBytes + bricks.gradientBytes;
    out.gpu.poolBytes = pool.bytes();
    out.gpu.budgetBytes = s.budget;
    out.gpu.budgetSource = s.budgetSource;
    out.gpu.bricksPerLevel = bricks.perLevel;
    out.gpu.levelOfBrick = bricks.levelOfBrick;
    out.gpu.pageSize = bricks.brickSize;
    out.gpu.pagesShown = bricks.bricksShown;
    out.gpu.pending = bricks.pending;
    out.gpu.lodReason = bricks.lodReason;

    s.scene.updateBricks(table);
    s.scene.updateTables(desc.transferFunction, tLo, tHi, sampling.step, preintegrate, kTableSize,
                         kPreintegrationSize);
    const glm::ivec3 per = table.bricksPerAxis;
    const glm::ivec3 cellsPer = table.cellsPerAxis;
    std::vector<glm::ivec3> levelDims = streamer.levelDims();
    levelDims.resize(8, levelDims.back());

    // Uniforms: the CPU ray caster's setup; each brick's level is in its page entry.
    const glm::dmat3 linear(g.direction[0] * g.spacing.x, g.direction[1] * g.spacing.y,
                            g.direction[2] * g.spacing.z);
    const double dt = sampling.step * std::min({g.spacing.x, g.spacing.y, g.spacing.z});
    const glm::dvec3 boxLo = part.boxLo, boxHi = part.boxHi;
    const double tableCell = (tHi - tLo) / double(kTableSize - 1);
    const auto [visLo, visHi] = visibleValueRange(desc.transferFunction, tableCell);
    const auto flag = [](bool b) { return b ? "true" : "false"; };
    const std::string defines =
        "#define LUCENT_MODE " + std::to_string(shaderMode(desc.mode)) +
        "\n#define LUCENT_INTERP " +
        std::to_string(sampling.interpolation == Interpolation::Nearest ? 0
                       : cubic                                          ? 2
                                                                        : 1) +
        "\n#define LUCENT_PRECLASSIFY " + flag(sampling.classification == Classification::Pre) +
        "\n#define LUCENT_PREINTEGRATE " + flag(preintegrate) + "\n#define LUCENT_SHADING " +
        flag(desc.transferFunction.shading.enabled) + "\n#define LUCENT_LEAP " +
        flag(sampling.emptySpaceLeaping && (overlay == nullptr || desc.mode == RenderMode::Dvr)) +
        "\n#define LUCENT_CELLS_IN_ONE_BRICK " + flag(table.brickSize % kCellSize == 0) +
        "\n#define LUCENT_GRADIENT_TEXTURE " + flag(pool.hasGradients()) +
        "\n#define LUCENT_GRADIENT_IN_POOL " + flag(pool.gradientsShareTexture()) +
        "\n#define LUCENT_SPECULAR_INT " +
        std::to_string(integerPower(desc.transferFunction.shading)) +
        "\n#define LUCENT_ROW_SAMPLES " + flag(countRows) + "\n#define LUCENT_SURFACE " +
        flag(s.surface != nullptr) + "\n#define LUCENT_OVERLAY " + flag(overlay != nullptr) + "\n" +
        s.leaping.update(desc, s.volume, table, kCellSize, {visLo, visHi, tableCell, tLo, tHi});
    auto& program = s.programs[defines];
    if (!program) {
        program = std::make_unique<ShaderProgram>("raycast.vert", "raycast.frag", defines);
    }
    if (s.surface) { // its own program and framebuffer: before the rays' are set
        out.gpu.surfaceBytesUploaded = s.drawSurface(desc);
    }
    if (overlay != nullptr) {
        out.gpu.bytesUploaded += s.overlay.update(desc.overlay, sampling.step);
        s.overlay.updateLeaping(desc.overlay, kCellSize, cellsPer, table.brickSize, per);
    }
    const ShaderProgram& p = *program;
    p.use();
    p.set("uEye", g.toIndex(frame.eye));
    p.set("uForward", frame.forward);
    p.set("uRight", frame.right);
    p.set("uUp", frame.up);
    p.set("uToIndex", glm::inverse(linear));
    p.set("uTanHalfFov", frame.tanHalfFov);
    p.set("uAspect", frame.aspect);
    p.set("uImageSize", glm::ivec2(desc.width, desc.height));
    p.set("uDt", dt);
    p.set("uBoxLo", boxLo);
    p.set("uBoxHi", boxHi);
    p.set("uClipLo", glm::max(desc.clip.lo, boxLo));
    p.set("uClipHi", glm::min(desc.clip.hi, boxHi));
    p.set("uPart", s.part ? 1 : 0);
    p.set("uOpenHi", part.openHi);
    p.set("uSceneClipLo", part.sceneClipLo);
    p.set("uSceneClipHi", part.sceneClipHi);
    const Shading& light = desc.transferFunction.shading;
    p.set("uEarlyTermination", float(sampling.earlyTermination));
    p.set("uIso", float(desc.isoValue));
    p.set("uLight", glm::vec4(light.ambient, light.diffuse, light.specular, light.specularPower));
    p.set("uGradientToWorld",
          glm::mat3(glm::transpose(glm::inverse(linear)) / gradientScale(s.valueLo, s.valueHi)));
    p.set("uVisibleLo", float(std::max(visLo, -3.0e38)));
    p.set("uVisibleHi", float(std::min(visHi, 3.0e38)));
    p.set("uStepRatio", float(sampling.step));
    glUniform3iv(p.location("uLevelDims[0]"), 8, &levelDims[0].x);
    p.set("uBrickSize", table.brickSize);
    p.set("uInvBrickSize", 1.0f / float(table.brickSize));
    p.set("uBricksPerAxis", per);
    p.set("uInvPoolSize", 1.0f / glm::vec3(pool.extent()));
    p.set("uValueScale", format.valueScale);
    p.set("uGradientScale", float(request.gradientUnit * 32767.0));
    p.set("uTableSize", kTableSize);
    p.set("uTableLo", float(tLo));
    p.set("uTableScale", float(double(kTableSize - 1) / (tHi - tLo)));
    p.set("uPreSize", kPreintegrationSize);
    p.set("uPreLo", float(tLo));
    p.set("uPreHi", float(tHi));
    p.set("uCellSize", kCellSize);
    p.set("uInvCellSize", 1.0f / float(kCellSize));
    p.set("uCellsPerAxis", cellsPer);
    if (overlay != nullptr) {
        s.overlay.setUniforms(p, desc.overlay);
    }
    // Texture units, in the order of the samplers' names.
    const std::pair<const char*, GLuint> units[] = {
        {"uPageTable", s.scene.pageTable()},
        {"uPageBox", s.scene.pageBox()},
        {"uCellCode", s.scene.cellCode()},
        {"uCellRange", s.scene.cellRange()},
        {"uPool", pool.texture()},
        {"uTable", s.scene.table()},
        {"uPreTable", preintegrate ? s.scene.preintegrationTable() : s.scene.table()},
        {"uGradientPool", pool.hasGradients() ? pool.gradientTexture() : pool.texture()},
        {"uSurfaceColour", s.surface ? s.surfaceRenderer->colour() : 0},
        {"uSurfaceDistance", s.surface ? s.surfaceRenderer->distance() : 0},
        {"uOverlay", overlay != nullptr ? s.overlay.volume() : 0},
        {"uOverlayTable", overlay != nullptr ? s.overlay.table() : 0},
        {"uOverlayEmptyCells", overlay != nullptr ? s.overlay.emptyCells() : 0},
        {"uOverlayEmptyBricks", overlay != nullptr ? s.overlay.emptyBricks() : 0},
    };
    for (int u = 0; u < int(std::size(units)); ++u) {
        glBindTextureUnit(GLuint(u), units[u].second);
        p.set(units[u].first, u);
    }
    s.leaping.bind(p, GLuint(std::size(units)));

    s.target.resize(desc.width, desc.height);
    // From here the target holds no frame until this one is cast.
    s.inTarget.reset();
    s.target.bindAndClear(countRows);
    glBindVertexArray(s.vao.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    checkGl("ray casting");
    RenderStats& stats = out.frame.stats;
    stats.bricksTotal = bricks.bricksTotal;
    stats.bricksUsed = bricks.bricksUsed;
    stats.lod = bricks.coarsestLevel;
    stats.lodReason = out.gpu.lodReason;
    stats.bricksPending = out.gpu.pending;
    s.inTarget = desc;
    s.inTarget->volume = &s.volume;
    s.last = out.gpu;
    return out;
}

} // namespace lucent
