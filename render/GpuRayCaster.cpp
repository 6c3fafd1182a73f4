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
#include <string>
#include <tuple>

#include "core/raycast/BrickVisibility.h"
#include "core/scene/ViewFrame.h"
#include "render/BrickStreamer.h"
#include "render/BrickTable.h"
#include "render/CastKey_p.h"
#include "render/GlError.h"
#include "render/GlObjects_p.h"
#include "render/GpuBudget.h"
#include "render/LeapTextures.h"
#include "render/OverlayTextures.h"
#include "render/PartFrame_p.h"
#include "render/RayCastSetup_p.h"
#include "render/RenderTarget.h"
#include "render/SceneTextures.h"
#include "render/SurfaceRenderer.h"

namespace lucent {

namespace {

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

    // The classification tables' range: the voxels', or the coefficients'
    // (a spline overshoots its samples).
    std::pair<double, double> tableRangeFor(const RenderDescription& d) {
        if (d.sampling.interpolation != Interpolation::Cubic) {
            return tableRange(valueLo, valueHi);
        }
        const auto [lo, hi] = streamer->valueRange(true, d.sampling.brickSize);
        return tableRange(lo, hi);
    }

    double gradientUnit() const { return std::max(valueHi - valueLo, 1e-30) / 2.0 / 32767.0; }

