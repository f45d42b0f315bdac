"""A triangle surface split into pieces for MPI runs: a partitioned .pvtp (one .vtp per piece)
with global point and cell ids, which SVG Geodesic Distance works on in place under
`mpiexec -n P pvbatch --symmetric` or a P-process pvserver (Docs/FILTERS.md, "Under MPI").
Debian 12's ParaView cannot run Redistribute DataSet (its expat rejects the raw binary the filter
sends between processes); this writes the pieces directly.

    pvpython Tools/pieces.py mesh.ply output_folder P      # writes output_folder/mesh.pvtp

The faces are dealt into P slabs of equal counts along x + 0.3 y of their centroids (not
contiguous in id order); each piece keeps the points its faces use (shared points repeated),
their global ids being the input's point and cell numbers. Written as inline base64 (ParaView
5.11's default raw appended binary cannot be read back by Debian's expat).
"""
import os
import sys


def read_surface(mesh_file):
    """The triangles of a .ply or .vtp file as a vtkPolyData."""
    import vtk
    reader = vtk.vtkPLYReader() if mesh_file.lower().endswith(".ply") else vtk.vtkXMLPolyDataReader()
    reader.SetFileName(mesh_file)
    reader.Update()
    return reader.GetOutput()


def slabs(surface, parts):
    """The piece of each face: `parts` slabs of equal counts along x + 0.3 y of the centroids."""
    import numpy
    from vtk.util.numpy_support import vtk_to_numpy
    points = vtk_to_numpy(surface.GetPoints().GetData()).astype(float)
    cells = vtk_to_numpy(surface.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    centres = points[cells].mean(axis=1)
    order = numpy.argsort(centres[:, 0] + 0.3 * centres[:, 1], kind="stable")
    part = numpy.empty(len(cells), dtype=int)
    part[order] = numpy.arange(len(cells)) * parts // len(cells)
    return part


def write_pieces(surface, part, folder, ids=True):
    """One .vtp per piece (faces whose `part` is its number) and their .pvtp in `folder`; global
    point and cell ids (the surface's numbers) when `ids`. Returns the .pvtp's path and each
    piece's face count."""
    import numpy
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    points = vtk_to_numpy(surface.GetPoints().GetData()).astype(float)
    cells = vtk_to_numpy(surface.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    os.makedirs(folder, exist_ok=True)
    names, sizes = [], []
    for p in range(int(max(part)) + 1):
        mine = numpy.nonzero(part == p)[0]
        used = numpy.unique(cells[mine])
        remap = numpy.full(len(points), -1, dtype=numpy.int64)
        remap[used] = numpy.arange(len(used))
        piece = vtk.vtkPolyData()
        piece_points = vtk.vtkPoints()
        piece_points.SetData(numpy_to_vtk(points[used], deep=True))
        piece.SetPoints(piece_points)
        polys = vtk.vtkCellArray()
        polys.SetData(numpy_to_vtk(numpy.arange(0, 3 * len(mine) + 1, 3, dtype=numpy.int64),
                                   deep=True, array_type=vtk.VTK_ID_TYPE),
                      numpy_to_vtk(remap[cells[mine]].ravel(), deep=True,
                                   array_type=vtk.VTK_ID_TYPE))
        piece.SetPolys(polys)
        if ids:
            for attributes, values, name in ((piece.GetPointData(), used, "GlobalPointIds"),
                                             (piece.GetCellData(), mine, "GlobalCellIds")):
                array = numpy_to_vtk(values.astype(numpy.int64), deep=True,
                                     array_type=vtk.VTK_ID_TYPE)
                array.SetName(name)
                attributes.SetGlobalIds(array)
        name = "piece_%d.vtp" % p
        writer = vtk.vtkXMLPolyDataWriter()
        writer.SetDataModeToBinary()
        writer.SetFileName(os.path.join(folder, name))
        writer.SetInputData(piece)
        writer.Write()
        names.append(name)
        sizes.append(len(mine))
    pvtp = os.path.join(folder, "mesh.pvtp")
    with open(pvtp, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="PPolyData" version="1.0" '
                'byte_order="LittleEndian" header_type="UInt64">\n<PPolyData GhostLevel="0">\n')
        if ids:
            f.write('<PPointData GlobalIds="GlobalPointIds"><PDataArray type="Int64" '
                    'Name="GlobalPointIds"/></PPointData>\n<PCellData GlobalIds="GlobalCellIds">'
                    '<PDataArray type="Int64" Name="GlobalCellIds"/></PCellData>\n')
        f.write('<PPoints><PDataArray type="Float64" NumberOfComponents="3"/></PPoints>\n')
        for n in names:
            f.write('<Piece Source="%s"/>\n' % n)
        f.write('</PPolyData>\n</VTKFile>\n')
    return pvtp, sizes


def split(mesh_file, parts, folder, ids=True):
    """`mesh_file` in `parts` slabs written to `folder`: the .pvtp, each piece's face count and
    the surface's face count."""
    surface = read_surface(mesh_file)
    pvtp, sizes = write_pieces(surface, slabs(surface, parts), folder, ids)
    return pvtp, sizes, surface.GetNumberOfCells()


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    pvtp, sizes, total = split(sys.argv[1], int(sys.argv[3]), sys.argv[2])
    print("%s: %d faces in %d pieces of %s faces" % (pvtp, total, len(sizes), sizes))
