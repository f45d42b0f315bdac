#include "vtkShapeDistributor.h"

#include "vtkCachedSurface.h"
#include "vtkDistributedSurface.h"
#include "vtkSafeDistanceTableImage.h"
#include "vtkShapeDistributorOutput.h"
#include "vtkSurfacePointLocator.h"

#include "OverlapCheck.h"
#include "SafeDistanceTable.h"
#include "DensityBrush.h"
#include "DirectionField.h"
#include "ShapeDistributor.h"
#include "ShapeDrawing.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <iomanip>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkShapeDistributor);

// The converted mesh and what is derived from it (vtkCachedSurface), and the distributor
// (per-thread geodesic engines), kept while the input mesh is unchanged.
struct vtkShapeDistributor::Cache : vtkCachedSurface
{
  std::unique_ptr<gs::ShapeDistributor> Distributor; // over Mesh.Build.Mesh and Graph()
};

// One Execute's inputs and results, step to step, and the wall time of each phase (reported as
// the field data PhaseSeconds of Placements).
struct vtkShapeDistributor::Run
{
  gs::SafeDistanceTables Tables;
  double ShapeSize = 0.0;     // resolved (ShapeSize 0: automatic)
  vtkIdType FirstPolygon = 0; // the surface's cell id of core face 0
  std::vector<gs::Vec3> Directions; // per face
  std::vector<double> Density;      // per vertex; empty: none
  int Symmetry = 1;                 // of the direction field (the input's field data Symmetry)
  std::string DirectionChoice;      // "CELLS name" or "POINTS name" (DirectionArrayUsed)
  gs::ShapeDistribution Distribution;
  std::vector<std::pair<const char*, double>> Phases;
  std::chrono::steady_clock::time_point Clock = std::chrono::steady_clock::now();

  // Ends the phase `name` now.
  void Lap(const char* name)
  {
    const auto now = std::chrono::steady_clock::now();
    this->Phases.emplace_back(name, std::chrono::duration<double>(now - this->Clock).count());
    this->Clock = now;
  }

  // PhaseSeconds: one tuple, a component per phase (SetUp .. Rounds split Distribution).
  void WritePhaseSeconds(vtkPolyData* placements) const
  {
    vtkNew<vtkDoubleArray> split;
    split->SetName("PhaseSeconds");
    split->SetNumberOfComponents(static_cast<int>(this->Phases.size()));
    split->SetNumberOfTuples(1);
    for (std::size_t k = 0; k < this->Phases.size(); ++k)
    {
      split->SetComponentName(static_cast<vtkIdType>(k), this->Phases[k].first);
      split->SetComponent(0, static_cast<int>(k), this->Phases[k].second);
    }
    placements->GetFieldData()->AddArray(split);
  }
};

