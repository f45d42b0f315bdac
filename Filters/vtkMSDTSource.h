/**
 * @class vtkMSDTSource
 * @brief Minimum safe distance tables (MSDT) between 2D shapes read from images or polygons.
 *
 * Each shape is one class: the silhouette of an image (ShapeFileNames; read with OpenImageIO:
 * PNG, JPEG, TIFF, EXR, ...; inside = alpha >= AlphaThreshold, or for images without alpha,
 * luminance < LuminanceThreshold; pixel rows are flipped so y is up) or closed polygons on the
 * optional input port. For every ordered pair of shapes (parts, see below) and every pair of
 * angle bins it computes the smallest centre distance at which the two shapes cannot overlap
 * (Wang et al. 2016, Sec. 4.2, Algorithm 1), conservative over whole angle bins:
 * Filters/Core/Shapes/SafeDistanceTable.h states the exact convention. In short: shape A at the origin
 * rotated by alpha_A about its circle centre, B at (d, 0) rotated by alpha_B; bin i is centred on
 * i * 2pi / AngleBins; for all angles in bins (i, j) and every d >= SafeDistance(i, j) the
 * interiors are disjoint. Values are multiples of (r_A + r_B) / DistanceSteps, at most r_A + r_B.
 *
 * Units: pixels (images) or polygon units, divided by the circumradius of the FIRST class (image
 * classes first, in ShapeFileNames order, then polygon classes): that class has radius 1.
 * Long shapes (aspect ratio above MaximumAspectRatio) are cut across their major axis into equal
 * parts, each with its own circle and tables (Fig. 7 of the paper).
 *
 * Input port 0 (optional vtkPolyData; in ParaView the "Input" of the filter proxy MSDT From
 * Polygons, while the MSDT Source proxy has no input): polygon and polyline cells in the XY plane (z
 * ignored), each a closed ring (a repeated last point is dropped). Rings with the same value of
 * an integer cell array "ClassId" form one class (even-odd rule: holes allowed); without that
 * array every cell is its own class.
 *
 * Output port 0 (vtkImageData): AngleBins x AngleBins x P^2 points (P: number of parts of all
 * classes), point array "SafeDistance" (double; x index i = bin of alpha_A, y index j = bin of
 * alpha_B, z index = pair a * P + b; spacing (bin width in radians, same, 1)). Field data:
 * ClassName, ClassRadius, ClassSourceCentre (circle centre in pixels / polygon units),
 * ClassAspectRatio, ClassMajorAxis, ClassNumberOfParts; PartClassId, PartIndex, PartCentre
 * (in the class frame: origin at the class circle centre, normalized units), PartRadius;
 * PairPartA, PairPartB, PairDistanceStep (per z slice); AngleBins, DistanceSteps,
 * RotationSamples, Scale (source units per normalized unit); the outlines as OutlinePoints
 * (2 components, normalized class frame), OutlineRingOffsets (one per ring plus the end) and
 * OutlineRingClass (one per ring): Shape Distributor needs only this port.
 * Output port 1 (vtkPolyData): the outlines as closed polylines, one cell per contour, in
 * normalized units with each class centred on its circle centre; cell array "ClassId".
 * Output port 2 (vtkImageData): the silhouettes, TextureSize x TextureSize, one unsigned char
 * component per class in point array "Silhouette" (255 inside); pixel (u, v) of class k samples
 * the class point r_k ((2u + 1) / T - 1, (2v + 1) / T - 1): the square around its circle, ready
 * to use as a decal texture. Geometry: origin (-1 + 1/T, -1 + 1/T), spacing 2/T.
 *
 * Pipeline: RequestInformation reads the shapes and splits them into parts, so the whole extent
 * of every image output is known up front (downstream image filters see ka x ka x P^2); the
 * classes and parts are cached and reused (RequestData does not read again) until a file name,
 * a file's modification time or size, the polygons input, a threshold or MaximumAspectRatio
 * changes. When port 0 is connected its upstream is brought up to date during the
 * information pass (the number of parts depends on it). Open polylines on that port (last point
 * not equal to the first) are closed, with a warning.
 *
 * Errors (vtkErrorMacro, empty outputs and empty whole extents): no shape, unreadable / empty / all-transparent /
 * all-opaque images, AngleBins outside [1, 4096], DistanceSteps outside [1, 4096],
 * MaximumAspectRatio < 1, thresholds outside [0, 1], TextureSize outside [1, 8192].
 * Progress is reported and the computation can be aborted.
 *
 * Example (pvpython):
 * @code
 * msdt = MSDTSource(ShapeFileNames=["star.png", "fish.png"], AngleBins=64, DistanceSteps=64)
 * @endcode
 */
