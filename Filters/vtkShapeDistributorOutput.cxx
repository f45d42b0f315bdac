#include "vtkShapeDistributorOutput.h"

#include "ParallelFor.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

namespace
{
vtkSmartPointer<vtkIdTypeArray> IdArray(vtkIdType n)
{
  vtkNew<vtkIdTypeArray> a;
  a->SetNumberOfValues(n);
  return vtkSmartPointer<vtkIdTypeArray>(a.GetPointer());
}
} // namespace

namespace vtkShapeDistributorOutput
{
// Fills Placements: one vertex per shape with its class, scale, direction, normal and face (the
// input's cell id), and the run's statistics as field data.
void WritePlacements(const gs::ShapeDistribution& result, vtkIdType firstPolygon, double shapeSize,
  const std::string& directionChoice, vtkPolyData* placements)
{
  const std::vector<gs::PlacedShape>& shapes = result.Shapes;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> verts;
  vtkNew<vtkIntArray> classId;
  classId->SetName("ClassId");
  vtkNew<vtkDoubleArray> scale;
  scale->SetName("Scale");
  vtkNew<vtkDoubleArray> direction;
  direction->SetName("Direction");
  direction->SetNumberOfComponents(3);
  vtkNew<vtkDoubleArray> normal;
  normal->SetName("Normal");
  normal->SetNumberOfComponents(3);
  vtkNew<vtkIdTypeArray> faceId;
  faceId->SetName("FaceId");
  for (const gs::PlacedShape& s : shapes)
  {
    const vtkIdType id = points->InsertNextPoint(s.Position.x, s.Position.y, s.Position.z);
    verts->InsertNextCell(1, &id);
    classId->InsertNextValue(s.ClassId);
    scale->InsertNextValue(s.Scale);
    direction->InsertNextTuple3(s.Direction.x, s.Direction.y, s.Direction.z);
    normal->InsertNextTuple3(s.Normal.x, s.Normal.y, s.Normal.z);
    faceId->InsertNextValue(firstPolygon + s.Centre.Face);
  }
  placements->SetPoints(points);
  placements->SetVerts(verts);
  placements->GetPointData()->AddArray(classId);
  placements->GetPointData()->AddArray(scale);
  placements->GetPointData()->AddArray(direction);
  placements->GetPointData()->AddArray(normal);
  placements->GetPointData()->AddArray(faceId);
  placements->GetPointData()->SetActiveScalars("ClassId");
  placements->GetPointData()->SetActiveVectors("Direction");
  vtkFieldData* fd = placements->GetFieldData();
  auto single = [fd](const char* name, double value) {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fd->AddArray(a);
  };
  single("NumberOfCandidates", static_cast<double>(result.Statistics.Candidates));
  single("NumberOfCharts", static_cast<double>(result.Statistics.Charts));
  // What rejected the candidates that were not placed (ShapeDistributionStatistics).
  single("CandidatesWithoutShape", static_cast<double>(result.Statistics.RejectedWithoutShape));
  single("CandidatesRejectedByTables", static_cast<double>(result.Statistics.RejectedByTables));
  single("CandidatesRejectedByFaithfulCheck",
    static_cast<double>(result.Statistics.RejectedByFaithfulCheck));
  single("CandidatesRejectedByDrawnCheck", static_cast<double>(result.Statistics.RejectedByDrawnCheck));
  single("Maximal", result.Statistics.Maximal ? 1.0 : 0.0);
  // (Place-keyed: the candidates decided in this run, and whether it reused the last one.)
  single("CandidatesRedecided", static_cast<double>(result.Statistics.Redecided));
  single("IncrementalRun", result.Statistics.Incremental ? 1.0 : 0.0);
  single("EditShare", result.Statistics.EditShare);
  single("Seconds", result.Statistics.Seconds);
  single("ShapeSizeUsed", shapeSize);
  vtkNew<vtkStringArray> used;
  used->SetName("DirectionArrayUsed");
  used->InsertNextValue(directionChoice);
  fd->AddArray(used);
}

// VerifyOverlaps' result on Placements: Overlaps per shape, OverlappingPairs, OverlapCheckSeconds.
void WriteOverlaps(const gs::OverlapCheckResult& found, int ns, vtkPolyData* placements)
{
  vtkNew<vtkIntArray> overlaps;
  overlaps->SetName("Overlaps");
  for (int s = 0; s < ns; ++s)
  {
    overlaps->InsertNextValue(found.Overlaps[s]);
  }
  placements->GetPointData()->AddArray(overlaps);
  vtkNew<vtkDoubleArray> pairs, seconds;
  pairs->SetName("OverlappingPairs");
  pairs->InsertNextValue(static_cast<double>(found.Pairs.size()));
  seconds->SetName("OverlapCheckSeconds");
  seconds->InsertNextValue(found.Seconds);
  placements->GetFieldData()->AddArray(pairs);
  placements->GetFieldData()->AddArray(seconds);
}

// Decals: the triangles of every shape's decal with their texture coordinates; cell arrays
// ShapeId and ClassId.
void WriteDecals(const gs::TriangleMesh& mesh, const std::vector<gs::PlacedShape>& shapes,
  const std::vector<gs::ShapeDecal>& decalOf, double lift, int threads, vtkPolyData* decals)
{
  (void)threads;
  const int ns = static_cast<int>(shapes.size());
  std::vector<vtkIdType> first(ns + 1, 0);
  for (int s = 0; s < ns; ++s)
  {
    first[s + 1] = first[s] + static_cast<vtkIdType>(decalOf[s].Faces.size());
  }
  const vtkIdType nd = first[ns];
  vtkNew<vtkDoubleArray> xyz;
  xyz->SetNumberOfComponents(3);
  xyz->SetNumberOfTuples(3 * nd);
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetName("TextureCoordinates");
  tcoords->SetNumberOfComponents(2);
  tcoords->SetNumberOfTuples(3 * nd);
  vtkNew<vtkIntArray> shapeId, classId;
  shapeId->SetName("ShapeId");
  classId->SetName("ClassId");
  shapeId->SetNumberOfValues(nd);
  classId->SetNumberOfValues(nd);
  vtkSmartPointer<vtkIdTypeArray> offsets = IdArray(nd + 1), connectivity = IdArray(3 * nd);
  double* x = xyz->GetPointer(0);
  float* t = tcoords->GetPointer(0);
  vtkIdType* o = offsets->GetPointer(0);
  vtkIdType* c = connectivity->GetPointer(0);
  gs::ParallelFor(ns, threads, 16, [&](int s, int) {
    const gs::ShapeDecal& d = decalOf[s];
    for (std::size_t k = 0; k < d.Faces.size(); ++k)
    {
      const vtkIdType cell = first[s] + static_cast<vtkIdType>(k);
      for (int j = 0; j < 3; ++j)
      {
        const gs::Vec3 p = gs::LiftedFacePoint(mesh, d.Faces[k], d.Corners[k][j], lift);
        const vtkIdType id = 3 * cell + j;
        x[3 * id] = p.x;
        x[3 * id + 1] = p.y;
        x[3 * id + 2] = p.z;
        t[2 * id] = static_cast<float>(d.TextureCoordinates[k][j].x);
        t[2 * id + 1] = static_cast<float>(d.TextureCoordinates[k][j].y);
        c[id] = id;
      }
      o[cell] = 3 * cell;
      shapeId->SetValue(cell, s);
      classId->SetValue(cell, shapes[s].ClassId);
    }
  });
  o[nd] = 3 * nd;
  vtkNew<vtkPoints> points;
  points->SetData(xyz);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  decals->SetPoints(points);
  decals->SetPolys(polys);
  decals->GetPointData()->SetTCoords(tcoords);
  decals->GetCellData()->AddArray(shapeId);
  decals->GetCellData()->AddArray(classId);
}

// Outlines: one polyline per outline piece (closed pieces repeat their first point); cell
// arrays ShapeId and ClassId.
void WriteOutlines(const gs::TriangleMesh& mesh, const std::vector<gs::PlacedShape>& shapes,
  const std::vector<std::vector<gs::OutlinePiece>>& outlineOf, double lift, int threads,
  vtkPolyData* outlines)
{
  (void)threads;
  const int ns = static_cast<int>(shapes.size());
  // Per shape: its first line and point; a closed piece repeats its first point id.
  std::vector<vtkIdType> firstLine(ns + 1, 0), firstPoint(ns + 1, 0), firstId(ns + 1, 0);
  for (int s = 0; s < ns; ++s)
  {
    vtkIdType lines = 0, points = 0, ids = 0;
    for (const gs::OutlinePiece& piece : outlineOf[s])
    {
      if (piece.Points.size() >= 2)
      {
        ++lines;
        points += static_cast<vtkIdType>(piece.Points.size());
        ids += static_cast<vtkIdType>(piece.Points.size()) + (piece.Closed ? 1 : 0);
      }
    }
    firstLine[s + 1] = firstLine[s] + lines;
    firstPoint[s + 1] = firstPoint[s] + points;
    firstId[s + 1] = firstId[s] + ids;
  }
  const vtkIdType nl = firstLine[ns], np = firstPoint[ns], ni = firstId[ns];
  vtkNew<vtkDoubleArray> xyz;
  xyz->SetNumberOfComponents(3);
  xyz->SetNumberOfTuples(np);
  vtkNew<vtkIntArray> shapeId, classId;
  shapeId->SetName("ShapeId");
  classId->SetName("ClassId");
  shapeId->SetNumberOfValues(nl);
  classId->SetNumberOfValues(nl);
  vtkSmartPointer<vtkIdTypeArray> offsets = IdArray(nl + 1), connectivity = IdArray(ni);
  double* x = xyz->GetPointer(0);
  vtkIdType* o = offsets->GetPointer(0);
  vtkIdType* c = connectivity->GetPointer(0);
  gs::ParallelFor(ns, threads, 16, [&](int s, int) {
    vtkIdType line = firstLine[s], point = firstPoint[s], id = firstId[s];
    for (const gs::OutlinePiece& piece : outlineOf[s])
    {
      if (piece.Points.size() < 2)
      {
        continue;
      }
      o[line] = id;
      shapeId->SetValue(line, s);
      classId->SetValue(line, shapes[s].ClassId);
      ++line;
      const vtkIdType start = point;
      for (const gs::SurfacePoint& q : piece.Points)
      {
        const gs::Vec3 p = gs::LiftedSurfacePoint(mesh, q, lift);
        x[3 * point] = p.x;
        x[3 * point + 1] = p.y;
        x[3 * point + 2] = p.z;
        c[id++] = point++;
      }
      if (piece.Closed)
      {
        c[id++] = start;
      }
    }
  });
  o[nl] = ni;
  vtkNew<vtkPoints> points;
  points->SetData(xyz);
  vtkNew<vtkCellArray> lines;
  lines->SetData(offsets, connectivity);
  outlines->SetPoints(points);
  outlines->SetLines(lines);
  outlines->GetCellData()->AddArray(shapeId);
  // (ClassId is not the active scalars: the GUI then draws the outlines in a solid colour,
  // which stands out on any surface colouring; colour by ClassId to tell the classes apart.)
  outlines->GetCellData()->AddArray(classId);
}

} // namespace vtkShapeDistributorOutput