    const BrickTable& updateBricks(const RenderDescription& d, const ViewFrame& view, double tLo,
                                   double tHi, GpuRenderResult& out);
    const ShaderProgram& program(const std::string& defines) {
        auto& p = programs[defines];
        if (!p) {
            p = std::make_unique<ShaderProgram>("raycast.vert", "raycast.frag", defines);
        }
        return *p;
    }
    void bindTextures(const ShaderProgram& p, bool preintegrate, bool withOverlay);
    GpuRenderResult castSurfaceAlone(const RenderDescription& d, bool countRows);

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
            {"convert_ms", fixed(g.convertMs)},
            {"prepare_ms", fixed(g.prepareMs)},
            {"bricks_planned", g.bricksPlanned ? "yes" : "no"}};
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

const BrickTable& GpuRayCaster::State::updateBricks(const RenderDescription& d,
                                                    const ViewFrame& view, double tLo, double tHi,
                                                    GpuRenderResult& out) {
    const SamplingSettings& sampling = d.sampling;
    const bool preintegrate = sampling.preintegrate && d.mode == RenderMode::Dvr;
    const bool shadedMode = d.mode == RenderMode::Dvr || d.mode == RenderMode::Isosurface;
    const VolumeGeometry& g = volume.geometry();
    BrickRequest request;
    request.brickSize = sampling.brickSize;
    request.cubic = sampling.interpolation == Interpolation::Cubic;
    request.halfFloat = options.halfFloatCoefficients;
    request.shaded = shadedMode && d.transferFunction.shading.enabled;
    request.gradientCache = options.gradientCache;
    request.gradientCacheBytes =
        std::size_t(std::max(options.gradientCacheShare, 0.0) * double(volume.byteCount()));
    request.gradientUnit = gradientUnit();
    request.visibilityKey =
        visibilityKey(d, tLo, tHi, preintegrate ? kRayPreintegrationSize : kRayTableSize);
    request.visible = valueVisibility(request.visibilityKey);
    request.decides = shadedMode;
    request.withNeighbours = preintegrate || d.mode == RenderMode::Isosurface;
    request.clip = d.clip;
    request.inView = [&](const glm::dvec3& lo, const glm::dvec3& hi) {
        return boxInView(g, view, lo, hi);
    };
    request.worth = [&](const glm::dvec3& lo, const glm::dvec3& hi, double content) {
        return brickWorth(g, view, d.height, lo, hi) * content;
    };
    request.policy = options.lodPolicy;
    request.uploadCap = options.uploadBytesPerFrame;
    request.tight = options.tightBricks;
    BrickFrameStats bricks;
    const BrickTable& table = streamer->update(request, bricks);
    const BrickPool& pool = streamer->pool();
    GpuFrameStats& gpu = out.gpu;
    gpu.bricksUploaded = bricks.bricksUploaded;
    gpu.bytesUploaded = bricks.bytesUploaded;
    gpu.gradientsCached = bricks.gradientsCached;
    gpu.bricksResident = pool.residentCount();
    gpu.valueBytes = bricks.valueBytes;
    gpu.gradientBytes = bricks.gradientBytes;
    gpu.tableBytes = bricks.tableBytes;
    gpu.residentBytes = bricks.valueBytes + bricks.gradientBytes;
    gpu.poolBytes = pool.bytes();
    gpu.budgetBytes = budget;
    gpu.budgetSource = budgetSource;
    gpu.bricksPerLevel = bricks.perLevel;
    gpu.levelOfBrick = bricks.levelOfBrick;
    gpu.pageSize = bricks.brickSize;
    gpu.pagesShown = bricks.bricksShown;
    gpu.pending = bricks.pending;
    gpu.lodReason = bricks.lodReason;
    gpu.levelsClassified = bricks.levelsClassified;
    gpu.bricksPlanned = bricks.planned;
    RenderStats& stats = out.frame.stats;
    stats.bricksTotal = bricks.bricksTotal;
    stats.bricksUsed = bricks.bricksUsed;
    stats.lod = bricks.coarsestLevel;
    stats.lodReason = bricks.lodReason;
    stats.bricksPending = bricks.pending;
    return table;
}

void GpuRayCaster::State::bindTextures(const ShaderProgram& p, bool preintegrate,
                                       bool withOverlay) {
    const BrickPool& pool = streamer->pool();
    // Texture units, in the order of the samplers' names.
    const std::pair<const char*, GLuint> units[] = {
        {"uPageEntry", scene.pageEntry()},
        {"uCellCode", scene.cellCode()},
        {"uCellRange", scene.cellRange()},
        {"uPool", pool.texture()},
        {"uTable", scene.table()},
        {"uPreTable", preintegrate ? scene.preintegrationTable() : scene.table()},
        {"uGradientPool", pool.hasGradients() ? pool.gradientTexture() : pool.texture()},
        {"uSurfaceColour", surface ? surfaceRenderer->colour() : 0},
        {"uSurfaceDistance", surface ? surfaceRenderer->distance() : 0},
        {"uOverlay", withOverlay ? overlay.volume() : 0},
        {"uOverlayTable", withOverlay ? overlay.table() : 0},
        {"uOverlayEmptyCells", withOverlay ? overlay.emptyCells() : 0},
        {"uOverlayEmptyBricks", withOverlay ? overlay.emptyBricks() : 0},
    };
    for (int u = 0; u < int(std::size(units)); ++u) {
        glBindTextureUnit(GLuint(u), units[u].second);
        p.set(units[u].first, u);
    }
    leaping.bind(p, GLuint(std::size(units))); // the distance maps take the next units
}

GpuRenderResult GpuRayCaster::State::castSurfaceAlone(const RenderDescription& d, bool countRows) {
    // The surface alone: no bricks, no rays.
    inTarget.reset();
    GpuRenderResult out;
    out.gpu.surfaceBytesUploaded = drawSurface(d);
    target.resize(d.width, d.height);
    target.bindAndClear(countRows);
    surfaceRenderer->copyColourTo(target.colour());
    inTarget = d;
    inTarget->volume = &volume;
    last = out.gpu;
    return out;
}

GpuRenderResult GpuRayCaster::cast(const RenderDescription& asked, bool countRows) {
    const auto started = std::chrono::steady_clock::now();
    asked.validate();
    if (asked.sampling.brickSize > kMaxPageBrickSize) {
        throw std::invalid_argument("brick: the GPU ray caster takes bricks of at most " +
                                    std::to_string(kMaxPageBrickSize) + " voxels, not " +
                                    std::to_string(asked.sampling.brickSize));
    }
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
    if (s.surface && !s.surface->showVolume) {
        return s.castSurfaceAlone(desc, countRows);
    }
    const SamplingSettings& sampling = desc.sampling;
    const bool preintegrate = sampling.preintegrate && desc.mode == RenderMode::Dvr;
    if (!s.streamer) {
        s.streamer = std::make_unique<BrickStreamer>(s.volume, s.budget);
    }
    GpuRenderResult out;
    const auto [tLo, tHi] = s.tableRangeFor(desc);
    // The bricks in view, each at the finest level the budget allows for it.
    const VolumeGeometry& g = s.volume.geometry();
    const ViewFrame view =
        makeViewFrame(s.part ? s.part->whole : g, desc.camera, desc.width, desc.height);
    const BrickTable& table = s.updateBricks(desc, view, tLo, tHi, out);
    out.gpu.tableUploaded = s.scene.updateBricks(table, s.streamer->tableGeneration());
    s.scene.updateTables(desc.transferFunction, tLo, tHi, sampling.step, preintegrate,
                         kRayTableSize, kRayPreintegrationSize);
    const double tableCell = (tHi - tLo) / double(kRayTableSize - 1);
    const auto [visLo, visHi] = visibleValueRange(desc.transferFunction, tableCell);
    const RayCastFrame frame{desc,
                             g,
                             view,
                             part,
                             s.part.has_value(),
                             table,
                             s.streamer->pool(),
                             s.streamer->levelDims(),
                             tLo,
                             tHi,
                             visLo,
                             visHi,
                             s.valueLo,
                             s.valueHi,
                             s.gradientUnit(),
                             preintegrate,
                             countRows,
                             s.surface != nullptr,
                             overlay != nullptr};
    const ShaderProgram& p =
        s.program(rayCastDefines(frame) +
                  s.leaping.update(desc, s.volume, table, s.streamer->tableGeneration(),
                                   kRayCellSize, {visLo, visHi, tableCell, tLo, tHi}));
    out.gpu.tableBytes += s.leaping.bytes(); // the distance maps
    if (s.surface) { // its own program and framebuffer: before the rays' are set
        out.gpu.surfaceBytesUploaded = s.drawSurface(desc);
    }
    if (overlay != nullptr) {
        out.gpu.bytesUploaded += s.overlay.update(desc.overlay, sampling.step);
        s.overlay.updateLeaping(desc.overlay, kRayCellSize, table.cellsPerAxis, table.brickSize,
                                table.bricksPerAxis);
    }
    p.use();
    setRayCastUniforms(p, frame);
    if (overlay != nullptr) {
        s.overlay.setUniforms(p, desc.overlay);
    }
    s.bindTextures(p, preintegrate, overlay != nullptr);
    s.target.resize(desc.width, desc.height);
    // From here the target holds no frame until this one is cast.
    s.inTarget.reset();
    s.target.bindAndClear(countRows);
    glBindVertexArray(s.vao.get());
    out.gpu.prepareMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started)
            .count();
    // Rays only where they can meet the box: on llvmpipe each pixel's ray
    // set-up (in double) costs about a sample's time.
    const PixelRect rays = rayPixels(frame);
    if (rays.x0 <= rays.x1 && rays.y0 <= rays.y1) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(rays.x0, desc.height - 1 - rays.y1, rays.x1 - rays.x0 + 1, rays.y1 - rays.y0 + 1);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDisable(GL_SCISSOR_TEST);
    }
    checkGl("ray casting");
    s.inTarget = desc;
    s.inTarget->volume = &s.volume;
    s.last = out.gpu;
    return out;
}

} // namespace lucent
