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

const std::array<ProfileInfo, 5> kProfiles = {{
    {"llvmpipe", "Mesa 22.3.6 llvmpipe (Debian 12), bit for bit",
     With(Profile::Llvmpipe, UnormRounding::HalfEven, CubeLod::Llvmpipe)},
    {"linear", "pemref linear: llvmpipe's texel selection with exact weights, float framebuffer",
     With(Profile::Linear, UnormRounding::HalfEven, CubeLod::Llvmpipe)},
    {"exact-lod", "Mesa 22.3.6 llvmpipe with the GL specification's exact cube LOD",
     With(Profile::Llvmpipe, UnormRounding::HalfEven, CubeLod::Exact)},
    {"d3d-rounding", "Mesa 22.3.6 llvmpipe with Direct3D's float to unorm8 rounding",
     With(Profile::Llvmpipe, UnormRounding::HalfUp, CubeLod::Llvmpipe)},
    {"softpipe",
     "Mesa 22.3.6 softpipe (Debian 12), bit for bit where modelled: geometry, interpolation, "
     "blending; uniform textures only, no depth buffer yet",
     With(Profile::Softpipe, UnormRounding::HalfEven, CubeLod::Llvmpipe), true},
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
