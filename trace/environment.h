// SPDX-License-Identifier: MIT
// environment.h — the radiance at infinity (scene extras `pemref_environment`), read from an
// OpenEXR file into float RGB and looked up by direction.
//
// Conventions:
//  - LatLong (data/README.md; OpenEXR's LatLongMap orientation, pixel-edge form): row 0 is +Y,
//    the centre column looks along +Z; for a unit direction d
//        u = 0.5 − atan2(d.x, d.z) / (2π),  v = 0.5 − asin(d.y) / π,
//    continuous pixel position (u·W, v·H), texel centres at (i + 0.5). Bilinear; columns wrap,
//    rows clamp.
//  - Cube: OpenEXR's cube layout (N wide, 6N tall, faces +X −X +Y −Y +Z −Z stacked vertically)
//    with Imf::CubeMap's face orientation. Bilinear inside a face, clamped at face edges (not
//    seamless).
//  - Radiance = texel RGB × intensity. Negative texels are clamped to 0 at load; NaN/Inf texels
//    are an input error. A default Environment (Mapping::None) is black.
// Not here: MIP levels, importance sampling.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace pem::trace {

struct Environment {
    enum class Mapping { None, LatLong, Cube };
    Mapping mapping = Mapping::None;
    std::string path;           // the EXR file (for messages)
    int width = 0, height = 0;  // of the whole image (cube: N by 6N)
    std::vector<float> rgb;     // width · height · 3, rows top-down
    float intensity = 1.0f;
    bool operator==(const Environment&) const = default;
};

// Reads an OpenEXR file (any compression RgbaInputFile handles, e.g. DWAB half). Throws
// pem::base::InputError("<path>: <cause>") when it is unreadable, too large, non-finite, or the
// wrong shape for a cube map.
Environment LoadEnvironment(const std::string& exrPath, Environment::Mapping mapping,
                            float intensity);

// Radiance arriving from direction `dir` (any length > 0); black for Mapping::None.
glm::vec3 EnvRadiance(const Environment& env, const glm::vec3& dir);

}  // namespace pem::trace
