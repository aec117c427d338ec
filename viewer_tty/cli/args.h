// SPDX-License-Identifier: MIT
// args.h — option values the commands share: image sizes, methods, profiles, the version, and
// the progress line every long job shows (view specs: pipeline/pem_set.h ViewCamera).
//
//   auto [w, h] = ParseSize("640x480");
//   runtime::Method m = ParseMethod("hybrid");
//
// Errors: base::InputError naming the option and what it expects.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "raster/camera.h"
#include "runtime/renderer.h"
#include "viewer_tty/tty/progress.h"

namespace pem::cli {

// "WxH" → (W, H), both in [1, 16384].
std::pair<int, int> ParseSize(const std::string& text);

// hybrid | pem | static | traced.
runtime::Method ParseMethod(const std::string& name);

// --profile NAME: one of raster/profile.h's profiles (the value is checked).
void AddProfileOption(CLI::App* sub, std::string* profile);

// The hardware the maps are inferred for: --profile, --anisotropy N (the lens maps'
// GL_TEXTURE_MAX_ANISOTROPY, 1..16), --lod-bias, --map-format and --radiance-scale. Returns the
// --lod-bias option: when it is not given, the caller sets the format's default
// (pipeline::DefaultLodBias), known only once --map-format is parsed.
CLI::Option* AddMapHardwareOptions(CLI::App* sub, runtime::MapHardware* hardware);

// --res N and --max-res N: the maps' face size, and the largest a test rendering at each sample
// may choose (infer, bake and demo).
void AddMapSizeOptions(CLI::App* sub, int* res, int* maxRes);

// --t T, --also-t T1,T2.. and --t-topology T: the tessellation t the maps are fitted on (and the
// renderers' default for them), further t whose rows they also fit, and every tessellation's
// topology threshold (infer and bake).
void AddTessellationOptions(CLI::App* sub, double* tessT, std::vector<double>* alsoTessT,
                            double* topologyT);
// --t-topology for a renderer: the maps' (nullopt) unless given.
void AddTopologyOption(CLI::App* sub, std::optional<double>* topologyT);

// --parameterization NAME: the maps' layout (runtime/parameterization.h).
CLI::Option* AddParameterizationOption(CLI::App* sub, runtime::Parameterization* parameterization);

// pemref's version ("0.1.0", the project's CMake version).
std::string PemrefVersion();
// It and every profile's model (`pemref --version`).
std::string VersionText();

// A job's progress callback that draws `line` (nothing when the line is disabled).
std::function<void(const std::string&, double)> ProgressTo(tty::ProgressLine* line);

}  // namespace pem::cli
