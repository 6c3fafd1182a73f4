#pragma once
// What a movie shows, frame by frame: a turntable of the volume rendering, or a
// cine through the slices along one of the volume's index axes, windowed like
// the MPR views. writeMovie() renders them into a MovieWriter with progress
// and cancel, for lucent-cli movie and File > Export movie alike.

#include <functional>
#include <string_view>

#include "core/image/Image.h"
#include "core/mpr/PlaneSampler.h"
#include "core/scene/RenderDescription.h"

namespace lucent {

class MovieWriter;
class Renderer;

class MovieFrames {
public:
    virtual ~MovieFrames() = default;
    virtual int count() const = 0;
    // Frame k (0 <= k < count()), of the movie's size.
    virtual ImageRGBA8 frame(int k) = 0;
};

// Frame k of n: the start with turntableCamera (core/scene/Turntable.h), its azimuth
// turned by k * degrees / n: a full turn loops without a repeat.
RenderDescription turntableFrame(const RenderDescription& start, double degrees, int frames, int k);

class TurntableFrames : public MovieFrames {
public:
    // `renderer` must be the start's volume's and outlive this.
    TurntableFrames(Renderer& renderer, const RenderDescription& start, double degrees, int frames);
    int count() const override { return frames_; }
    ImageRGBA8 frame(int k) override;

private:
    Renderer& renderer_;
    RenderDescription start_;
    double degrees_;
    int frames_;
};

enum class IndexAxis { I, J, K };
// "i", "j" or "k". Throws std::invalid_argument naming the text.
IndexAxis parseIndexAxis(std::string_view text);

// The number of slices along `axis` (the volume's size along it).
int sliceCount(const VolumeGeometry& geometry, IndexAxis axis);
// The slice index frame k of `frames` shows: the slices spread evenly from the
// first to the last; frames 0 means every slice.
int cineSlice(int slices, int frames, int k);
// The plane through slice `slice` along `axis`, spanned by the other two index
// axes (so it samples that slice's voxels exactly), each signed and ordered to
// match the radiological view it is nearest to (axial, coronal or sagittal),
// the whole slice fitted into width x height pixels.
SlicePlane cinePlane(const VolumeGeometry& geometry, IndexAxis axis, int slice, int width,
                     int height);
// The plane's samples through the window as opaque grey (outside the volume black).
ImageRGBA8 windowedSlice(const Volume& volume, const SlicePlane& plane, const WindowLevel& window);

class CineFrames : public MovieFrames {
public:
    // frames 0, or more than there are slices: every slice. `volume` must outlive this.
    CineFrames(const Volume& volume, IndexAxis axis, int frames, const WindowLevel& window,
               int width, int height);
    int count() const override { return frames_; }
    ImageRGBA8 frame(int k) override;

private:
    const Volume& volume_;
    IndexAxis axis_;
    int slices_;
    int frames_;
    WindowLevel window_;
    int width_, height_;
};

// Renders every frame into `writer` and finishes it, calling progress(done,
// total) before the first frame and after each; progress returning false
// cancels. Returns false when cancelled: the writer is left unfinished, and
// destroying it removes the temporary file.
bool writeMovie(MovieFrames& frames, MovieWriter& writer,
                const std::function<bool(int done, int total)>& progress = {});

} // namespace lucent
