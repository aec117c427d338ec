// SPDX-License-Identifier: MIT
// args.h — option values the commands share: image sizes, viewpoints and methods, and the
// progress line every long job shows.
//
//   auto [w, h] = ParseSize("640x480");
//   raster::Camera c = ParseViewSpec(renderer, "orbit:5:10:1", w, h);
//
// Errors: base::InputError naming the option and what it expects.
#pragma once

#include <functional>
#include <string>
#include <utility>

#include "raster/camera.h"
#include "runtime/renderer.h"
#include "viewer_tty/tty/progress.h"

namespace pem::cli {

// "WxH" → (W, H), both in [1, 16384].
std::pair<int, int> ParseSize(const std::string& text);

// hybrid | pem | static | traced.
runtime::Method ParseMethod(const std::string& name);

// sample:I (the camera sample I was traced with), orbit:AZ:EL:DIST (degrees added to the first
// sample's azimuth and elevation about the lens centre, DIST scales its distance) or camera
// (the scene's camera), at the given size.
raster::Camera ParseViewSpec(const runtime::Renderer& renderer, const std::string& spec, int width,
                             int height);

// A job's progress callback that draws `line` (nothing when the line is disabled).
std::function<void(const std::string&, double)> ProgressTo(tty::ProgressLine* line);

}  // namespace pem::cli
