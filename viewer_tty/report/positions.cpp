// SPDX-License-Identifier: MIT
// positions.cpp — the report's three camera positions (positions.h).
#include "viewer_tty/report/positions.h"

#include <cmath>

#include "trace/scene.h"

namespace pem::report {
namespace {

// Azimuth of an eye about the lens centre (radians, from +Z toward +X).
double Azimuth(const glm::vec3& eye, const glm::vec3& centre) {
    return std::atan2(static_cast<double>(eye.x - centre.x), static_cast<double>(eye.z - centre.z));
}

}  // namespace

// On the circle at the first sample, halfway to the next sample, and 10° above that.
std::vector<Position> Positions(const runtime::Renderer& renderer) {
    const runtime::MapSet& maps = renderer.maps();
    const glm::vec3 centre = trace::LensCentre(renderer.scene());
    const int s0 = maps.inferred.front();
    double step = 10.0;
    if (maps.inferred.size() > 1) {
        const double d = Azimuth(maps.samples[static_cast<size_t>(maps.inferred[1])].eye, centre) -
                         Azimuth(maps.samples[static_cast<size_t>(s0)].eye, centre);
        step = glm::degrees(std::remainder(d, 2.0 * M_PI));
    }
    return {{"on circle", "on_circle", renderer.SampleCamera(s0)},
            {"between samples", "between", renderer.Orbit(step / 2.0, 0.0, 1.0)},
            {"10° above", "above", renderer.Orbit(step / 2.0, 10.0, 1.0)}};
}

}  // namespace pem::report
