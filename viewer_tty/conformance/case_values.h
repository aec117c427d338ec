// SPDX-License-Identifier: MIT
// case_values.h — typed access to the JSON values of a case file, for the case reader only:
// scalars (ints, exact floats, seeds, enum names), key-path naming, and pass geometry.
// Conventions: `where` is the key path of the value read ("passes[2].vertices"); every problem
// throws CaseError("<where>: <cause>"), which the reader wraps into pem::base::InputError with the
// path. Not here: the frame structure (case_file.cpp); nothing here knows about files.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "raster/frame.h"
#include "viewer_tty/conformance/case_names.h"

namespace pem::conformance {

class CaseError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

[[noreturn]] void Fail(const std::string& where, const std::string& cause);
std::string Key(const std::string& where, const char* key);  // "a.b" (or "b" at top level)
std::string Index(const std::string& where, size_t i);       // "a[i]"

// Object members: nullptr when absent / a "missing key" failure.
const nlohmann::json* Find(const nlohmann::json& obj, const char* key);
const nlohmann::json& Require(const nlohmann::json& obj, const std::string& where, const char* key);

// Typed values; a wrong JSON type or a value out of [lo, hi] fails.
const nlohmann::json& AsObject(const nlohmann::json& v, const std::string& where);
const nlohmann::json& AsArray(const nlohmann::json& v, const std::string& where);
std::string AsString(const nlohmann::json& v, const std::string& where);
int64_t AsInt(const nlohmann::json& v, const std::string& where, int64_t lo, int64_t hi);
float AsFloat(const nlohmann::json& v, const std::string& where);  // finite float32 only
uint64_t AsSeed(const nlohmann::json& v, const std::string& where);

// Optional object members with defaults.
int IntOr(const nlohmann::json& obj, const std::string& where, const char* key, int fallback,
          int lo, int hi);
float FloatOr(const nlohmann::json& obj, const std::string& where, const char* key, float fallback);
bool BoolOr(const nlohmann::json& obj, const std::string& where, const char* key, bool fallback);

template <class E, size_t N>
E EnumOr(const nlohmann::json& obj, const std::string& where, const char* key,
         const std::array<NameTable<E>, N>& table, E fallback) {
    const nlohmann::json* v = Find(obj, key);
    if (!v) return fallback;
    const std::string name = AsString(*v, Key(where, key));
    for (const auto& entry : table)
        if (entry.first == name) return entry.second;
    Fail(Key(where, key), "unknown value \"" + name + "\"");
}

// Pass geometry (case_geometry.cpp): `vertices` / `vertices_b64` with 4 + 3*numUnits + 4 numbers
// per vertex, optional `indices` / `indices_b64`, and the triangle-list consistency checks.
std::vector<raster::Vertex> ParseVertices(const nlohmann::json& pass, const std::string& where,
                                          int numUnits);
std::vector<uint32_t> ParseIndices(const nlohmann::json& pass, const std::string& where);
void CheckTriangles(const raster::Pass& pass, const std::string& where);

}  // namespace pem::conformance