namespace
{
// A warning naming the check that rejected most candidates, with the advice that fits.
void WarnAboutRejections(
  vtkShapeDistributor* self, const gs::ShapeDistributionStatistics& st, std::size_t placed)
{
  // Of the candidates the tables let through (placed, or rejected by a later check), a check
  // that rejects most is worth a word: the user sees few shapes and no reason otherwise.
  const double passed = static_cast<double>(placed) +
    static_cast<double>(st.RejectedByFaithfulCheck + st.RejectedByDrawnCheck);
  auto share = [](double part, double whole) {
    return static_cast<int>(100.0 * part / whole + 0.5);
  };
  if (passed >= 50 && st.RejectedByFaithfulCheck > 0.5 * passed)
  {
    vtkWarningWithObjectMacro(self, "FaithfulCheck rejected "
      << st.RejectedByFaithfulCheck << " of the " << static_cast<long long>(passed)
      << " candidates the safe distance tables accepted ("
      << share(st.RejectedByFaithfulCheck, passed) << "%; " << placed
      << " placed): the shapes' maps are not one-to-one over their silhouettes on this "
         "surface, either because the shapes are too large for its curvature (wrapping round a "
         "tube or a bump) or too small for its roughness (a few noisy triangles across). Another "
         "ShapeSize or a smoother mesh place more; FaithfulCheck off places more too, but decals "
         "may then not draw the outlines that were checked.");
  }
  if (passed >= 50 && st.RejectedByDrawnCheck > 0.5 * passed)
  {
    vtkWarningWithObjectMacro(self, "The drawn check (DrawnCheck) rejected "
      << st.RejectedByDrawnCheck << " of the " << static_cast<long long>(passed)
      << " candidates the safe distance tables accepted ("
      << share(st.RejectedByDrawnCheck, passed) << "%; " << placed
      << " placed): their outlines as drawn on this surface overlap where the tables say they "
         "do not. A larger HolonomyMargin makes the tables keep such shapes apart sooner "
         "(fewer wasted candidates); larger shapes or a smoother mesh reduce the difference.");
  }
  const double all = static_cast<double>(st.Candidates);
  if (all >= 100 && st.RejectedWithoutShape > 0.5 * all)
  {
    vtkWarningWithObjectMacro(self, "" << st.RejectedWithoutShape << " of the " << st.Candidates
                       << " candidates (" << share(st.RejectedWithoutShape, all)
                       << "%) could not be laid on the surface: a long shape's streamline or a "
                          "part left the surface (a boundary, a singularity of the field) or "
                          "KeepInside kept it off. Shorter shapes (MSDT Source's "
                          "MaximumAspectRatio splits them), a field with fewer singularities, "
                          "or KeepInside off place more.");
  }
}

// ShapeSize 0 (the proxy's default before the GUI proposes a value): this fraction of the
// input's largest bounding-box side.
constexpr double AutomaticShapeSize = 0.04;
// Fraction of ShapeSize by which decals and outlines are lifted along the face normals.
constexpr double Lift = 0.002;

vtkDataArray* FieldArray(vtkFieldData* fd, const char* name, int components)
{
  vtkDataArray* a = fd ? vtkDataArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  return a && a->GetNumberOfComponents() == components ? a : nullptr;
}

// False (with an error) when no face has a usable (finite, tangent) vector; warns when over 10%
// have none.
bool CheckUsableDirections(vtkShapeDistributor* self, const gs::TriangleMesh& mesh,
  const std::string& directionName, const std::vector<gs::Vec3>& directions)
{
  // Faces whose vector is zero, not finite or normal to the surface give their shapes a random
  // orientation (the distributor's rule): a few are normal (a field's singularities), all or
  // most of them are a mistake the user should hear about.
  const int nf = mesh.NumberOfFaces();
  int unusable = 0;
  for (int f = 0; f < nf; ++f)
  {
    const gs::Vec3& d = directions[f];
    const gs::Vec3 n = mesh.FaceNormal(f);
    const gs::Vec3 t = d - n * gs::Dot(n, d);
    unusable += !(gs::IsFinite(d) && gs::Norm(t) > 1e-12 * gs::Norm(d) && gs::Norm(t) > 0.0);
  }
  if (unusable == nf)
  {
    vtkErrorWithObjectMacro(self, "The DirectionArray \"" << directionName << "\" has no usable vector: all "
                                          << nf
                                          << " triangles get a zero, NaN or surface-normal "
                                             "vector. Run Cross Field, or give tangent vectors.");
    return false;
  }
  if (unusable > nf / 10)
  {
    vtkWarningWithObjectMacro(self, "The DirectionArray \"" << directionName << "\": " << unusable << " of " << nf
                                            << " triangles ("
                                            << static_cast<int>(100.0 * unusable / nf + 0.5)
                                            << "%) get a zero, NaN or surface-normal vector: "
                                               "shapes there get a random orientation.");
  }
  return true;
}

} // namespace

//------------------------------------------------------------------------------
vtkShapeDistributor::vtkShapeDistributor()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "Direction");
}

//------------------------------------------------------------------------------
vtkShapeDistributor::~vtkShapeDistributor() = default;