#ifndef vtkMSDTSource_h
#define vtkMSDTSource_h

#include "GeodesicShapesFiltersModule.h" // for export macro
#include "vtkAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string
#include <vector> // for std::vector

class vtkImageData;
class vtkPolyData;

class GEODESICSHAPESFILTERS_EXPORT vtkMSDTSource : public vtkAlgorithm
{
public:
  static vtkMSDTSource* New();
  vtkTypeMacro(vtkMSDTSource, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Image files, one class each (in this order, before polygon classes).
  void AddShapeFileName(const char* fileName);
  void RemoveAllShapeFileNames();
  int GetNumberOfShapeFileNames() const { return static_cast<int>(this->ShapeFileNames.size()); }
  const char* GetShapeFileName(int i) const { return this->ShapeFileNames[i].c_str(); }
  ///@}

  ///@{
  /// ka: angle bins per shape. Default 64.
  vtkSetMacro(AngleBins, int);
  vtkGetMacro(AngleBins, int);
  ///@}

  ///@{
  /// kr: distance steps between 0 and r_A + r_B. Default 64.
  vtkSetMacro(DistanceSteps, int);
  vtkGetMacro(DistanceSteps, int);
  ///@}

  ///@{
  /// Images with alpha: inside where alpha >= AlphaThreshold (0..1). Default 0.5.
  vtkSetMacro(AlphaThreshold, double);
  vtkGetMacro(AlphaThreshold, double);
  ///@}

  ///@{
  /// Images without alpha: inside where luminance < LuminanceThreshold (0..1). Default 0.5.
  vtkSetMacro(LuminanceThreshold, double);
  vtkGetMacro(LuminanceThreshold, double);
  ///@}

  ///@{
  /// Shapes with a larger aspect ratio are split into parts. Default 2 (at least 1).
  vtkSetMacro(MaximumAspectRatio, double);
  vtkGetMacro(MaximumAspectRatio, double);
  ///@}

  ///@{
  /// Side of the silhouette images of output port 2. Default 256.
  vtkSetMacro(TextureSize, int);
  vtkGetMacro(TextureSize, int);
  ///@}

  /// Connect the optional polygons (port 0).
  void SetPolygonsConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(0, output); }
  void SetPolygonsData(vtkDataObject* data) { this->SetInputDataObject(0, data); }

  vtkImageData* GetTablesOutput();
  vtkPolyData* GetOutlinesOutput();
  vtkImageData* GetSilhouettesOutput();

  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

protected:
  vtkMSDTSource();
  ~vtkMSDTSource() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector);
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector);

private:
  vtkMSDTSource(const vtkMSDTSource&) = delete;
  void operator=(const vtkMSDTSource&) = delete;

  /// Reads and splits the shapes unless the cache already holds them for the current inputs.
  void UpdateShapes(vtkInformationVector** inputVector);

  struct ShapeCache; // classes and parts of the last read, with what they were read from
  std::unique_ptr<ShapeCache> Shapes;
  // How many times the shapes were read and split into parts since construction (at most once
  // per change of their inputs, see the class comment): read by the tests' seam.
  int NumberOfShapeLoads = 0;
  friend struct vtkMSDTSourceInspector;

  std::vector<std::string> ShapeFileNames;
  int AngleBins = 64;
  int DistanceSteps = 64;
  double AlphaThreshold = 0.5;
  double LuminanceThreshold = 0.5;
  double MaximumAspectRatio = 2.0;
  int TextureSize = 256;
};

#endif
