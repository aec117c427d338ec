// SPDX-License-Identifier: MIT
// ray.cpp — the angle between two directions.
#include "trace/ray.h"

#include <cmath>
#include <numbers>

namespace pem::trace {

double AngleBetweenDeg(const glm::dvec3& a, const glm::dvec3& b) {
    const double radians = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
    return radians * (180.0 / std::numbers::pi);
}

}  // namespace pem::trace
