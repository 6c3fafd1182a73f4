#!/usr/bin/python3
"""The VTK anchor of the render benchmarks, measured with VTK 9.1's
vtkFixedPointVolumeRayCastMapper (--mapper fixed, the default: the CPU caster's
anchor) or vtkGPUVolumeRayCastMapper (--mapper gpu: the GL caster's) on the
same scene as the benchmarks (app/bench/BenchScenes.h):
a volume (as converted by lucent-cli convert), 512x512 unless --size, a preset
(the JSON of writeTransferFunction: "opacity", "colour", "shading"), shading
on, trilinear, step 0.5 voxel of the smallest spacing, Lucent's anterior
camera (30 degree view angle, zoom 1 fits the bounding sphere).
The opacity unit distance is one voxel of the smallest spacing, as in Lucent.

Needs Debian's python3-vtk9 (a measuring tool, not a project dependency) and
a display (run under xvfb-run; the GPU mapper then runs on Mesa's llvmpipe, as
Lucent's GL caster does through EGL). lucent-cli bench interactive and the
benchmarks in tests/perf carry this file in their binary and run it themselves
(app/bench/VtkAnchor.cpp), printing both side by side. By hand:
  build/bin/lucent-cli convert ../shared/data/dcm_qa_ct/Philips_S21570/S2020 /tmp/philips.mhd
  xvfb-run -a -s "-screen 0 1280x1024x24" /usr/bin/python3 app/bench/vtk_anchor.py \
      [--mapper fixed|gpu] [--size WxH] /tmp/philips.mhd resources/presets/ct-bone.json \
      OUT.png [UNIT_MM]
Prints the median time of 6 frames turning 5 degrees (each frame waits for the
GL to finish). Without UNIT_MM the
scene is bench_cpu_render's first (opacity per voxel): compare OUT.png with
build/bench_cpu_render_reference.png; with UNIT_MM 1 (VTK's default, the
issue's anchor) compare with build/bench_cpu_render_reference_per_mm.png,
using build/bin/lucent-cli compare.
"""
import argparse
import json
import math
import statistics
import time

import vtk

parser = argparse.ArgumentParser(description="VTK's volume mappers on Lucent's benchmark scene")
parser.add_argument("--mapper", choices=["fixed", "gpu"], default="fixed")
parser.add_argument("--size", default="512x512", help="image size, WxH")
parser.add_argument("volume")
parser.add_argument("preset")
parser.add_argument("out")
# The opacity unit distance in mm (default: Lucent's, the smallest spacing).
parser.add_argument("unit_mm", nargs="?", type=float)
arguments = parser.parse_args()
volume_path, preset_path, out_path = arguments.volume, arguments.preset, arguments.out
unit_distance = arguments.unit_mm
width, height = (int(n) for n in arguments.size.split("x"))
reader = vtk.vtkMetaImageReader()
reader.SetFileName(volume_path)
reader.Update()
image = reader.GetOutput()
dims = image.GetDimensions()
spacing = image.GetSpacing()
origin = image.GetOrigin()

preset = json.load(open(preset_path))
opacity = vtk.vtkPiecewiseFunction()
for value, a in preset["opacity"]:
    opacity.AddPoint(value, a)
colour = vtk.vtkColorTransferFunction()
for value, r, g, b in preset["colour"]:
    colour.AddRGBPoint(value, r, g, b)
shading = preset.get("shading", {})

prop = vtk.vtkVolumeProperty()
prop.SetScalarOpacity(opacity)
prop.SetColor(colour)
prop.SetInterpolationTypeToLinear()
prop.SetScalarOpacityUnitDistance(unit_distance or min(spacing))
if shading.get("enabled", True):
    prop.ShadeOn()
    prop.SetAmbient(shading.get("ambient", 0.1))
    prop.SetDiffuse(shading.get("diffuse", 0.9))
    prop.SetSpecular(shading.get("specular", 0.2))
    prop.SetSpecularPower(shading.get("specular_power", 10))

if arguments.mapper == "gpu":
    mapper = vtk.vtkGPUVolumeRayCastMapper()
    mapper.SetInputData(image)
    mapper.SetAutoAdjustSampleDistances(0)
    mapper.SetSampleDistance(0.5 * min(spacing))
    mapper.SetImageSampleDistance(1.0)
    label = "vtk_gpu"
    threads = "llvmpipe"
else:
    mapper = vtk.vtkFixedPointVolumeRayCastMapper()
    mapper.SetInputData(image)
    mapper.SetAutoAdjustSampleDistances(0)
    mapper.SetSampleDistance(0.5 * min(spacing))
    mapper.SetInteractiveSampleDistance(0.5 * min(spacing))
    mapper.SetImageSampleDistance(1.0)
    mapper.SetNumberOfThreads(2)
    label = "vtk_fixed_point"
    threads = "2 threads"

actor = vtk.vtkVolume()
actor.SetMapper(mapper)
actor.SetProperty(prop)
renderer = vtk.vtkRenderer()
renderer.AddVolume(actor)
renderer.SetBackground(0, 0, 0)
window = vtk.vtkRenderWindow()
window.SetOffScreenRendering(1)
window.AddRenderer(renderer)
window.SetSize(width, height)

# Lucent's ViewFrame: eye in front (anterior, -y), looking +y, head (+z) up.
centre = [origin[i] + spacing[i] * (dims[i] - 1) / 2 for i in range(3)]
radius = math.sqrt(sum((spacing[i] * (dims[i] - 1) / 2) ** 2 for i in range(3)))
distance = radius / math.sin(math.radians(15.0))
camera = renderer.GetActiveCamera()
camera.SetFocalPoint(*centre)
camera.SetPosition(centre[0], centre[1] - distance, centre[2])
camera.SetViewUp(0, 0, 1)
camera.SetViewAngle(30.0)
renderer.ResetCameraClippingRange()


def render():
    window.Render()
    if hasattr(window, "WaitForCompletion"):
        window.WaitForCompletion()  # glFinish: the GPU mapper's frame is done, not queued


render()  # first frame: setup, as Lucent's first_ms
grab = vtk.vtkWindowToImageFilter()
grab.SetInput(window)
grab.SetInputBufferTypeToRGB()
grab.ReadFrontBufferOff()
grab.Update()
writer = vtk.vtkPNGWriter()
writer.SetFileName(out_path)
writer.SetInputConnection(grab.GetOutputPort())
writer.Write()

times = []
for frame in range(6):
    camera.Azimuth(5.0)
    renderer.ResetCameraClippingRange()
    t0 = time.perf_counter()
    render()
    times.append((time.perf_counter() - t0) * 1000.0)
renderer_lines = [l for l in window.ReportCapabilities().splitlines() if "renderer string" in l]
gl = renderer_lines[0].split(":", 1)[1].strip() if renderer_lines else "unknown"
print("%s: render_ms=%.1f (median of 6, %dx%d, %s) gl_renderer=%s"
      % (label, statistics.median(times), width, height, threads, gl))
