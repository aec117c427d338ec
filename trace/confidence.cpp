// SPDX-License-Identifier: MIT
// confidence.cpp — per-pixel confidence from the spread of exit-ray directions.
#include "trace/confidence.h"

#include <algorithm>
#include <cassert>

#include "trace/ray.h"

namespace pem::trace {

double Confidence(double thetaMaxDeg, double thetaCDeg) {
    const double m = std::min(thetaMaxDeg, thetaCDeg);
    return 1.0 - (m * m) / (thetaCDeg * thetaCDeg);
}

double MaxPairAngleDeg(std::span<const glm::vec3> dirs) {
    double maxAngle = 0.0;
    for (size_t i = 0; i < dirs.size(); ++i) {
        if (dirs[i] == glm::vec3(0.0f)) continue;
        for (size_t j = i + 1; j < dirs.size(); ++j) {
            if (dirs[j] == glm::vec3(0.0f)) continue;
            maxAngle =
                std::max(maxAngle, AngleBetweenDeg(glm::dvec3(dirs[i]), glm::dvec3(dirs[j])));
        }
    }
    return maxAngle;
}

double PixelConfidence(std::span<const glm::vec3> dirs, double thetaCDeg) {
    const bool any = std::any_of(dirs.begin(), dirs.end(),
                                 [](const glm::vec3& d) { return d != glm::vec3(0.0f); });
    if (!any) return 0.0;
    return Confidence(MaxPairAngleDeg(dirs), thetaCDeg);
}

ConfidenceImage MakeConfidenceImage(int width, int height, int samplesPerPixel,
                                    std::span<const glm::vec3> dirs, double thetaCDeg) {
    const auto spp = static_cast<size_t>(samplesPerPixel);
    const auto nPixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    assert(dirs.size() == nPixels * spp);
    ConfidenceImage image{width, height, std::vector<float>(nPixels, 0.0f)};
    for (size_t p = 0; p < nPixels; ++p) {
        const double c = PixelConfidence(dirs.subspan(p * spp, spp), thetaCDeg);
        image.values[p] = static_cast<float>(c);
    }
    return image;
}

}  // namespace pem::trace
