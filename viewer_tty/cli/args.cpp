// SPDX-License-Identifier: MIT
// args.cpp — shared option parsing (args.h).
#include "viewer_tty/cli/args.h"

#include <cmath>
#include <cstdio>

#include "base/input_error.h"

namespace pem::cli {

std::pair<int, int> ParseSize(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 1 ||
        h < 1 || w > 16384 || h > 16384)
        throw base::InputError("--size " + text, "expected WxH, e.g. 640x480");
    return {w, h};
}

runtime::Method ParseMethod(const std::string& name) {
    if (name == "hybrid") return runtime::Method::Hybrid;
    if (name == "pem") return runtime::Method::Pem;
    if (name == "static") return runtime::Method::StaticEm;
    if (name == "traced") return runtime::Method::RayTraced;
    throw base::InputError("--method " + name, "expected hybrid, pem, static or traced");
}

raster::Camera ParseViewSpec(const runtime::Renderer& renderer, const std::string& spec, int width,
                             int height) {
    raster::Camera c;
    int index = 0;
    double az = 0, el = 0, dist = 1;
    char extra = 0;
    if (spec == "camera") {
        if (!renderer.scene().camera)
            throw base::InputError("--view camera", "the scene has no camera");
        c = trace::CameraForSize(*renderer.scene().camera, width, height);
    } else if (std::sscanf(spec.c_str(), "sample:%d%c", &index, &extra) == 1) {
        if (index < 0 || index >= static_cast<int>(renderer.maps().samples.size()))
            throw base::InputError("--view " + spec, "no such viewpoint sample");
        c = renderer.SampleCamera(index);
    } else if (std::sscanf(spec.c_str(), "orbit:%lf:%lf:%lf%c", &az, &el, &dist, &extra) == 3 &&
               std::isfinite(az) && std::isfinite(el) && std::isfinite(dist) && dist > 0.0) {
        c = renderer.Orbit(az, el, dist);
    } else {
        throw base::InputError("--view " + spec, "expected sample:I, orbit:AZ:EL:DIST or camera");
    }
    c.width = width;
    c.height = height;
    return c;
}

std::function<void(const std::string&, double)> ProgressTo(tty::ProgressLine* line) {
    if (!line->Enabled()) return {};
    return [line](const std::string&, double f) { line->Update(f); };
}

}  // namespace pem::cli
