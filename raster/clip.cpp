// SPDX-License-Identifier: MIT
// clip.cpp — Mesa's draw module for llvmpipe and softpipe with an RGBA8 FBO (no guard band: x, y
// and z are clipped in float by draw_pipe_clip.c; the arithmetic is restated here in our own
// words).
//
//  - Clip mask per vertex (unordered compares: NaN is outside): x > w, x + w < 0, y > w,
//    y + w < 0, z + w < 0, z > w (the z planes only without depth clamp).
//  - Unclipped vertices: oow = 1 / w; window = fma(p * oow, scale, translate) (llvmpipe's JIT
//    code), or (p * oow) * scale + translate (softpipe: draw_cliptest_tmp.h, plain C).
//  - A triangle with any vertex outside is clipped plane by plane (Sutherland-Hodgman, planes in
//    mask-bit order, distances dot(p, plane) evaluated left to right); triangles entirely
//    outside one plane are dropped. New vertices: p = out + t * (in - out) on every attribute,
//    window = ((p * (1 / w)) * scale) + translate (C code, no fusion). A polygon v0..vn-1 is
//    drawn as triangles (v[i-1], v[i], v[0]), the provoking vertex last.
#include "raster/clip.h"

#include <cmath>

namespace pem::raster {
namespace {

constexpr int kMaxPoly = 16;

struct Viewport {
    float scale[3], trans[3];
};

Viewport MakeViewport(int width, int height) {
    const float hw = static_cast<float>(width) * 0.5f, hh = static_cast<float>(height) * 0.5f;
    return {{hw, hh, 0.5f}, {hw, hh, 0.5f}};
}

// Bit k set when the vertex is outside plane k (NaN counts as outside). llvmpipe's JIT compares
// x > w unordered; softpipe's C code tests !(w - x >= 0), which also rejects x = w = +Inf.
unsigned ClipMask(const glm::vec4& p, bool clipZ, ViewportForm form) {
    auto gt = [](float a, float b) { return !(a <= b); };  // unordered greater
    auto out = [](float d) { return !(d >= 0.0f); };       // softpipe: distance not >= 0
    unsigned m = 0;
    const bool plain = form == ViewportForm::Plain;
    if (plain ? out(p.w - p.x) : gt(p.x, p.w)) m |= 1u;
    if (gt(0.0f, p.x + p.w)) m |= 2u;
    if (plain ? out(p.w - p.y) : gt(p.y, p.w)) m |= 4u;
    if (gt(0.0f, p.y + p.w)) m |= 8u;
    if (clipZ) {
        if (gt(0.0f, p.z + p.w)) m |= 16u;
        if (plain ? out(p.w - p.z) : gt(p.z, p.w)) m |= 32u;
    }
    return m;
}

// A vertex in the clipper: clip position, attributes, and its window position once known.
struct PolyVertex {
    glm::vec4 clip;
    std::array<float, kMaxAttribs> attr;
    WindowVertex win;
};

WindowVertex Window(const ClipVertex& v, const Viewport& vp, int numAttribs, ViewportForm form) {
    WindowVertex w;
    const float oow = 1.0f / v.pos.w;
    if (form == ViewportForm::Fused) {
        w.x = std::fma(v.pos.x * oow, vp.scale[0], vp.trans[0]);
        w.y = std::fma(v.pos.y * oow, vp.scale[1], vp.trans[1]);
        w.z = std::fma(v.pos.z * oow, vp.scale[2], vp.trans[2]);
    } else {
        w.x = v.pos.x * oow * vp.scale[0] + vp.trans[0];
        w.y = v.pos.y * oow * vp.scale[1] + vp.trans[1];
        w.z = v.pos.z * oow * vp.scale[2] + vp.trans[2];
    }
    w.oow = oow;
    w.attr = {};
    for (int k = 0; k < numAttribs; ++k) w.attr[k] = v.attr[k];
    return w;
}

float PlaneDistance(const glm::vec4& p, int plane) {
    static const float kPlanes[6][4] = {{-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1},
                                        {0, 1, 0, 1},  {0, 0, 1, 1}, {0, 0, -1, 1}};
    const float* q = kPlanes[plane];
    return p.x * q[0] + p.y * q[1] + p.z * q[2] + p.w * q[3];
}

float Linterp(float t, float out, float in) {
    return out + t * (in - out);
}

// New vertex between `out` and `in` at parameter t.
PolyVertex Interpolate(float t, const PolyVertex& out, const PolyVertex& in, const Viewport& vp,
                       int numAttribs) {
    PolyVertex d;
    for (int k = 0; k < 4; ++k) d.clip[k] = Linterp(t, out.clip[k], in.clip[k]);
    const float oow = 1.0f / d.clip.w;
    d.win.x = d.clip.x * oow * vp.scale[0] + vp.trans[0];
    d.win.y = d.clip.y * oow * vp.scale[1] + vp.trans[1];
    d.win.z = d.clip.z * oow * vp.scale[2] + vp.trans[2];
    d.win.oow = oow;
    d.attr = {};
    for (int k = 0; k < numAttribs; ++k) d.attr[k] = Linterp(t, out.attr[k], in.attr[k]);
    d.win.attr = d.attr;
    return d;
}

}  // namespace

void ClipTriangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c, int numAttribs,
                  bool depthClamp, int width, int height, ViewportForm form,
                  std::vector<WindowTriangle>* out) {
    const Viewport vp = MakeViewport(width, height);
    const ClipVertex* v[3] = {&a, &b, &c};
    unsigned masks[3], any = 0, all = ~0u;
    for (int i = 0; i < 3; ++i) {
        masks[i] = ClipMask(v[i]->pos, !depthClamp, form);
        any |= masks[i];
        all &= masks[i];
    }
    if (any == 0) {
        out->push_back({Window(a, vp, numAttribs, form), Window(b, vp, numAttribs, form),
                        Window(c, vp, numAttribs, form)});
        return;
    }
    if (all != 0) return;  // entirely outside one plane

    // Sutherland-Hodgman over the planes the triangle crosses, in bit order.
    PolyVertex bufA[kMaxPoly + 1], bufB[kMaxPoly + 1];
    PolyVertex* in = bufA;
    PolyVertex* outList = bufB;
    for (int i = 0; i < 3; ++i) {
        in[i].clip = v[i]->pos;
        in[i].attr = v[i]->attr;
        in[i].win = Window(*v[i], vp, numAttribs, form);
    }
    int n = 3;
    for (int plane = 0; plane < 6 && n >= 3; ++plane) {
        if (!(any & (1u << plane))) continue;
        float dpPrev = PlaneDistance(in[0].clip, plane);
        if (!std::isfinite(dpPrev)) return;
        in[n] = in[0];
        int count = 0;
        for (int i = 1; i <= n; ++i) {
            const float dp = PlaneDistance(in[i].clip, plane);
            if (!std::isfinite(dp)) return;
            bool crossing;
            if (dpPrev >= 0.0f) {
                if (count >= kMaxPoly) return;
                outList[count++] = in[i - 1];
                crossing = dp < 0.0f;
            } else {
                crossing = !(dp < 0.0f);
            }
            if (crossing) {
                if (count >= kMaxPoly) return;
                const float denom = dp - dpPrev;
                if (dp < 0.0f) {
                    if (-dp < dpPrev)
                        outList[count++] =
                            Interpolate(dp / denom, in[i], in[i - 1], vp, numAttribs);
                    else
                        outList[count++] =
                            Interpolate(-dpPrev / denom, in[i - 1], in[i], vp, numAttribs);
                } else {
                    if (-dpPrev < dp)
                        outList[count++] =
                            Interpolate(-dpPrev / denom, in[i - 1], in[i], vp, numAttribs);
                    else
                        outList[count++] =
                            Interpolate(dp / denom, in[i], in[i - 1], vp, numAttribs);
                }
            }
            dpPrev = dp;
        }
        std::swap(in, outList);
        n = count;
    }
    for (int i = 2; i < n; ++i) out->push_back({in[i - 1].win, in[i].win, in[0].win});
}

ClipVertex PassClipVertex(const Pass& pass, uint32_t index) {
    const Vertex& v = pass.vertices[index];
    ClipVertex cv{v.pos, {}};
    for (int u = 0; u < pass.numUnits; ++u)
        for (int k = 0; k < 3; ++k) cv.attr[static_cast<size_t>(3 * u + k)] = v.coord[u][k];
    for (int k = 0; k < 4; ++k)
        cv.attr[static_cast<size_t>(PassColourAttrib(pass) + k)] = v.color[k];
    return cv;
}

bool InsideViewVolume(const glm::vec4& pos, bool depthClamp, ViewportForm form) {
    return ClipMask(pos, !depthClamp, form) == 0;
}

WindowVertex ToWindow(const ClipVertex& v, int numAttribs, int width, int height,
                      ViewportForm form) {
    return Window(v, MakeViewport(width, height), numAttribs, form);
}

}  // namespace pem::raster
