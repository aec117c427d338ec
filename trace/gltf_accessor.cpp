// SPDX-License-Identifier: MIT
// gltf_accessor.cpp — checked reads of glTF accessors and extras/extension JSON values.
// Every byte range is checked against its bufferView and buffer with overflow-safe arithmetic
// before it is read (memcpy, so unaligned data is fine). Not supported: sparse accessors,
// accessors without a bufferView, non-float positions/normals (KHR_mesh_quantization).
#include <cmath>
#include <cstring>

#include "base/input_error.h"
#include "trace/gltf_internal.h"

namespace pem::trace::gltf {

void Fail(const Context& ctx, const std::string& cause) {
    throw pem::base::InputError(ctx.path, cause);
}

void Note(const Context& ctx, const std::string& note) {
    if (ctx.notes) ctx.notes->push_back(note);
}

// JSON values ---------------------------------------------------------------------------------

const tinygltf::Value* Member(const tinygltf::Value& object, const std::string& key) {
    if (!object.IsObject() || !object.Has(key)) return nullptr;
    return &object.Get(key);
}

double NumberOr(const Context& ctx, const tinygltf::Value& object, const std::string& key,
                double fallback, const std::string& where) {
    const tinygltf::Value* v = Member(object, key);
    if (!v) return fallback;
    if (!v->IsNumber() || !std::isfinite(v->GetNumberAsDouble()))
        Fail(ctx, where + "." + key + ": expected a finite number");
    return v->GetNumberAsDouble();
}

std::string StringOr(const Context& ctx, const tinygltf::Value& object, const std::string& key,
                     const std::string& fallback, const std::string& where) {
    const tinygltf::Value* v = Member(object, key);
    if (!v) return fallback;
    if (!v->IsString()) Fail(ctx, where + "." + key + ": expected a string");
    return v->Get<std::string>();
}

glm::dvec3 Vec3Or(const Context& ctx, const tinygltf::Value& object, const std::string& key,
                  const glm::dvec3& fallback, const std::string& where) {
    const tinygltf::Value* v = Member(object, key);
    if (!v) return fallback;
    if (!v->IsArray() || v->ArrayLen() != 3) Fail(ctx, where + "." + key + ": expected 3 numbers");
    glm::dvec3 out;
    for (int i = 0; i < 3; ++i) {
        const tinygltf::Value& e = v->Get(i);
        if (!e.IsNumber() || !std::isfinite(e.GetNumberAsDouble()))
            Fail(ctx, where + "." + key + ": expected 3 finite numbers");
        out[i] = e.GetNumberAsDouble();
    }
    return out;
}

const tinygltf::Value* Extension(const tinygltf::ExtensionMap& map, const std::string& name) {
    auto it = map.find(name);
    return it == map.end() ? nullptr : &it->second;
}

// Accessors -----------------------------------------------------------------------------------

namespace {

int ComponentBytes(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;
    }
}

int TypeComponents(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        case TINYGLTF_TYPE_VEC4:
            return 4;
        default:
            return 0;
    }
}

// A validated window onto an accessor's bytes: element i starts at base + i * stride.
struct View {
    const unsigned char* base = nullptr;
    size_t stride = 0, count = 0;
    int componentType = 0, components = 0;
    bool normalized = false;
};

// a + b <= limit without overflow.
bool FitsSum(size_t a, size_t b, size_t limit) {
    return a <= limit && b <= limit - a;
}

const tinygltf::BufferView& CheckedBufferView(const Context& ctx, const tinygltf::Accessor& acc,
                                              const std::string& where) {
    const auto& m = ctx.model;
    if (acc.bufferView < 0 || static_cast<size_t>(acc.bufferView) >= m.bufferViews.size())
        Fail(ctx, where + ": bufferView " + std::to_string(acc.bufferView) + " out of range");
    const tinygltf::BufferView& bv = m.bufferViews[static_cast<size_t>(acc.bufferView)];
    if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= m.buffers.size())
        Fail(ctx, where + ": buffer " + std::to_string(bv.buffer) + " out of range");
    const size_t bufferSize = m.buffers[static_cast<size_t>(bv.buffer)].data.size();
    if (!FitsSum(bv.byteOffset, bv.byteLength, bufferSize))
        Fail(ctx, where + ": bufferView " + std::to_string(acc.bufferView) + " (offset " +
                      std::to_string(bv.byteOffset) + ", length " + std::to_string(bv.byteLength) +
                      ") exceeds its buffer of " + std::to_string(bufferSize) +
                      " bytes (missing or short .bin?)");
    return bv;
}

