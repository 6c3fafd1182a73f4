# VTK 9's isosurfaces of a MetaImage, for bench_surface: vtkFlyingEdges3D and
# vtkMarchingCubes at the same iso value, on the volume padded by one voxel of
# its lowest value (as 3D Slicer pads label maps) so that, like Lucent's,
# surfaces cut by the field of view are closed and the counts compare.
# Prints: threads fe_ms fe_triangles mc_ms mc_triangles (best of `repeat`).
import sys
import time

import vtk

path, iso, repeat = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
reader = vtk.vtkMetaImageReader()
reader.SetFileName(path)
reader.Update()
image = reader.GetOutput()
lo = image.GetScalarRange()[0]
extent = list(image.GetExtent())
pad = vtk.vtkImageConstantPad()
pad.SetInputData(image)
pad.SetOutputWholeExtent(extent[0] - 1, extent[1] + 1, extent[2] - 1, extent[3] + 1,
                         extent[4] - 1, extent[5] + 1)
pad.SetConstant(lo)
pad.Update()
padded = pad.GetOutput()


def best(make):
    times, triangles = [], 0
    for _ in range(repeat):
        f = make()
        f.SetInputData(padded)
        f.SetValue(0, iso)
        f.ComputeNormalsOff()
        f.ComputeGradientsOff()
        f.ComputeScalarsOff()
        start = time.perf_counter()
        f.Update()
        times.append((time.perf_counter() - start) * 1000.0)
        triangles = f.GetOutput().GetNumberOfPolys()
    return min(times), triangles


fe_ms, fe_tri = best(vtk.vtkFlyingEdges3D)
mc_ms, mc_tri = best(vtk.vtkMarchingCubes)
threads = vtk.vtkSMPTools.GetEstimatedNumberOfThreads()
print(threads, f"{fe_ms:.1f}", fe_tri, f"{mc_ms:.1f}", mc_tri)