//------------------------------------------------------------------------------
void vtkShapeDistributor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ShapeSize: " << this->ShapeSize << "\n";
  os << indent << "Mode: " << this->Mode << "\n";
  os << indent << "CandidateOrder: " << this->CandidateOrder << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MaximumShapes: " << this->MaximumShapes << "\n";
  os << indent << "MaximalFailures: " << this->MaximalFailures << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "DistortionLimit: " << this->DistortionLimit << "\n";
  os << indent << "HolonomyMargin: " << this->HolonomyMargin << "\n";
  os << indent << "KeepInside: " << this->KeepInside << "\n";
  os << indent << "DrawnCheck: " << this->DrawnCheck << "\n";
  os << indent << "FaithfulCheck: " << this->FaithfulCheck << "\n";
  os << indent << "DecalTolerance: " << this->DecalTolerance << "\n";
  os << indent << "VerifyOverlaps: " << this->VerifyOverlaps << "\n";
  os << indent << "Solver: " << this->Solver << " ("
     << gs::GeodesicSolverName(static_cast<gs::GeodesicSolver>(this->Solver)) << ")\n";
  os << indent << "K: " << this->K << "\n";
  os << indent << "GraphAccuracy: " << this->GraphAccuracy << "\n";
  os << indent << "CacheFileName: " << this->CacheFileName << "\n";
  os << indent << "BrushCenter: (" << this->BrushCenter[0] << ", " << this->BrushCenter[1] << ", "
     << this->BrushCenter[2] << ")\n";
  os << indent << "BrushRadius: " << this->BrushRadius << "\n";
  os << indent << "BrushDensity: " << this->BrushDensity << "\n";
}

