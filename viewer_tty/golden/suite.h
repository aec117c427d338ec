// SPDX-License-Identifier: MIT
// suite.h — a golden-image suite: a folder of inputs. Every raster case file in it (*.json other
// than suite.json) is a test compared exactly; suite.json may add scene renders and give any
// test a fuzzy tolerance or model bounds:
//
//   {"format": "pemref_golden_suite", "version": 1, "tests": [
//     {"name": "sphere", "case": "sphere.json", "fuzzy": [2, 40]},
//     {"name": "room", "scene": "room.gltf", "camera": "scene", "size": [96, 72],
//      "method": "traced", "spp": 2},
//     {"name": "cup_static", "scene": "room.gltf", "method": "static", "size": [96, 72]},
//     {"name": "cup_hybrid", "pem": "bake/pem", "view": "sample:0", "method": "hybrid",
//      "size": [96, 72]},
//     {"name": "sphere_gpu", "case": "sphere.json", "bounds_lsb": 1}]}
//
// Paths are relative to the suite folder. "fuzzy": [D, N] accepts at most N differing pixels,
// none by more than D (reftest's fuzzy); "bounds_lsb": n accepts an image whose every channel
// lies within the range the modelled profiles span, widened by n (model_bounds.h). Scene
// cameras: "scene" (the glTF camera at `size`) or a camera object as trace.json stores it.
// Errors: base::InputError naming suite.json and the entry.
// Not here: golden.json (golden_file.h), rendering (golden_render.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "viewer_tty/golden/image_diff.h"

namespace pem::golden {

struct GoldenTest {
    std::string name;
    enum class Kind { Case, Scene, Pem } kind = Kind::Case;
    std::string input;   // the case file, the glTF scene or the PEM directory (absolute)
    std::string camera;  // scenes: "scene" or a camera's JSON text
    std::string view;    // PEM tests: sample:I | orbit:AZ:EL:DIST | camera
    std::string method;  // scenes: traced | static; PEM tests: hybrid | pem | static | traced
    int width = 0, height = 0;  // scenes and PEM tests (0: the PEMs' size)
    int spp = 1;                // the ray tracer's K×K
    Fuzzy fuzzy;                // exact unless given
    std::optional<int> boundsLsb;
};

struct Suite {
    std::string dir;
    std::vector<GoldenTest> tests;  // in suite.json's order, then the other case files by name
    const GoldenTest* Find(const std::string& name) const;
};

Suite ReadSuite(const std::string& dir);

}  // namespace pem::golden