View CheckedView(const Context& ctx, int index, const std::string& where) {
    const auto& m = ctx.model;
    // Step 1: the accessor itself.
    if (index < 0 || static_cast<size_t>(index) >= m.accessors.size())
        Fail(ctx, where + ": accessor " + std::to_string(index) + " out of range");
    const tinygltf::Accessor& acc = m.accessors[static_cast<size_t>(index)];
    if (acc.sparse.isSparse) Fail(ctx, where + ": sparse accessors are not supported");
    View v;
    v.componentType = acc.componentType;
    v.components = TypeComponents(acc.type);
    v.normalized = acc.normalized;
    v.count = acc.count;
    const size_t elemBytes = static_cast<size_t>(ComponentBytes(acc.componentType) * v.components);
    if (elemBytes == 0) Fail(ctx, where + ": invalid accessor type or componentType");
    if (v.count == 0) return v;
    // Step 2: its bufferView and buffer.
    const tinygltf::BufferView& bv = CheckedBufferView(ctx, acc, where);
    v.stride = bv.byteStride ? bv.byteStride : elemBytes;
    if (v.stride < elemBytes) Fail(ctx, where + ": byteStride smaller than the element size");
    // Step 3: the last element must end inside the bufferView.
    const size_t span = (v.count - 1 > (SIZE_MAX - elemBytes) / v.stride)
                            ? SIZE_MAX
                            : (v.count - 1) * v.stride + elemBytes;
    if (span == SIZE_MAX || !FitsSum(acc.byteOffset, span, bv.byteLength))
        Fail(ctx, where + ": accessor " + std::to_string(index) + " (count " +
                      std::to_string(v.count) + ") exceeds its bufferView of " +
                      std::to_string(bv.byteLength) + " bytes");
    v.base = m.buffers[static_cast<size_t>(bv.buffer)].data.data() + bv.byteOffset + acc.byteOffset;
    return v;
}

template <typename T>
T Load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));
    return value;
}

// Component c of element i as float (normalized integers mapped to [0, 1]).
float ComponentAsFloat(const View& v, size_t i, int c) {
    const unsigned char* p = v.base + i * v.stride;
    switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return Load<float>(p + 4 * c);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return static_cast<float>(p[c]) / 255.0f;
        default:
            return static_cast<float>(Load<uint16_t>(p + 2 * c)) / 65535.0f;
    }
}

void RequireFloat(const Context& ctx, const View& v, int components, const std::string& where) {
    if (v.components != components || v.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        Fail(ctx, where + ": expected float VEC" + std::to_string(components) + " data");
}

}  // namespace

std::vector<glm::vec3> ReadVec3(const Context& ctx, int accessor, const std::string& where) {
    const View v = CheckedView(ctx, accessor, where);
    RequireFloat(ctx, v, 3, where);
    std::vector<glm::vec3> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        for (int c = 0; c < 3; ++c) out[i][c] = ComponentAsFloat(v, i, c);
        if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y) || !std::isfinite(out[i].z))
            Fail(ctx, where + "[" + std::to_string(i) + "]: non-finite value (NaN or Inf)");
    }
    return out;
}

std::vector<glm::vec2> ReadTexcoord(const Context& ctx, int accessor, const std::string& where) {
    const View v = CheckedView(ctx, accessor, where);
    const bool ok = v.components == 2 &&
                    (v.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                     (v.normalized && (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                       v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)));
    if (!ok) Fail(ctx, where + ": expected VEC2 float or normalized unsigned byte/short data");
    std::vector<glm::vec2> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        out[i] = {ComponentAsFloat(v, i, 0), ComponentAsFloat(v, i, 1)};
        if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y))
            Fail(ctx, where + "[" + std::to_string(i) + "]: non-finite value (NaN or Inf)");
    }
    return out;
}

std::vector<uint32_t> ReadIndices(const Context& ctx, int accessor, const std::string& where) {
    const View v = CheckedView(ctx, accessor, where);
    if (v.components != 1) Fail(ctx, where + ": indices must be SCALAR");
    std::vector<uint32_t> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        const unsigned char* p = v.base + i * v.stride;
        switch (v.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                out[i] = p[0];
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
                out[i] = Load<uint16_t>(p);
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
                out[i] = Load<uint32_t>(p);
                break;
            default:
                Fail(ctx, where + ": indices must be unsigned byte, short or int");
        }
    }
    return out;
}

}  // namespace pem::trace::gltf
