"""The main job: geodesic distance on a bundled mesh, as a data file and a picture.

Run from the repository root (scripts/setup.sh demo does this under xvfb-run):
    pvpython Examples/geodesic_distance.py [--mesh Data/torus.ply] [--source 0] [--output output]
        [--solver "SVG (label-correcting)" | "SVG (Dijkstra)" | Exact] [--k 50] [--cache file.svgg]
Writes <output>/geodesic_distance.vtp (the mesh with the GeodesicDistance point array) and
<output>/geodesic_distance.png (the distance coloured in bands, with isolines).
With --cache, the saddle vertex graph is saved there and loaded again by the next run.
"""
import argparse
import os
import sys

from paraview.simple import *  # noqa: F401,F403
# Inline base64 (zlib) XML: ParaView 5.11 on Debian 12 cannot read back the raw appended
# data it writes by default (its libexpat rejects the binary bytes).
VTP = dict(DataMode="Binary", CompressorType="ZLib")

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", default=os.path.join(
    root, "build", "lib", "paraview-5.11", "plugins", "GeodesicShapes", "GeodesicShapes.so"))
parser.add_argument("--mesh", default=os.path.join(root, "Data", "torus.ply"))
parser.add_argument("--source", type=int, default=0, help="source point id")
parser.add_argument("--isolines", type=int, default=20)
parser.add_argument("--output", default=os.path.join(root, "output"))
parser.add_argument("--solver", default="SVG (label-correcting)",
                    choices=["SVG (label-correcting)", "SVG (Dijkstra)", "Exact"])
parser.add_argument("--k", type=int, default=50, help="saddle vertex graph K (SVG solvers)")
parser.add_argument("--cache", default="", help="saddle vertex graph cache file (SVG solvers)")
args = parser.parse_args()

LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.output, exist_ok=True)

mesh = PLYReader(FileNames=[args.mesh])
geodesic = SVGGeodesicDistance(Input=mesh, SourceVertexIds=[args.source], Solver=args.solver,
                               K=args.k, CacheFileName=args.cache)
geodesic.UpdatePipeline()
low, high = geodesic.PointData["GeodesicDistance"].GetRange()
print("%s: %d points, %s distance from point %d in [%g, %g]" % (
    os.path.basename(args.mesh), geodesic.GetDataInformation().GetNumberOfPoints(),
    args.solver, args.source, low, high))
if args.solver != "Exact":
    # The field data describes the saddle vertex graph (fetched: it is tiny).
    from paraview import servermanager
    field = servermanager.Fetch(geodesic).GetFieldData()
    print("saddle vertex graph: %s, %.1f links per vertex, build time %.3f s" % (
        field.GetAbstractArray("SVGGraphOrigin").GetValue(0),
        field.GetArray("SVGMeanDegree").GetValue(0), field.GetArray("SVGBuildSeconds").GetValue(0)))

vtp = os.path.join(args.output, "geodesic_distance.vtp")
SaveData(vtp, proxy=geodesic, **VTP)

step = high / args.isolines
isolines = Contour(Input=geodesic, ContourBy=["POINTS", "GeodesicDistance"],
                   Isosurfaces=[step * (i + 0.5) for i in range(args.isolines)],
                   ComputeScalars=False)

view = CreateRenderView()
view.ViewSize = [1000, 700]
view.OrientationAxesVisibility = 0
view.Background = [1.0, 1.0, 1.0]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0

# Smooth shading only (the distance itself is computed on the flat-faced mesh).
smooth = GenerateSurfaceNormals(Input=geodesic, FeatureAngle=90.0)
surface = Show(smooth, view)
ColorBy(surface, ("POINTS", "GeodesicDistance"))
lut = GetColorTransferFunction("GeodesicDistance")
lut.ApplyPreset("Viridis (matplotlib)", True)
lut.RescaleTransferFunction(0.0, high)
surface.SetScalarBarVisibility(view, True)
bar = GetScalarBar(lut, view)
bar.Title = "geodesic distance"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]

lines = Show(isolines, view)
lines.ColorArrayName = ["POINTS", ""]
lines.AmbientColor = lines.DiffuseColor = [0.05, 0.05, 0.05]
lines.LineWidth = 2.0

Render(view)  # the first Render resets the camera: adjust it afterwards
view.ResetCamera()
camera = view.GetActiveCamera()
camera.Elevation(-50)
camera.Azimuth(30)
view.ResetCamera()
camera.Zoom(1.35)
Render(view)
png = os.path.join(args.output, "geodesic_distance.png")
SaveScreenshot(png, view, ImageResolution=[1000, 700])
print("wrote", vtp, "and", png)

Delete(view)
del view
sys.exit(0)
