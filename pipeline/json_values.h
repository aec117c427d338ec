// SPDX-License-Identifier: MIT
// json_values.h — the JSON forms of the values trace.json and manifest.json share, each with its
// reader beside its writer: vectors, a viewpoint sample's camera, EM shells and a lens group's
// EM geometry (runtime/lens_group_em.h).
//
//   json j = CameraJson(camera);   raster::Camera c = CameraFromJson(j);   // c == camera
//
// Conventions: numbers are written as doubles (floats widen exactly, so a float read back is the
// same float); a camera is stored whole: eye, target, up, fov_y_radians, size [w, h]. Readers
// throw nlohmann::json::exception or std::runtime_error on a missing key or a bad value; the
// file readers turn them into base::InputError naming the file.
// Not here: whole files (trace_manifest.h, pem_manifest.h).
#pragma once

#include <fstream>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "base/input_error.h"
#include "raster/camera.h"
#include "runtime/lens_group_em.h"
#include "trace/shell.h"

namespace pem::pipeline {

using nlohmann::json;

json Vec3Json(const glm::dvec3& v);
glm::dvec3 Vec3FromJson(const json& j);

json CameraJson(const raster::Camera& camera);
raster::Camera CameraFromJson(const json& j);

json ShellJson(const trace::Shell& shell);
trace::Shell ShellFromJson(const json& j);

json LensGroupJson(const runtime::LensGroupEm& group);
runtime::LensGroupEm LensGroupFromJson(const json& j, int index);

// The JSON file at path through fromJson: a missing file (`missing` says what to do), a parse
// error or a bad value (std::runtime_error from fromJson) become one base::InputError
// "<path>: <cause>".
template <class F>
auto ReadJsonFile(const std::string& path, const std::string& missing, const F& fromJson) {
    std::ifstream f(path);
    if (!f) throw base::InputError(path, "cannot open (" + missing + ")");
    try {
        return fromJson(json::parse(f));
    } catch (const json::exception& e) {
        throw base::InputError(path, std::string("malformed: ") + e.what());
    } catch (const std::runtime_error& e) {
        throw base::InputError(path, e.what());
    }
}

}  // namespace pem::pipeline
