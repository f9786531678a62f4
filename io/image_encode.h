#pragma once
// A frame encoded in memory for the service (PNG or JPEG bytes to send, not a file to write).
#include <string>

#include <glm/glm.hpp>

#include "io/image.h"

namespace sortlast {

// The premultiplied frame composited over `background` exactly as writeImage does, encoded as
// opaque RGB: format "png" (fast compression, lossless) or "jpeg" (quality 1-100). Throws
// InputError for another format or a quality out of range.
std::string encodeImage(const ImageRGBA8& img, const glm::dvec3& background,
                        const std::string& format, int quality = 90);

}  // namespace sortlast
