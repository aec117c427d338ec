// SPDX-License-Identifier: MIT
// profile.cpp — the profile table (profile.h).
#include "raster/profile.h"

#include <array>
#include <stdexcept>

namespace pem::raster {
namespace {

RenderOptions With(Profile p, UnormRounding r, CubeLod lod) {
    RenderOptions o;
    o.profile = p;
    o.rounding = r;
    o.cubeLod = lod;
    return o;
}

// An llvmpipe profile: its rendering matrix comes from the linear profile with its LOD rule
// (llvmpipe's 8-bit filter paths round; the matrix holds their exact weights).
ProfileInfo LlvmpipeBased(const char* name, const char* model, UnormRounding r, CubeLod lod) {
    return {name, model, With(Profile::Llvmpipe, r, lod), With(Profile::Linear, r, lod)};
}

const std::array<ProfileInfo, 5> kProfiles = {{
    LlvmpipeBased("llvmpipe", "Mesa 22.3.6 llvmpipe (Debian 12), bit for bit",
                  UnormRounding::HalfEven, CubeLod::Llvmpipe),
    {"linear", "pemref linear: llvmpipe's texel selection with exact weights, float framebuffer",
     With(Profile::Linear, UnormRounding::HalfEven, CubeLod::Llvmpipe),
     With(Profile::Linear, UnormRounding::HalfEven, CubeLod::Llvmpipe)},
    LlvmpipeBased("exact-lod", "Mesa 22.3.6 llvmpipe with the GL specification's exact cube LOD",
                  UnormRounding::HalfEven, CubeLod::Exact),
    LlvmpipeBased("d3d-rounding", "Mesa 22.3.6 llvmpipe with Direct3D's float to unorm8 rounding",
                  UnormRounding::HalfUp, CubeLod::Llvmpipe),
    // softpipe filters in float: its own frame is linear in the texels up to the final rounding.
    {"softpipe", "Mesa 22.3.6 softpipe (Debian 12), bit for bit",
     With(Profile::Softpipe, UnormRounding::HalfEven, CubeLod::Llvmpipe),
     With(Profile::Softpipe, UnormRounding::HalfEven, CubeLod::Llvmpipe)},
}};

}  // namespace

std::span<const ProfileInfo> Profiles() {
    return kProfiles;
}

const ProfileInfo& ProfileNamed(const std::string& name) {
    for (const ProfileInfo& p : kProfiles)
        if (name == p.name) return p;
    throw std::invalid_argument("unknown profile \"" + name + "\" (" + ProfileNames() + ")");
}

std::string ProfileNames() {
    std::string out;
    for (const ProfileInfo& p : kProfiles) out += (out.empty() ? "" : ", ") + std::string(p.name);
    return out;
}

}  // namespace pem::raster
