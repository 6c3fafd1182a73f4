# Reads a mesh file with VTK's own readers (Debian's python3-vtk9: what 3D
# Slicer and ParaView use) and prints: points, polygons, point arrays, the
# range of the svr array. Run by test_mesh_files.
import sys, vtk
path = sys.argv[1]
ext = path.rsplit('.', 1)[1].lower()
r = {'vtk': vtk.vtkPolyDataReader, 'stl': vtk.vtkSTLReader, 'ply': vtk.vtkPLYReader, 'obj': vtk.vtkOBJReader}[ext]()
r.SetFileName(path)
r.Update()
pd = r.GetOutput()
arrays = [pd.GetPointData().GetArrayName(i) for i in range(pd.GetPointData().GetNumberOfArrays())]
svr = pd.GetPointData().GetArray('svr')
print(pd.GetNumberOfPoints(), pd.GetNumberOfPolys(), ','.join(a or '' for a in arrays), svr.GetRange() if svr else '')
