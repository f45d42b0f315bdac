#include "vtkSafeDistanceTableImage.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>

#include <initializer_list>
#include <utility>
#include <vector>

namespace
{
vtkSmartPointer<vtkDoubleArray> DoubleArray(const char* name, int components)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  return vtkSmartPointer<vtkDoubleArray>(a.GetPointer());
}

vtkSmartPointer<vtkIntArray> IntArray(const char* name)
{
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  return vtkSmartPointer<vtkIntArray>(a.GetPointer());
}

vtkDataArray* FieldArray(vtkFieldData* fd, const char* name, int components)
{
  vtkDataArray* a = fd ? vtkDataArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  return a && a->GetNumberOfComponents() == components ? a : nullptr;
}

// The image's geometry: x and y the angle bins of the pair's two parts (an angle bin wide), z
// the ordered pair of parts; at the origin.
struct TableImageGeometry
{
  int Extent[6];
  double Spacing[3];
  TableImageGeometry(int angleBins, int numberOfParts)
    : Extent{ 0, angleBins - 1, 0, angleBins - 1, 0, numberOfParts * numberOfParts - 1 }
    , Spacing{ 2.0 * vtkMath::Pi() / angleBins, 2.0 * vtkMath::Pi() / angleBins, 1.0 }
  {
  }
};
} // namespace

using Names = vtkSafeDistanceTableImage;

//------------------------------------------------------------------------------
void vtkSafeDistanceTableImage::ToImage(const gs::SafeDistanceTables& tables, vtkImageData* image)
{
  image->Initialize();
  const int ka = tables.AngleBins, P = tables.NumberOfParts();
  TableImageGeometry geometry(ka, P);
  image->SetExtent(geometry.Extent);
  image->SetSpacing(geometry.Spacing);
  image->SetOrigin(0.0, 0.0, 0.0);
  vtkNew<vtkDoubleArray> values;
  values->SetName(Names::SafeDistance);
  values->SetNumberOfTuples(static_cast<vtkIdType>(tables.Values.size()));
  for (std::size_t k = 0; k < tables.Values.size(); ++k)
  {
    values->SetValue(static_cast<vtkIdType>(k), tables.Values[k]);
  }
  image->GetPointData()->SetScalars(values);

  vtkFieldData* fd = image->GetFieldData();
  vtkNew<vtkStringArray> className;
  className->SetName(Names::ClassName);
  auto classRadius = DoubleArray(Names::ClassRadius, 1);
  auto classCentre = DoubleArray(Names::ClassSourceCentre, 2);
  auto classAspect = DoubleArray(Names::ClassAspectRatio, 1);
  auto classAxis = DoubleArray(Names::ClassMajorAxis, 2);
  auto classParts = IntArray(Names::ClassNumberOfParts);
  for (const gs::SafeDistanceClass& c : tables.Classes)
  {
    className->InsertNextValue(c.Name);
    classRadius->InsertNextValue(c.Radius);
    classCentre->InsertNextTuple2(c.SourceCircle.Centre.x, c.SourceCircle.Centre.y);
    classAspect->InsertNextValue(c.AspectRatio);
    classAxis->InsertNextTuple2(c.MajorAxis.x, c.MajorAxis.y);
    classParts->InsertNextValue(static_cast<int>(c.Parts.size()));
  }
  auto partClass = IntArray(Names::PartClassId);
  auto partIndex = IntArray(Names::PartIndex);
  auto partCentre = DoubleArray(Names::PartCentre, 2);
  auto partRadius = DoubleArray(Names::PartRadius, 1);
  for (const gs::SafeDistancePart& p : tables.Parts)
  {
    partClass->InsertNextValue(p.ClassId);
    partIndex->InsertNextValue(p.Index);
    partCentre->InsertNextTuple2(p.Centre.x, p.Centre.y);
    partRadius->InsertNextValue(p.Radius);
  }
  auto outlinePoints = DoubleArray(Names::OutlinePoints, 2);
  auto ringOffsets = IntArray(Names::OutlineRingOffsets);
  auto ringClass = IntArray(Names::OutlineRingClass);
  for (std::size_t k = 0; k < tables.Classes.size(); ++k)
  {
    for (const auto& ring : tables.Classes[k].Outline.Rings)
    {
      ringOffsets->InsertNextValue(static_cast<int>(outlinePoints->GetNumberOfTuples()));
      ringClass->InsertNextValue(static_cast<int>(k));
      for (const gs::Vec2& q : ring)
      {
        outlinePoints->InsertNextTuple2(q.x, q.y);
      }
    }
  }
  ringOffsets->InsertNextValue(static_cast<int>(outlinePoints->GetNumberOfTuples()));
  auto pairA = IntArray(Names::PairPartA);
  auto pairB = IntArray(Names::PairPartB);
  auto pairStep = DoubleArray(Names::PairDistanceStep, 1);
  for (int a = 0; a < P; ++a)
  {
    for (int b = 0; b < P; ++b)
    {
      pairA->InsertNextValue(a);
      pairB->InsertNextValue(b);
      pairStep->InsertNextValue(tables.Step(a, b));
    }
  }
  for (vtkAbstractArray* a : std::initializer_list<vtkAbstractArray*>{ className, classRadius,
         classCentre, classAspect, classAxis, classParts, partClass, partIndex, partCentre,
         partRadius, pairA, pairB, pairStep, outlinePoints, ringOffsets, ringClass })
  {
    fd->AddArray(a);
  }
  auto single = [fd](vtkSmartPointer<vtkDataArray> a, double v) {
    a->InsertNextTuple1(v);
    fd->AddArray(a);
  };
  single(IntArray(Names::AngleBins), ka);
  single(IntArray(Names::DistanceSteps), tables.DistanceSteps);
  single(IntArray(Names::RotationSamples), tables.RotationSamples);
  single(DoubleArray(Names::Scale, 1), tables.Scale);
}

