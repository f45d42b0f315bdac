/**
 * @class   vtkSafeDistanceTableImage
 * @brief   The one definition of MSDT Source's tables image: gs::SafeDistanceTables <-> vtkImageData.
 *
 * MSDT Source writes its port 0 with ToImage; Shape Distributor reads its Table input with
 * FromImage. Layout: an image of AngleBins x AngleBins x P^2 points (P parts in all; the table of
 * the ordered pair of parts (a, b) is slice z = a * P + b, x the bin of a's angle, y of b's), the
 * double point array SafeDistance (the active scalars), and field data describing the classes,
 * parts, pairs and outlines (the names below). Private to the module (not wrapped).
 */
#ifndef vtkSafeDistanceTableImage_h
#define vtkSafeDistanceTableImage_h

#include "SafeDistanceTable.h" // for gs::SafeDistanceTables
#include "Status.h"            // for gs::Result

class vtkImageData;
class vtkInformation;

class vtkSafeDistanceTableImage
{
public:
  // Point data.
  static constexpr const char* SafeDistance = "SafeDistance";
  // Field data: one tuple per class.
  static constexpr const char* ClassName = "ClassName"; // string
  static constexpr const char* ClassRadius = "ClassRadius";
  static constexpr const char* ClassSourceCentre = "ClassSourceCentre"; // 2 components
  static constexpr const char* ClassAspectRatio = "ClassAspectRatio";
  static constexpr const char* ClassMajorAxis = "ClassMajorAxis"; // 2 components
  static constexpr const char* ClassNumberOfParts = "ClassNumberOfParts";
  // One tuple per part.
  static constexpr const char* PartClassId = "PartClassId";
  static constexpr const char* PartIndex = "PartIndex";
  static constexpr const char* PartCentre = "PartCentre"; // 2 components
  static constexpr const char* PartRadius = "PartRadius";
  // One tuple per ordered pair of parts (a, b), a * P + b.
  static constexpr const char* PairPartA = "PairPartA";
  static constexpr const char* PairPartB = "PairPartB";
  static constexpr const char* PairDistanceStep = "PairDistanceStep";
  // The class outlines (normalized units, class frame): ring r of class OutlineRingClass[r] holds
  // points OutlineRingOffsets[r] .. OutlineRingOffsets[r + 1] - 1 of OutlinePoints.
  static constexpr const char* OutlinePoints = "OutlinePoints"; // 2 components
  static constexpr const char* OutlineRingOffsets = "OutlineRingOffsets";
  static constexpr const char* OutlineRingClass = "OutlineRingClass";
  // Single values.
  static constexpr const char* AngleBins = "AngleBins";
  static constexpr const char* DistanceSteps = "DistanceSteps";
  static constexpr const char* RotationSamples = "RotationSamples";
  static constexpr const char* Scale = "Scale";

  /// Writes `tables` into `image` (its previous content is replaced).
  static void ToImage(const gs::SafeDistanceTables& tables, vtkImageData* image);

  /// Describes the image that ToImage will write for tables of `angleBins` bins and
  /// `numberOfParts` parts in an output port's information (whole extent, spacing, origin, scalar
  /// type), for a RequestInformation pass, before the tables are computed.
  static void SetInformation(int angleBins, int numberOfParts, vtkInformation* info);

  /// Reads `image` back; fails, naming what is missing or inconsistent, when it is not such an
  /// image.
  static gs::Result<gs::SafeDistanceTables> FromImage(vtkImageData* image);
};

#endif
// VTK-HeaderTest-Exclude: vtkSafeDistanceTableImage.h