//------------------------------------------------------------------------------
void vtkShapeDistributor::SetNumberOfClassWeights(int n)
{
  n = std::max(0, n);
  if (static_cast<int>(this->ClassWeights.size()) != n)
  {
    this->ClassWeights.resize(n, 1.0);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkShapeDistributor::SetClassWeight(int i, double w)
{
  if (i < 0)
  {
    return;
  }
  if (i >= static_cast<int>(this->ClassWeights.size()))
  {
    this->ClassWeights.resize(i + 1, 1.0);
  }
  if (this->ClassWeights[i] != w)
  {
    this->ClassWeights[i] = w;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkShapeDistributor::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    return 1;
  }
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkShapeDistributor::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkImageData* tableImage = vtkImageData::GetData(inputVector[1], 0);
  vtkPolyData* placements = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* decals = vtkPolyData::GetData(outputVector, 1);
  vtkPolyData* outlines = vtkPolyData::GetData(outputVector, 2);
  if (!placements || !decals || !outlines)
  {
    vtkErrorMacro("Missing outputs.");
    return 0;
  }
  placements->Initialize();
  decals->Initialize();
  outlines->Initialize();

  // Under MPI: the whole surface and the tables on process 0, which outputs every shape (the
  // other processes output empty placements, decals and outlines).
  const vtkDistributedSurface distributed(outputVector->GetInformationObject(0));
  if (distributed)
  {
    vtkSmartPointer<vtkPolyData> whole = distributed.GatherSurface(input);
    vtkSmartPointer<vtkDataObject> tables = distributed.GatherFirstNonEmpty(tableImage);
    if (distributed.IsRoot())
    {
      this->Execute(whole, vtkImageData::SafeDownCast(tables), placements, decals, outlines);
    }
    return 1;
  }
  return this->Execute(input, tableImage, placements, decals, outlines);
}

//------------------------------------------------------------------------------
int vtkShapeDistributor::Execute(vtkPolyData* input, vtkImageData* tableImage,
  vtkPolyData* placements, vtkPolyData* decals, vtkPolyData* outlines)
{
  if (!input || !tableImage)
  {
    vtkErrorMacro("Shape Distributor needs a mesh (port 0) and the tables of MSDT Source "
                  "(port 1, Table).");
    return 1;
  }
  this->UpdateProgress(0.0);
  Run run;

  // 1. Parameters and tables.
  if (!this->CheckParameters())
  {
    return 1;
  }
  gs::Result<gs::SafeDistanceTables> tables = vtkSafeDistanceTableImage::FromImage(tableImage);
  if (!tables.Ok())
  {
    vtkErrorMacro("" << tables.Message() << ".");
    return 1;
  }
  run.Tables = std::move(*tables);
  run.Lap("Tables");

  // 2. Mesh (kept while unchanged) and the shape size.
  Cache& cache = vtkSurfaceMeshConverter::Update(this->MeshCache, input);
  if (!vtkSurfaceMeshConverter::Report(cache.Mesh, this) || !this->ResolveShapeSize(cache, run))
  {
    return 1;
  }
  run.Lap("Mesh");

  // 3. Direction (per face) and density (per vertex), read on the converted surface (which
  // carries the input's arrays through a triangulation).
  if (!this->ReadDirections(input, cache, run) || !this->ReadDensity(cache, run))
  {
    return 1;
  }
  this->UpdateProgress(0.05);
  if (this->CheckAbort())
  {
    return 1;
  }
  run.Lap("Input");

  // 4. The geodesic graph of the charts (shared, cached: the saddle vertex graph of K, or the
  //    discrete geodesic graph of K and GraphAccuracy; none for Solver EXACT) and the
  //    distributor.
  if (!this->UseGraph(cache))
  {
    return 1;
  }
  run.Lap("Graph");
  if (this->BrushRadius > 0.0)
  {
    if (!this->ApplyBrush(cache, run))
    {
      return 1;
    }
    run.Lap("Brush");
  }

  // 5. Distribution.
  if (!this->Distribute(cache, run))
  {
    return 1;
  }

  // 6. Placements.
  vtkShapeDistributorOutput::WritePlacements(
    run.Distribution, run.FirstPolygon, run.ShapeSize, run.DirectionChoice, placements);
  this->UpdateProgress(0.87);
  if (this->CheckAbort())
  {
    placements->Initialize();
    return 1;
  }

  // 7. Decals and outlines, checked for overlaps if asked.
  if (!this->DrawShapes(cache, run, placements, decals, outlines))
  {
    placements->Initialize();
    return 1;
  }
  run.WritePhaseSeconds(placements);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkShapeDistributor::UseGraph(Cache& cache)
{
  bool graphChanged = false;
  if (!cache.UseEngineGraph(this, this->Solver, this->K, this->GraphAccuracy, this->CacheFileName,
        0.05, 0.35, graphChanged))
  {
    return false; // aborted, or the error is reported
  }
  if (!cache.Distributor || graphChanged)
  {
    cache.Distributor.reset();
    cache.Distributor.reset(new gs::ShapeDistributor(cache.Mesh.Build.Mesh, cache.Graph()));
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkShapeDistributor::DrawShapes(
  const Cache& cache, Run& run, vtkPolyData* placements, vtkPolyData* decals, vtkPolyData* outlines)
{
  // Every shape's decal and outline, computed per shape in parallel (the outlines as the drawn
  // check drew them).
  const gs::ShapeDistributor& distributor = *cache.Distributor;
  // (Progress and abort inside each drawing phase too: they are proportional to the shapes
  // placed, which may be many.)
  auto phase = [this](double start, double span) {
    return [this, start, span](double fraction) {
      this->UpdateProgress(start + span * fraction);
      return !this->CheckAbort();
    };
  };
  const std::vector<gs::ShapeDecal> decalOf = gs::DrawDecals(
    distributor, this->DecalTolerance, this->UsedThreads(), nullptr, phase(0.85, 0.05));
  run.Lap("Decals");
  if (this->CheckAbort())
  {
    return false;
  }
  const std::vector<std::vector<gs::OutlinePiece>> outlineOf =
    gs::DrawOutlines(distributor, this->UsedThreads(), phase(0.9, 0.03));
  run.Lap("Outlines");
  if (this->CheckAbort())
  {
    return false;
  }

  // VerifyOverlaps: the drawn outlines checked against each other, independently of the tables.
  const std::vector<gs::PlacedShape>& shapes = run.Distribution.Shapes;
  if (this->VerifyOverlaps)
  {
    gs::OverlapCheckOptions check;
    check.NumberOfThreads = this->UsedThreads();
    check.Progress = phase(0.93, 0.04);
    const gs::Result<gs::OverlapCheckResult> found =
      gs::CheckOverlaps(distributor, outlineOf, check);
    if (found.IsAborted())
    {
      return false;
    }
    if (!found.Ok())
    {
      vtkErrorMacro("VerifyOverlaps: " << found.Message() << ".");
      return false;
    }
    vtkShapeDistributorOutput::WriteOverlaps(*found, static_cast<int>(shapes.size()), placements);
    if (!found->Pairs.empty())
    {
      vtkWarningMacro("VerifyOverlaps: " << found->Pairs.size() << " pair(s) of shapes overlap "
                                         << "(first: shapes " << found->Pairs[0].first << " and "
                                         << found->Pairs[0].second
                                         << "); see the Overlaps array of Placements.");
    }
    run.Lap("VerifyOverlaps");
  }

  // Assembled in shape order, lifted off the surface.
  const int threads = gs::ThreadCount(this->UsedThreads());
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  const double lift = Lift * run.ShapeSize;
  vtkShapeDistributorOutput::WriteDecals(mesh, shapes, decalOf, lift, threads, decals);
  vtkShapeDistributorOutput::WriteOutlines(mesh, shapes, outlineOf, lift, threads, outlines);
  run.Lap("Assembly");
  return true;
}

//------------------------------------------------------------------------------
int vtkShapeDistributor::UsedThreads() const
{
  // (Capped: more threads than processors only cost memory, a chart engine each.)
  return std::min(this->NumberOfThreads, gs::MaximumThreadCount());
}

//------------------------------------------------------------------------------
// The parameters the distributor does not see (it checks its own options when it runs).
bool vtkShapeDistributor::CheckParameters()
{
  if (!(this->BrushRadius >= 0.0) || !std::isfinite(this->BrushRadius))
  {
    vtkErrorMacro("BrushRadius must be a finite number, at least 0 (0: no brush); it is "
      << this->BrushRadius << ".");
    return false;
  }
  if (this->BrushRadius > 0.0)
  {
    // (The brush's own check, before any work.)
    if (const gs::Status checked =
          gs::CheckBrushParameters(this->BrushRadius, this->BrushDensity);
        !checked.Ok())
    {
      vtkErrorMacro("BrushRadius, BrushDensity: " << checked.Message() << ".");
      return false;
    }
    if (!std::isfinite(this->BrushCenter[0]) || !std::isfinite(this->BrushCenter[1]) ||
      !std::isfinite(this->BrushCenter[2]))
    {
      vtkErrorMacro("BrushCenter must be a finite point; it is (" << this->BrushCenter[0] << ", "
                                                                  << this->BrushCenter[1] << ", "
                                                                  << this->BrushCenter[2] << ").");
      return false;
    }
  }
  if (!(this->DecalTolerance >= 0.0) || !std::isfinite(this->DecalTolerance))
  {
    vtkErrorMacro("DecalTolerance must be a finite number, at least 0 (it is "
      << this->DecalTolerance << ").");
    return false;
  }
  if (!vtkCachedSurface::CheckEngine(this, this->Solver,
        { gs::GeodesicSolver::Exact, gs::GeodesicSolver::SVGLabelCorrecting, gs::GeodesicSolver::DGG },
        this->K))
  {
    return false;
  }
  // The options the distributor checks itself, checked here before any work (the same ranges
  // and messages: the properties carry the options' names).
  gs::ShapeDistributionOptions ranges;
  ranges.MaximumShapes = this->MaximumShapes;
  ranges.MaximalFailures = this->MaximalFailures;
  ranges.Order = static_cast<gs::CandidateOrder>(this->CandidateOrder);
  ranges.NumberOfThreads = this->NumberOfThreads;
  ranges.DistortionLimit = this->DistortionLimit;
  ranges.HolonomyMargin = this->HolonomyMargin;
  if (const gs::Status checked = gs::ShapeDistributor::CheckOptionRanges(ranges); !checked.Ok())
  {
    vtkErrorMacro(<< checked.Message() << ".");
    return false;
  }
  if (this->NumberOfThreads > gs::MaximumThreadCount())
  {
    vtkWarningMacro("NumberOfThreads " << this->NumberOfThreads << " is more than the "
                                       << gs::MaximumThreadCount() << " processors: "
                                       << gs::MaximumThreadCount()
                                       << " threads are used (the result does not depend on it).");
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkShapeDistributor::ResolveShapeSize(const Cache& cache, Run& run)
{
  vtkPolyData* surface = cache.Mesh.Surface;
  // ShapeSize 0: automatic, a fraction of the surface's largest bounding-box side (what the
  // GUI's properties panel proposes too, through the property's bounds domain).
  double shapeSize = this->ShapeSize;
  if (shapeSize == 0.0)
  {
    double b[6];
    surface->GetBounds(b);
    shapeSize = AutomaticShapeSize * std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
    if (!(shapeSize > 0.0) || !std::isfinite(shapeSize))
    {
      vtkErrorMacro("ShapeSize is 0 (automatic) but the input's bounds are empty: set ShapeSize.");
      return false;
    }
  }
  run.ShapeSize = shapeSize;
  run.FirstPolygon = surface->GetNumberOfVerts() + surface->GetNumberOfLines();
  return true;
}

//------------------------------------------------------------------------------
bool vtkShapeDistributor::ChooseDirectionArray(
  vtkPolyData* surface, std::string& name, int& association)
{
  vtkInformation* directionInfo = this->GetInputArrayInformation(0);
  const char* directionName = directionInfo && directionInfo->Has(vtkDataObject::FIELD_NAME())
    ? directionInfo->Get(vtkDataObject::FIELD_NAME())
    : nullptr;
  association = directionInfo && directionInfo->Has(vtkDataObject::FIELD_ASSOCIATION())
    ? directionInfo->Get(vtkDataObject::FIELD_ASSOCIATION())
    : vtkDataObject::FIELD_ASSOCIATION_CELLS;
  // Unset (ParaView leaves "0" or nothing when the input's arrays were not known when the
  // filter was made): the cell array Direction (Cross Field's), its point array, then the active
  // vectors (cells, then points). The choice is the field data DirectionArrayUsed of Placements.
  if (!directionName || !*directionName || std::string(directionName) == "0" ||
    std::string(directionName) == "None")
  {
    auto vectors3 = [](vtkDataArray* a) { return a && a->GetNumberOfComponents() == 3 ? a : nullptr; };
    const std::pair<vtkDataArray*, int> found[] = {
      { vectors3(surface->GetCellData()->GetArray("Direction")), vtkDataObject::FIELD_ASSOCIATION_CELLS },
      { vectors3(surface->GetPointData()->GetArray("Direction")), vtkDataObject::FIELD_ASSOCIATION_POINTS },
      { vectors3(surface->GetCellData()->GetVectors()), vtkDataObject::FIELD_ASSOCIATION_CELLS },
      { vectors3(surface->GetPointData()->GetVectors()), vtkDataObject::FIELD_ASSOCIATION_POINTS },
    };
    directionName = nullptr;
    for (const auto& f : found)
    {
      if (f.first && f.first->GetName() && *f.first->GetName())
      {
        directionName = f.first->GetName();
        association = f.second;
        break;
      }
    }
    if (!directionName)
    {
      vtkErrorMacro("No DirectionArray given and the input has none to use: no cell or point "
                    "array Direction and no active 3-component vectors. Run Cross Field first, or "
                    "set DirectionArray to a cell or point array of tangent vectors.");
      return false;
    }
  }
  name = directionName;
  if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
    association != vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    vtkErrorMacro("The DirectionArray \"" << name
                                          << "\" must be a point or cell array (association "
                                          << association << ").");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkShapeDistributor::ReadDirections(vtkPolyData* input, const Cache& cache, Run& run)
{
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  vtkPolyData* surface = cache.Mesh.Surface;
  const int nf = mesh.NumberOfFaces();
  std::string directionName;
  int directionAssociation = vtkDataObject::FIELD_ASSOCIATION_CELLS;
  if (!this->ChooseDirectionArray(surface, directionName, directionAssociation))
  {
    return false;
  }
  const bool onPoints = directionAssociation == vtkDataObject::FIELD_ASSOCIATION_POINTS;
  run.DirectionChoice = std::string(onPoints ? "POINTS " : "CELLS ") + directionName;
  int& symmetry = run.Symmetry;
  symmetry = 1;
  if (vtkDataArray* s = FieldArray(input->GetFieldData(), "Symmetry", 1))
  {
    symmetry = static_cast<int>(s->GetComponent(0, 0));
    if (symmetry != 1 && symmetry != 2 && symmetry != 4)
    {
      vtkWarningMacro("The input's field data Symmetry is " << symmetry
                                                           << " (not 1, 2 or 4): 1 is used.");
      symmetry = 1;
    }
  }
  std::vector<gs::Vec3>& directions = run.Directions;
  directions.assign(nf, gs::Vec3{ 0, 0, 0 });
  vtkDataArray* a = onPoints ? surface->GetPointData()->GetArray(directionName.c_str())
                             : surface->GetCellData()->GetArray(directionName.c_str());
  if (!a || a->GetNumberOfComponents() != 3)
  {
    vtkErrorMacro("The DirectionArray \"" << directionName << "\" is missing from the input's "
                  << (onPoints ? "point" : "cell") << " data or does not have 3 components.");
    return false;
  }
  if (onPoints)
  {
    // Per face: the corners' vectors averaged N-symmetrically (a cross given by any arm).
    const std::vector<double> values =
      vtkSurfaceMeshConverter::PointArrayOnVertices(a, cache.Mesh.Build, 0.0);
    std::vector<gs::Vec3> atVertex(mesh.NumberOfVertices());
    for (std::size_t v = 0; v < atVertex.size(); ++v)
    {
      atVertex[v] = gs::Vec3{ values[3 * v], values[3 * v + 1], values[3 * v + 2] };
    }
    gs::Result<std::vector<gs::Vec3>> perFace =
      gs::FaceDirectionsFromVertices(mesh, atVertex, symmetry);
    if (!perFace.Ok())
    {
      vtkErrorMacro("The DirectionArray \"" << directionName << "\": " << perFace.Message()
                                             << ".");
      return false;
    }
    directions = std::move(*perFace);
  }
  else
  {
    for (int f = 0; f < nf; ++f)
    {
      double x[3];
      a->GetTuple(run.FirstPolygon + f, x);
      directions[f] = gs::Vec3{ x[0], x[1], x[2] };
    }
  }
  return CheckUsableDirections(this, mesh, directionName, directions);
}

//------------------------------------------------------------------------------
bool vtkShapeDistributor::ReadDensity(const Cache& cache, Run& run)
{
  const std::vector<int>& pointToVertex = cache.Mesh.Build.PointToVertex;
  vtkPolyData* surface = cache.Mesh.Surface;
  const int nv = cache.Mesh.Build.Mesh.NumberOfVertices();
  std::vector<double>& density = run.Density;
  density.clear();
  vtkInformation* densityInfo = this->GetInputArrayInformation(1);
  const char* densityName = densityInfo && densityInfo->Has(vtkDataObject::FIELD_NAME())
    ? densityInfo->Get(vtkDataObject::FIELD_NAME())
    : nullptr;
  if (densityName && *densityName && std::string(densityName) != "None")
  {
    vtkDataArray* a = surface->GetPointData()->GetArray(densityName);
    if (!a || a->GetNumberOfComponents() != 1)
    {
      vtkErrorMacro("The DensityArray \"" << densityName
                                          << "\" is missing from the input's point data or is "
                                             "not a scalar array.");
      return false;
    }
    density = vtkSurfaceMeshConverter::PointArrayOnVertices(
      a, cache.Mesh.Build, std::numeric_limits<double>::quiet_NaN());
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkShapeDistributor::ApplyBrush(Cache& cache, Run& run)
{
  // The closest surface point, however far the sphere widget's centre was dragged off the
  // surface (from inside a closed mesh too), unless it lies beyond the bounding box diagonal:
  // a point in other units or another frame.
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  const gs::Result<gs::SurfacePoint> center = cache.Locator().Snap(this->BrushCenter, 1.0);
  if (!center.Ok())
  {
    vtkErrorMacro("BrushCenter: " << center.Message() << ".");
    return false;
  }
  gs::DensityBrush brush;
  brush.Center = *center;
  brush.Radius = this->BrushRadius;
  brush.Density = this->BrushDensity;
  const gs::Result<std::vector<double>> factors =
    gs::BrushFactors(mesh, cache.Graph(), brush, this->UsedThreads());
  if (!factors.Ok())
  {
    vtkErrorMacro("Density brush: " << factors.Message() << ".");
    return false;
  }
  gs::ApplyBrushFactors(*factors, run.Density);
  return true;
}

//------------------------------------------------------------------------------
bool vtkShapeDistributor::Distribute(Cache& cache, Run& run)
{
  gs::ShapeDistributor& distributor = *cache.Distributor;
  // A warning first when it will be long: a tiny ShapeSize, or density factors near 0, multiply
  // the shapes by 1 / f^2.
  const double expected = gs::ShapeDistributor::ExpectedCount(
    distributor.Mesh(), run.Tables, run.Density, run.ShapeSize);
  // (Not for counts the distributor refuses anyway: sizes below a 1e7th of an edge.)
  if (expected > 250000.0 && run.ShapeSize * 1e7 >= distributor.Mesh().MeanEdgeLength() &&
    (this->MaximumShapes == 0 || this->MaximumShapes > 250000))
  {
    // (Printed as a number of 3 digits: a count beyond 2^63, from an absurd size, is refused by
    // the distributor, but the warning comes first and must not overflow.)
    std::ostringstream count;
    count << std::setprecision(3) << expected;
    vtkWarningMacro("About " << count.str()
                             << " shapes are expected (ShapeSize " << run.ShapeSize
                             << " times the density factors): the run may take minutes and "
                                "gigabytes. A larger ShapeSize, density factors away from 0 or "
                                "MaximumShapes keep it short; it can be aborted.");
  }
  gs::ShapeDistributionOptions options;
  options.ShapeSize = run.ShapeSize;
  options.ClassWeights = this->ClassWeights;
  options.Mode = static_cast<gs::DistributionMode>(this->Mode);
  options.Order = static_cast<gs::CandidateOrder>(this->CandidateOrder);
  options.Seed = static_cast<std::uint64_t>(static_cast<std::uint32_t>(this->Seed));
  options.MaximumShapes = this->MaximumShapes;
  options.MaximalFailures = this->MaximalFailures;
  options.NumberOfThreads = this->UsedThreads();
  options.Symmetry = run.Symmetry;
  options.DistortionLimit = this->DistortionLimit;
  options.HolonomyMargin = this->HolonomyMargin;
  options.KeepInside = this->KeepInside;
  options.DrawnCheck = this->DrawnCheck;
  options.FaithfulCheck = this->FaithfulCheck;
  gs::Result<gs::ShapeDistribution> placed =
    distributor.Run(run.Tables, run.Directions, run.Density, options, [this](double p) {
      this->UpdateProgress(0.4 + 0.45 * p);
      return !this->CheckAbort();
    });
  if (!placed.Ok())
  {
    if (!placed.IsAborted())
    {
      vtkErrorMacro("Shape distribution: " << placed.Message() << ".");
    }
    return false;
  }
  run.Distribution = std::move(*placed);
  run.Lap("Distribution");
  const gs::ShapeDistributionStatistics& st = run.Distribution.Statistics;
  run.Phases.emplace_back("SetUp", st.PrepareSeconds);
  run.Phases.emplace_back("Candidates", st.GenerateSeconds);
  run.Phases.emplace_back("ChecksAndCharts", st.CheckSeconds);
  run.Phases.emplace_back("Rounds", st.RoundSeconds);
  WarnAboutRejections(this, st, run.Distribution.Shapes.size());
  return true;
}

