// SPDX-License-Identifier: MIT
// profile.h — the hardware profiles by name and what each one models: the one table the command
// line (--profile, --version), the golden images and the manifests read.
//
//   const ProfileInfo& p = ProfileNamed("llvmpipe");   // p.options, p.model
//
// A profile is a set of RenderOptions: `llvmpipe` (Mesa 22.3.6 llvmpipe, bit for bit), `linear`
// (the same texel selection and weights without rounding, a float framebuffer: the rendering
// matrix's profile), `softpipe` (Mesa 22.3.6 softpipe: softpipe_render.h), and the
// variants `exact-lod` (GL-spec log2 for the cube LOD) and `d3d-rounding` (float → unorm8 by
// floor(x + 0.5)), which span what conformant hardware may do. Not here: the rules themselves
// (render.h and docs/raster-model.md).
#pragma once

#include <span>
#include <string>

#include "raster/render.h"

namespace pem::raster {

struct ProfileInfo {
    const char* name;       // as --profile takes it
    const char* model;      // what it reproduces, with the version
    RenderOptions options;  // how it renders
    // How its rendering matrix is built (BuildRenderingMatrix): the texel selection and weights
    // its frames are linear in. llvmpipe's: the linear profile with the same LOD rule; softpipe's:
    // itself (float filtering).
    RenderOptions matrix;
};

// Every profile, llvmpipe first.
std::span<const ProfileInfo> Profiles();

// The profile called `name`; throws std::invalid_argument listing the names otherwise.
const ProfileInfo& ProfileNamed(const std::string& name);

// "llvmpipe, linear, exact-lod, d3d-rounding, softpipe".
std::string ProfileNames();

}  // namespace pem::raster