//------------------------------------------------------------------------------
void vtkSafeDistanceTableImage::SetInformation(
  int angleBins, int numberOfParts, vtkInformation* info)
{
  const TableImageGeometry geometry(angleBins, numberOfParts);
  const double origin[3] = { 0.0, 0.0, 0.0 };
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), geometry.Extent, 6);
  info->Set(vtkDataObject::SPACING(), geometry.Spacing, 3);
  info->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_DOUBLE, 1);
}

//------------------------------------------------------------------------------
gs::Result<gs::SafeDistanceTables> vtkSafeDistanceTableImage::FromImage(vtkImageData* image)
{
  vtkFieldData* fd = image ? image->GetFieldData() : nullptr;
  vtkDataArray* values = image ? image->GetPointData()->GetArray(Names::SafeDistance) : nullptr;
  vtkDataArray* bins = FieldArray(fd, Names::AngleBins, 1);
  vtkDataArray* steps = FieldArray(fd, Names::DistanceSteps, 1);
  vtkDataArray* samples = FieldArray(fd, Names::RotationSamples, 1);
  vtkDataArray* scale = FieldArray(fd, Names::Scale, 1);
  vtkDataArray* classRadius = FieldArray(fd, Names::ClassRadius, 1);
  vtkDataArray* classCentre = FieldArray(fd, Names::ClassSourceCentre, 2);
  vtkDataArray* classAxis = FieldArray(fd, Names::ClassMajorAxis, 2);
  vtkDataArray* classAspect = FieldArray(fd, Names::ClassAspectRatio, 1);
  vtkDataArray* partClass = FieldArray(fd, Names::PartClassId, 1);
  vtkDataArray* partIndex = FieldArray(fd, Names::PartIndex, 1);
  vtkDataArray* partCentre = FieldArray(fd, Names::PartCentre, 2);
  vtkDataArray* partRadius = FieldArray(fd, Names::PartRadius, 1);
  vtkDataArray* outline = FieldArray(fd, Names::OutlinePoints, 2);
  vtkDataArray* ringOffsets = FieldArray(fd, Names::OutlineRingOffsets, 1);
  vtkDataArray* ringClass = FieldArray(fd, Names::OutlineRingClass, 1);
  vtkStringArray* names =
    vtkStringArray::SafeDownCast(fd ? fd->GetAbstractArray(Names::ClassName) : nullptr);
  if (!values || values->GetNumberOfComponents() != 1 || !bins || !steps || !scale ||
    !classRadius || !classAxis || !partClass || !partIndex || !partCentre || !partRadius ||
    !outline || !ringOffsets || !ringClass)
  {
    return gs::Status::Error("the Table input is not the output of MSDT Source (port 0): it "
                             "needs the point array SafeDistance and the field data of the "
                             "classes, parts and outlines");
  }
  gs::SafeDistanceTables tables;
  tables.AngleBins = static_cast<int>(bins->GetComponent(0, 0));
  tables.DistanceSteps = static_cast<int>(steps->GetComponent(0, 0));
  tables.RotationSamples = samples ? static_cast<int>(samples->GetComponent(0, 0)) : 0;
  tables.Scale = scale->GetComponent(0, 0);
  const vtkIdType nc = classRadius->GetNumberOfTuples(), np = partRadius->GetNumberOfTuples();
  if (nc < 1 || np < nc || classAxis->GetNumberOfTuples() != nc ||
    partClass->GetNumberOfTuples() != np || partCentre->GetNumberOfTuples() != np ||
    partIndex->GetNumberOfTuples() != np || tables.AngleBins < 1 ||
    values->GetNumberOfTuples() != np * np * tables.AngleBins * tables.AngleBins)
  {
    return gs::Status::Error("the Table input is inconsistent (numbers of classes, parts, angle "
                             "bins and values do not match)");
  }
  tables.Classes.resize(nc);
  for (vtkIdType k = 0; k < nc; ++k)
  {
    gs::SafeDistanceClass& c = tables.Classes[k];
    c.Name = names && k < names->GetNumberOfValues() ? names->GetValue(k) : "class " + std::to_string(k);
    c.Radius = classRadius->GetComponent(k, 0);
    c.MajorAxis = gs::Vec2{ classAxis->GetComponent(k, 0), classAxis->GetComponent(k, 1) };
    c.AspectRatio = classAspect && k < classAspect->GetNumberOfTuples() ? classAspect->GetComponent(k, 0) : 1.0;
    if (classCentre && k < classCentre->GetNumberOfTuples())
    {
      c.SourceCircle.Centre = gs::Vec2{ classCentre->GetComponent(k, 0), classCentre->GetComponent(k, 1) };
    }
  }
  tables.Parts.resize(np);
  for (vtkIdType p = 0; p < np; ++p)
  {
    gs::SafeDistancePart& part = tables.Parts[p];
    part.ClassId = static_cast<int>(partClass->GetComponent(p, 0));
    part.Index = static_cast<int>(partIndex->GetComponent(p, 0));
    part.Centre = gs::Vec2{ partCentre->GetComponent(p, 0), partCentre->GetComponent(p, 1) };
    part.Radius = partRadius->GetComponent(p, 0);
    if (part.ClassId < 0 || part.ClassId >= nc)
    {
      return gs::Status::Error("the Table input has a part of an unknown class");
    }
    tables.Classes[part.ClassId].Parts.push_back(static_cast<int>(p));
  }
  const vtkIdType rings = ringClass->GetNumberOfTuples();
  if (ringOffsets->GetNumberOfTuples() != rings + 1)
  {
    return gs::Status::Error("the Table input's outline rings are inconsistent");
  }
  for (vtkIdType r = 0; r < rings; ++r)
  {
    const int k = static_cast<int>(ringClass->GetComponent(r, 0));
    const vtkIdType from = static_cast<vtkIdType>(ringOffsets->GetComponent(r, 0));
    const vtkIdType to = static_cast<vtkIdType>(ringOffsets->GetComponent(r + 1, 0));
    if (k < 0 || k >= nc || from < 0 || to < from || to > outline->GetNumberOfTuples())
    {
      return gs::Status::Error("the Table input's outline rings are inconsistent");
    }
    std::vector<gs::Vec2> ring;
    for (vtkIdType i = from; i < to; ++i)
    {
      ring.emplace_back(outline->GetComponent(i, 0), outline->GetComponent(i, 1));
    }
    tables.Classes[k].Outline.Rings.push_back(std::move(ring));
  }
  tables.Values.resize(static_cast<std::size_t>(values->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    tables.Values[static_cast<std::size_t>(i)] = values->GetComponent(i, 0);
  }
  return tables;
}
