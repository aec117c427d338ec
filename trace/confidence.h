// SPDX-License-Identifier: MIT
// confidence.h — the hybrid paper's per-pixel confidence (§4.3):
//     c = 1 - min(theta_m, theta_c)^2 / theta_c^2,
// theta_m the maximum angle between any pair of exit-ray directions contributing to the pixel (its
// supersamples), theta_c = 5 degrees: c = 1 for parallel rays, 0 at and beyond theta_c. Degrees.
//
// Image layout: row-major, top-left origin, `samplesPerPixel` consecutive directions per pixel. A
// zero direction marks a sub-sample without an exit ray (skipped); a pixel with no exit ray at all
// gets confidence 0, one with a single exit ray gets 1.
//
// Not here: the confidence of direct images (distance to the lens images' records), weighting A, b.
#pragma once

#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace pem::trace {

constexpr double kConfidenceThetaCDeg = 5.0;

double Confidence(double thetaMaxDeg, double thetaCDeg = kConfidenceThetaCDeg);

// Maximum angle in degrees between any two of the non-zero directions (0 if fewer than two).
double MaxPairAngleDeg(std::span<const glm::vec3> dirs);

double PixelConfidence(std::span<const glm::vec3> dirs, double thetaCDeg = kConfidenceThetaCDeg);

struct ConfidenceImage {
    int width = 0;
    int height = 0;
    std::vector<float> values;  // row-major, top-left origin
    bool operator==(const ConfidenceImage&) const = default;
};

ConfidenceImage MakeConfidenceImage(int width, int height, int samplesPerPixel,
                                    std::span<const glm::vec3> dirs,
                                    double thetaCDeg = kConfidenceThetaCDeg);

}  // namespace pem::trace
