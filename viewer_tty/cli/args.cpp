// SPDX-License-Identifier: MIT
// args.cpp — shared option parsing (args.h).
#include "viewer_tty/cli/args.h"

#include <cmath>
#include <cstdio>

#include "base/input_error.h"
#include "raster/profile.h"

#ifndef PEM_VERSION
#define PEM_VERSION "unknown"
#endif

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

std::string PemrefVersion() {
    return PEM_VERSION;
}

std::string VersionText() {
    std::string text = "pemref " + PemrefVersion() + "\nprofiles:";
    for (const raster::ProfileInfo& p : raster::Profiles())
        text += std::string("\n  ") + p.name + ": " + p.model;
    return text;
}

void AddProfileOption(CLI::App* sub, std::string* profile) {
    sub->add_option("--profile", *profile, "hardware profile: " + raster::ProfileNames())
        ->check([](const std::string& name) -> std::string {
            try {
                raster::ProfileNamed(name);
                return "";
            } catch (const std::invalid_argument& e) {
                return e.what();
            }
        });
}

void AddMapSizeOptions(CLI::App* sub, int* res, int* maxRes) {
    sub->add_option("--res", *res,
                    "map size N (power of two): a cube's face size, a 2D layout's height");
    sub->add_option("--max-res", *maxRes,
                    "each map's face size from a test rendering at its sample, up to N (power of "
                    "two, >= --res; PEM §4 EM resolution)");
}

namespace {
constexpr const char* kTopologyHelp =
    "topology threshold (subpixels): triangles whose vertices' ray paths differ in topology are "
    "refined down to min(t, this); 0: t alone (the hybrid paper's)";

// 0 or a t.
std::string CheckTopologyT(const std::string& v) {
    try {
        const double t = std::stod(v);
        if (t == 0.0 || (t >= 0.25 && t <= 1e4)) return "";
    } catch (const std::exception&) {
    }
    return "0 or a value in [0.25, 1e4]";
}
}  // namespace

void AddTopologyOption(CLI::App* sub, std::optional<double>* topologyT) {
    sub->add_option_function<double>(
           "--t-topology", [topologyT](double v) { *topologyT = v; },
           std::string(kTopologyHelp) + " (default: the maps', manifest.json)")
        ->check(CheckTopologyT);
}

void AddTessellationOptions(CLI::App* sub, double* tessT, std::vector<double>* alsoTessT,
                            double* topologyT) {
    sub->add_option("--t", *tessT, "tessellation t (subpixels) the maps are fitted on")
        ->check(CLI::Range(0.25, 1e4));
    sub->add_option("--also-t", *alsoTessT,
                    "further t the layer maps also fit, e.g. 5: maps that hold up when drawn "
                    "at that t too")
        ->delimiter(',')
        ->check(CLI::Range(0.25, 1e4));
    sub->add_option("--t-topology", *topologyT, kTopologyHelp)->check(CheckTopologyT);
}

CLI::Option* AddParameterizationOption(CLI::App* sub, runtime::Parameterization* parameterization) {
    std::string names;
    for (runtime::Parameterization p : runtime::kParameterizations)
        names += (names.empty() ? "" : "|") + std::string(runtime::ParameterizationName(p));
    return sub
        ->add_option_function<std::string>(
            "--parameterization",
            [parameterization](const std::string& v) {
                *parameterization = *runtime::ParseParameterization(v);
            },
            "the maps' layout: " + names + " (default cube)")
        ->check([names](const std::string& v) -> std::string {
            return runtime::ParseParameterization(v) ? "" : "expected one of " + names;
        });
}

CLI::Option* AddMapHardwareOptions(CLI::App* sub, runtime::MapHardware* hardware) {
    AddProfileOption(sub, &hardware->profile);
    sub->add_option("--anisotropy", hardware->maxAnisotropy,
                    "the lens maps' GL_TEXTURE_MAX_ANISOTROPY (1: off, 2..16)")
        ->check(CLI::Range(1.0, 16.0));
    CLI::Option* lodBias =
        sub->add_option("--lod-bias", hardware->lodBias,
                        "the lens maps' GL_TEXTURE_LOD_BIAS (-4..4; below 0: finer levels; "
                        "default -4, float maps -2.5)")
            ->check(CLI::Range(-runtime::kMaxLodBias, runtime::kMaxLodBias));
    sub->add_option_function<std::string>(
           "--map-format",
           [hardware](const std::string& v) {
               for (const auto& [name, format] : raster::kTexelFormatNames)
                   if (name == v) hardware->format = format;
           },
           "the maps' texels: rgba8 (8-bit, [0, 1]; default) or rgba32f (floats, unbounded, drawn "
           "into an RGBA32F colour buffer)")
        ->check(CLI::IsMember({"rgba8", "rgba32f"}));
    sub->add_option("--radiance-scale", hardware->radianceScale,
                    "the maps hold radiance / S (S: 1, 2, 4 .. 64)")
        ->check([](const std::string& v) -> std::string {
            try {
                if (runtime::IsRadianceScale(std::stof(v))) return "";
            } catch (const std::exception&) {
            }
            return "a power of two in [1, 64]";
        });
    return lodBias;
}

std::function<void(const std::string&, double)> ProgressTo(tty::ProgressLine* line) {
    if (!line->Enabled()) return {};
    return [line](const std::string&, double f) { line->Update(f); };
}

}  // namespace pem::cli
