// Silhouette images as shape classes of one size, for the tests and benchmarks that distribute
// the bundled (or any) silhouettes side by side.
#pragma once

#include "Silhouette.h"
#include "Status.h"

#include <string>

namespace gs
{

// The silhouette of an image (ReadSilhouetteImage, ShapeFromMask) moved and scaled so that its
// smallest enclosing circle is the unit circle. Fails as ReadSilhouetteImage does.
Result<Shape2D> UnitShapeFromImage(const std::string& file);

} // namespace gs
