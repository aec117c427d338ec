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
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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

// An integer of type T named `what` in messages: a JSON integer within T's range. 2.5, 1e300, a
// string or 2^40 for an int throw std::runtime_error (nlohmann's get<int>() would truncate, wrap
// or overflow them).
template <class T>
T IntFromJson(const json& j, std::string_view what) {
    if (j.is_number_unsigned() && std::in_range<T>(j.get<uint64_t>()))
        return static_cast<T>(j.get<uint64_t>());
    if (j.is_number_integer() && !j.is_number_unsigned() && std::in_range<T>(j.get<int64_t>()))
        return static_cast<T>(j.get<int64_t>());
    const std::string found = j.is_primitive() ? j.dump().substr(0, 40) : j.type_name();
    throw std::runtime_error(std::string(what) + ": " + found + " is not an integer in [" +
                             std::to_string(std::numeric_limits<T>::min()) + ", " +
                             std::to_string(std::numeric_limits<T>::max()) + "]");
}

// j[key] as IntFromJson; IntAtOr gives `fallback` where the key is absent (older files).
template <class T>
T IntAt(const json& j, const char* key) {
    return IntFromJson<T>(j.at(key), key);
}
template <class T>
T IntAtOr(const json& j, const char* key, T fallback) {
    return j.contains(key) ? IntAt<T>(j, key) : fallback;
}

// j[key], the name of a hardware profile this pemref knows (raster/profile.h).
std::string ProfileAt(const json& j, const char* key);

// j[key], an array of IntFromJson.
template <class T>
std::vector<T> IntsAt(const json& j, const char* key) {
    const json& a = j.at(key);
    if (!a.is_array()) throw std::runtime_error(std::string(key) + ": not an array");
    std::vector<T> out;
    for (const json& v : a) out.push_back(IntFromJson<T>(v, key));
    return out;
}

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
