// SPDX-License-Identifier: MIT
// ray.h — trace/'s Ray (an alias of raster/camera.h's, so camera rays feed the tracer unchanged)
// and the angle between two directions. A Ray has a float origin and direction; `dir` need not be
// unit length unless a function says so. Code that needs accuracy converts to double (glm::dvec3).
// Not here: cameras and pixel rays (raster/camera.h).
#pragma once

#include <glm/glm.hpp>

#include "raster/camera.h"

namespace pem::trace {

using Ray = raster::Ray;

// Angle between two non-zero directions in degrees, in [0, 180]. atan2(|a×b|, a·b) in double, which
// stays accurate for nearly parallel directions (acos of a dot product does not).
double AngleBetweenDeg(const glm::dvec3& a, const glm::dvec3& b);

}  // namespace pem::trace
