#include "server/SliceFrames.h"

#include <QElapsedTimer>

#include "core/mpr/CrosshairSlice.h"
#include "protocol/FrameMessage.h"
#include "protocol/PngEncoder.h"

namespace lucent::remote {

RenderedSlices renderSliceFrames(const Volume& volume, const SliceJob& job) {
    RenderedSlices result;
    result.view = job.view;
    result.seq = job.seq;
    result.generation = job.generation;
    if (job.window) {
        result.window = *job.window;
    } else {
        const WindowLevel level = defaultWindow(volume);
        result.window = {level.center, level.width};
    }
    const VolumeGeometry& geometry = volume.geometry();
    for (const Orientation view : job.views) {
        QElapsedTimer timer;
        timer.start();
        // The workstation's plane at zoom 1 without pan or turn: the same pixels.
        const SlicePlane plane =
            crosshairPlane(geometry, view, job.crosshair, job.size.x, job.size.y);
        const std::vector<std::uint8_t> grey =
            windowedGrey(sampleImage(volume, plane), result.window.center, result.window.width);
        FrameHeader header;
        header.renderMs = double(timer.nsecsElapsed()) / 1e6;
        timer.restart();
        const std::string png = encodeGreyPng(grey, plane.width, plane.height);
        header.encodeMs = double(timer.nsecsElapsed()) / 1e6;
        header.width = plane.width;
        header.height = plane.height;
        header.format = "png";
        header.seq = job.seq;
        header.quality = Quality::Still;
        header.slice = SliceFrameInfo{
            view,    job.crosshair, result.window,   plane.centre,
            plane.u, plane.v,       plane.pixelSize, sliceStep(geometry, plane.normal())};
        const std::string message = frameMessage(header, png);
        result.frames.emplace_back(view, QByteArray(message.data(), qsizetype(message.size())));
    }
    return result;
}

} // namespace lucent::remote
