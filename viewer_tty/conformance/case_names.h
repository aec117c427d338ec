// SPDX-License-Identifier: MIT
// case_names.h — the spelling of every enum value in gl_ref_case/1 files (filters, wraps, blend
// factors and equations, texel and colour formats, depth formats and functions), shared by the case
// reader and writer so the two cannot drift apart. Conventions: lowercase GL names without the GL_
// prefix, e.g. "linear_mipmap_nearest". Not here: parsing or error reporting (case_file.cpp).
#pragma once

#include <array>
#include <string_view>
#include <utility>

#include "raster/frame.h"

namespace pem::conformance {

struct MinFilterName {
    std::string_view name;
    raster::Filter filter;
    raster::MipFilter mip;
};

inline constexpr std::array<MinFilterName, 6> kMinFilterNames = {{
    {"nearest", raster::Filter::Nearest, raster::MipFilter::None},
    {"linear", raster::Filter::Linear, raster::MipFilter::None},
    {"nearest_mipmap_nearest", raster::Filter::Nearest, raster::MipFilter::Nearest},
    {"linear_mipmap_nearest", raster::Filter::Linear, raster::MipFilter::Nearest},
    {"nearest_mipmap_linear", raster::Filter::Nearest, raster::MipFilter::Linear},
    {"linear_mipmap_linear", raster::Filter::Linear, raster::MipFilter::Linear},
}};

template <class E>
using NameTable = std::pair<std::string_view, E>;

inline constexpr std::array<NameTable<raster::Filter>, 2> kMagFilterNames = {{
    {"nearest", raster::Filter::Nearest},
    {"linear", raster::Filter::Linear},
}};

inline constexpr std::array<NameTable<raster::Wrap>, 3> kWrapNames = {{
    {"clamp_to_edge", raster::Wrap::ClampToEdge},
    {"repeat", raster::Wrap::Repeat},
    {"mirrored_repeat", raster::Wrap::MirroredRepeat},
}};

inline constexpr std::array<NameTable<raster::BlendFactor>, 11> kBlendFactorNames = {{
    {"zero", raster::BlendFactor::Zero},
    {"one", raster::BlendFactor::One},
    {"src_color", raster::BlendFactor::SrcColor},
    {"one_minus_src_color", raster::BlendFactor::OneMinusSrcColor},
    {"dst_color", raster::BlendFactor::DstColor},
    {"one_minus_dst_color", raster::BlendFactor::OneMinusDstColor},
    {"src_alpha", raster::BlendFactor::SrcAlpha},
    {"one_minus_src_alpha", raster::BlendFactor::OneMinusSrcAlpha},
    {"dst_alpha", raster::BlendFactor::DstAlpha},
    {"one_minus_dst_alpha", raster::BlendFactor::OneMinusDstAlpha},
    {"src_alpha_saturate", raster::BlendFactor::SrcAlphaSaturate},
}};

inline constexpr std::array<NameTable<raster::BlendEquation>, 5> kBlendEquationNames = {{
    {"add", raster::BlendEquation::Add},
    {"subtract", raster::BlendEquation::Subtract},
    {"reverse_subtract", raster::BlendEquation::ReverseSubtract},
    {"min", raster::BlendEquation::Min},
    {"max", raster::BlendEquation::Max},
}};

// A texture's `internal_format` and the frame's `color_format`.
inline constexpr auto kTexelFormatNames = raster::kTexelFormatNames;  // one spelling everywhere

inline constexpr std::array<NameTable<raster::ColorFormat>, 2> kColorFormatNames = {{
    {"rgba8", raster::ColorFormat::Rgba8},
    {"rgba32f", raster::ColorFormat::Rgba32F},
}};

inline constexpr std::array<NameTable<raster::DepthFormat>, 3> kDepthFormatNames = {{
    {"z16", raster::DepthFormat::Z16},
    {"z24", raster::DepthFormat::Z24},
    {"z32f", raster::DepthFormat::Z32F},
}};

inline constexpr std::array<NameTable<raster::DepthFunc>, 8> kDepthFuncNames = {{
    {"never", raster::DepthFunc::Never},
    {"less", raster::DepthFunc::Less},
    {"equal", raster::DepthFunc::Equal},
    {"lequal", raster::DepthFunc::LEqual},
    {"greater", raster::DepthFunc::Greater},
    {"notequal", raster::DepthFunc::NotEqual},
    {"gequal", raster::DepthFunc::GEqual},
    {"always", raster::DepthFunc::Always},
}};

// The name of `value` in `table` (every enum value is present).
template <class E, size_t N>
constexpr std::string_view NameOf(const std::array<NameTable<E>, N>& table, E value) {
    for (const auto& entry : table)
        if (entry.second == value) return entry.first;
    return {};
}

}  // namespace pem::conformance
