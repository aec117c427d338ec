// SPDX-License-Identifier: MIT
// case_geometry.cpp — a pass's vertices and indices from a case file (see case_values.h).
// Conventions: a vertex is x y z w, then 3 numbers per texture unit (cube direction, or 2D s t
// and a third kept but unused number), then r g b a; base64 payloads are little-endian.
// Not here: texture units and blending (case_file.cpp).
#include <bit>
#include <cmath>
#include <cstring>

#include "viewer_tty/conformance/case_codec.h"
#include "viewer_tty/conformance/case_values.h"

namespace pem::conformance {

using nlohmann::json;

namespace {

uint32_t LoadLe32(const uint8_t* p) {
    return uint32_t{p[0]} | (uint32_t{p[1]} << 8) | (uint32_t{p[2]} << 16) | (uint32_t{p[3]} << 24);
}

// The bytes of a base64 key whose length must be a multiple of `unit` bytes.
std::vector<uint8_t> DecodeB64Key(const json& pass, const std::string& where, const char* key,
                                  size_t unit) {
    const std::string keyWhere = Key(where, key);
    DecodeResult decoded = Base64Decode(AsString(*Find(pass, key), keyWhere));
    if (!decoded.error.empty()) Fail(keyWhere, decoded.error);
    if (decoded.bytes.size() % unit != 0)
        Fail(keyWhere, std::to_string(decoded.bytes.size()) + " bytes, not a multiple of " +
                           std::to_string(unit));
    return decoded.bytes;
}

// Floats of `vertices`: an array of per-vertex arrays, or one flat array.
std::vector<float> VertexFloatsFromJson(const json& list, const std::string& where, size_t stride) {
    std::vector<float> floats;
    const bool nested = !list.empty() && list[0].is_array();
    if (!nested) {
        if (list.size() % stride != 0)
            Fail(where, std::to_string(list.size()) + " numbers, not a multiple of " +
                            std::to_string(stride));
        for (size_t k = 0; k < list.size(); ++k)
            floats.push_back(AsFloat(list[k], Index(where, k)));
        return floats;
    }
    for (size_t v = 0; v < list.size(); ++v) {
        const std::string vertexWhere = Index(where, v);
        const json& numbers = AsArray(list[v], vertexWhere);
        if (numbers.size() != stride)
            Fail(vertexWhere, "expected " + std::to_string(stride) + " numbers, got " +
                                  std::to_string(numbers.size()));
        for (size_t k = 0; k < stride; ++k)
            floats.push_back(AsFloat(numbers[k], Index(vertexWhere, k)));
    }
    return floats;
}

// Floats of `vertices_b64`: little-endian float32, NaN and infinities rejected.
std::vector<float> VertexFloatsFromB64(const json& pass, const std::string& where, size_t stride) {
    const std::vector<uint8_t> bytes = DecodeB64Key(pass, where, "vertices_b64", 4 * stride);
    std::vector<float> floats;
    for (size_t k = 0; k * 4 < bytes.size(); ++k) {
        const float f = std::bit_cast<float>(LoadLe32(bytes.data() + 4 * k));
        const std::string numberWhere =
            Index(Index(Key(where, "vertices_b64"), k / stride), k % stride);
        if (std::isnan(f)) Fail(numberWhere, "NaN");
        if (std::isinf(f)) Fail(numberWhere, "infinite");
        floats.push_back(f);
    }
    return floats;
}

raster::Vertex MakeVertex(const float* f, int numUnits) {
    raster::Vertex v;
    v.pos = {f[0], f[1], f[2], f[3]};
    for (int u = 0; u < numUnits; ++u) {
        const float* c = f + 4 + 3 * u;
        v.coord[size_t(u)] = {c[0], c[1], c[2]};
    }
    const float* col = f + 4 + 3 * numUnits;
    v.color = {col[0], col[1], col[2], col[3]};
    return v;
}

}  // namespace

std::vector<raster::Vertex> ParseVertices(const json& pass, const std::string& where,
                                          int numUnits) {
    const size_t stride = size_t(8 + 3 * numUnits);
    const json* list = Find(pass, "vertices");
    const json* b64 = Find(pass, "vertices_b64");
    if (list && b64) Fail(Key(where, "vertices"), "both \"vertices\" and \"vertices_b64\" given");
    if (!list && !b64) Fail(Key(where, "vertices"), "missing key");
    const std::vector<float> floats =
        list ? VertexFloatsFromJson(AsArray(*list, Key(where, "vertices")), Key(where, "vertices"),
                                    stride)
             : VertexFloatsFromB64(pass, where, stride);
    std::vector<raster::Vertex> vertices;
    for (size_t k = 0; k < floats.size(); k += stride)
        vertices.push_back(MakeVertex(floats.data() + k, numUnits));
    return vertices;
}

std::vector<uint32_t> ParseIndices(const json& pass, const std::string& where) {
    const json* list = Find(pass, "indices");
    const json* b64 = Find(pass, "indices_b64");
    if (list && b64) Fail(Key(where, "indices"), "both \"indices\" and \"indices_b64\" given");
    std::vector<uint32_t> indices;
    if (b64) {
        const std::vector<uint8_t> bytes = DecodeB64Key(pass, where, "indices_b64", 4);
        for (size_t k = 0; k < bytes.size(); k += 4) indices.push_back(LoadLe32(bytes.data() + k));
    } else if (list) {
        const std::string listWhere = Key(where, "indices");
        const json& items = AsArray(*list, listWhere);
        for (size_t k = 0; k < items.size(); ++k)
            indices.push_back(
                static_cast<uint32_t>(AsInt(items[k], Index(listWhere, k), 0, 0xFFFFFFFF)));
    }
    return indices;
}

void CheckTriangles(const raster::Pass& pass, const std::string& where) {
    const size_t numVertices = pass.vertices.size();
    if (pass.indices.empty()) {
        if (numVertices % 3 != 0)
            Fail(Key(where, "vertices"),
                 std::to_string(numVertices) + " vertices without indices, not a multiple of 3");
        return;
    }
    if (pass.indices.size() % 3 != 0)
        Fail(Key(where, "indices"),
             std::to_string(pass.indices.size()) + " indices, not a multiple of 3");
    for (size_t k = 0; k < pass.indices.size(); ++k)
        if (pass.indices[k] >= numVertices)
            Fail(Index(Key(where, "indices"), k), "index " + std::to_string(pass.indices[k]) +
                                                      " out of range (" +
                                                      std::to_string(numVertices) + " vertices)");
}

}  // namespace pem::conformance
