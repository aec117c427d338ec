// SPDX-License-Identifier: MIT
// case_values.cpp — scalar JSON access for the case reader (see case_values.h).
// Conventions: floats are JSON numbers (double, then rounded to nearest float32) or strings read
// whole by strtod (hex floats); NaN, infinities and values beyond float32 range are rejected.
// Not here: geometry (case_geometry.cpp).
#include "viewer_tty/conformance/case_values.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace pem::conformance {

using nlohmann::json;

namespace {

std::string TypeName(const json& v) {
    return v.type_name();
}

[[noreturn]] void FailType(const json& v, const std::string& where, const char* expected) {
    Fail(where, std::string("expected ") + expected + ", got " + TypeName(v));
}

// strtod over the whole string, or a failure naming the text.
double ParseNumberString(const std::string& text, const std::string& where) {
    if (text.empty()) Fail(where, "empty number string");
    const char* begin = text.c_str();
    char* end = nullptr;
    const double d = std::strtod(begin, &end);
    if (end != begin + text.size()) Fail(where, "not a number: \"" + text + "\"");
    return d;
}

}  // namespace

void Fail(const std::string& where, const std::string& cause) {
    throw CaseError(where + ": " + cause);
}

std::string Key(const std::string& where, const char* key) {
    return where.empty() ? std::string(key) : where + "." + key;
}

std::string Index(const std::string& where, size_t i) {
    return where + "[" + std::to_string(i) + "]";
}

const json* Find(const json& obj, const char* key) {
    auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
}

const json& Require(const json& obj, const std::string& where, const char* key) {
    const json* v = Find(obj, key);
    if (!v) Fail(Key(where, key), "missing key");
    return *v;
}

const json& AsObject(const json& v, const std::string& where) {
    if (!v.is_object()) FailType(v, where, "an object");
    return v;
}

const json& AsArray(const json& v, const std::string& where) {
    if (!v.is_array()) FailType(v, where, "an array");
    return v;
}

std::string AsString(const json& v, const std::string& where) {
    if (!v.is_string()) FailType(v, where, "a string");
    return v.get<std::string>();
}

int64_t AsInt(const json& v, const std::string& where, int64_t lo, int64_t hi) {
    if (!v.is_number_integer()) FailType(v, where, "an integer");
    const bool tooBig =
        v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(std::numeric_limits<int64_t>::max());
    const int64_t i = tooBig ? std::numeric_limits<int64_t>::max() : v.get<int64_t>();
    if (i < lo || i > hi)
        Fail(where,
             std::to_string(i) + " out of range " + std::to_string(lo) + ".." + std::to_string(hi));
    return i;
}

float AsFloat(const json& v, const std::string& where) {
    double d = 0.0;
    if (v.is_number()) {
        d = v.get<double>();
    } else if (v.is_string()) {
        d = ParseNumberString(v.get<std::string>(), where);
    } else {
        FailType(v, where, "a number or numeric string");
    }
    if (std::isnan(d)) Fail(where, "NaN");
    if (std::isinf(d)) Fail(where, "infinite");
    if (std::fabs(d) > double(std::numeric_limits<float>::max()))
        Fail(where, "beyond float32 range");
    return static_cast<float>(d);
}

uint64_t AsSeed(const json& v, const std::string& where) {
    if (v.is_number_unsigned()) return v.get<uint64_t>();
    if (v.is_number_integer()) Fail(where, "negative seed");
    if (!v.is_string()) FailType(v, where, "an unsigned integer or string");
    const std::string text = v.get<std::string>();
    char* end = nullptr;
    errno = 0;
    const unsigned long long seed = std::strtoull(text.c_str(), &end, 0);
    if (text.empty() || text[0] == '-' || text[0] == '+' || text[0] == ' ' ||
        end != text.c_str() + text.size() || errno == ERANGE)
        Fail(where, "not an unsigned 64-bit integer: \"" + text + "\"");
    return static_cast<uint64_t>(seed);
}

int IntOr(const json& obj, const std::string& where, const char* key, int fallback, int lo,
          int hi) {
    const json* v = Find(obj, key);
    return v ? static_cast<int>(AsInt(*v, Key(where, key), lo, hi)) : fallback;
}

float FloatOr(const json& obj, const std::string& where, const char* key, float fallback) {
    const json* v = Find(obj, key);
    return v ? AsFloat(*v, Key(where, key)) : fallback;
}

bool BoolOr(const json& obj, const std::string& where, const char* key, bool fallback) {
    const json* v = Find(obj, key);
    if (!v) return fallback;
    if (!v->is_boolean()) FailType(*v, Key(where, key), "a boolean");
    return v->get<bool>();
}

}  // namespace pem::conformance
