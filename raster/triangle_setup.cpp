// SPDX-License-Identifier: MIT
#include "raster/triangle_setup.h"

#include <algorithm>
#include <cmath>

#include "raster/numeric.h"

namespace pem::raster {
namespace {

// Bounding boxes up to this many pixels are tested for covering any pixel at all.
constexpr int kSmallBoxPixels = 16;

// Subpixel snap of one window coordinate: (v - 0.5) * 256 in float, cvtps2dq (RNE; NaN and
// overflow give INT32_MIN).
int32_t Snap(float v) {
    return RoundHalfEvenI32((v - 0.5f) * 256.0f);
}

struct Fixed {
    std::array<int32_t, 3> x, y;
};

int32_t WrapSub(int32_t a, int32_t b) {
    return static_cast<int32_t>(static_cast<uint32_t>(a) - static_cast<uint32_t>(b));
}

// Signed fixed-point doubled area: dx01 * dy20 - dx20 * dy01 in 64 bits (wrapping like the
// uint64 arithmetic of the reference).
int AreaSign(const Fixed& p) {
    const int64_t dx01 = WrapSub(p.x[0], p.x[1]), dy01 = WrapSub(p.y[0], p.y[1]);
    const int64_t dx20 = WrapSub(p.x[2], p.x[0]), dy20 = WrapSub(p.y[2], p.y[0]);
    const uint64_t area = static_cast<uint64_t>(dx01 * dy20) - static_cast<uint64_t>(dx20 * dy01);
    return area == 0 ? 0 : (area >> 63) ? -1 : 1;
}

// Edge i runs from vertex i to vertex i+1 (mod 3). Left edges (dcdx < 0) and, among
// horizontal edges, those with dcdy < 0 (GL FBO: bottom_edge_rule 1) are inclusive.
Edge MakeEdge(const Fixed& p, int i) {
    const int j = (i + 1) % 3;
    const int64_t dcdx = WrapSub(p.y[i], p.y[j]);  // 32-bit differences, as the reference
    const int64_t dcdy = WrapSub(p.x[i], p.x[j]);
    int64_t c = WrapSub64(dcdx * p.x[i], dcdy * p.y[i]);
    if (dcdx < 0 || (dcdx == 0 && dcdy < 0)) c = WrapAdd64(c, 1);
    return {c, dcdx * 256, dcdy * 256};
}

// Attribute planes from the float positions (lp_state_setup.c's generated code); with
// `withPositionPlanes` also 1/w and z.
void Planes(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c, int numAttribs,
            bool withPositionPlanes, TriangleSetup* out) {
    const WindowVertex* v[3] = {&a, &b, &c};
    const float x0c = v[0]->x - 0.5f, y0c = v[0]->y - 0.5f;
    float dx01 = v[0]->x - v[1]->x, dy01 = v[0]->y - v[1]->y;
    float dx20 = v[2]->x - v[0]->x, dy20 = v[2]->y - v[0]->y;
    const float e = dx01 * dy20, f = dy01 * dx20;
    const float ooa = 1.0f / (e - f);
    dx20 *= ooa;
    dy20 *= ooa;
    dx01 *= ooa;
    dy01 *= ooa;
    auto plane = [&](float a0, float a1, float a2) {
        const float da01 = a0 - a1, da20 = a2 - a0;
        const float dadx = da01 * dy20 - da20 * dy01;
        const float dady = da20 * dx01 - da01 * dx20;
        return Plane{a0 - (dadx * x0c + dady * y0c), dadx, dady};
    };
    if (withPositionPlanes) {
        out->oow = plane(v[0]->oow, v[1]->oow, v[2]->oow);
        out->z = plane(v[0]->z, v[1]->z, v[2]->z);
    }
    out->numAttribs = numAttribs;
    for (int k = 0; k < numAttribs; ++k)
        out->attr[k] =
            plane(v[0]->attr[k] * v[0]->oow, v[1]->attr[k] * v[1]->oow, v[2]->attr[k] * v[2]->oow);
}

}  // namespace

bool SetupTriangle(const WindowVertex& in0, const WindowVertex& in1, const WindowVertex& in2,
                   int numAttribs, const PixelBox& drawn, TriangleSetup* out) {
    // Snap to the subpixel grid; draw clockwise triangles as (v1, v0, v2).
    const WindowVertex* v[3] = {&in0, &in1, &in2};
    Fixed p{{Snap(in0.x), Snap(in1.x), Snap(in2.x)}, {Snap(in0.y), Snap(in1.y), Snap(in2.y)}};
    const int sign = AreaSign(p);
    if (sign == 0) return false;
    if (sign < 0) {
        std::swap(v[0], v[1]);
        std::swap(p.x[0], p.x[1]);
        std::swap(p.y[0], p.y[1]);
    }

    // Bounding box in pixels (bottom-left fill convention), clipped to the drawn box.
    const int32_t minX = std::min({p.x[0], p.x[1], p.x[2]});
    const int32_t maxX = std::max({p.x[0], p.x[1], p.x[2]});
    const int32_t minY = std::min({p.y[0], p.y[1], p.y[2]});
    const int32_t maxY = std::max({p.y[0], p.y[1], p.y[2]});
    out->x0 = std::max(minX >> 8, drawn.x);
    out->x1 = std::min((maxX - 1) >> 8, drawn.x + drawn.width - 1);
    out->y0 = std::max((minY + 1) >> 8, drawn.y);
    out->y1 = std::min((maxY - 1 + 1) >> 8, drawn.y + drawn.height - 1);
    if (out->x0 > out->x1 || out->y0 > out->y1) return false;
    for (int i = 0; i < 3; ++i) out->edge[i] = MakeEdge(p, i);
    // A small triangle that covers no pixel centre writes nothing: no attribute planes.
    if ((out->x1 - out->x0 + 1) * (out->y1 - out->y0 + 1) <= kSmallBoxPixels) {
        bool covers = false;
        for (int y = out->y0; y <= out->y1 && !covers; ++y)
            for (int x = out->x0; x <= out->x1 && !covers; ++x) covers = Inside(*out, x, y);
        if (!covers) return false;
    }

    out->swapped = sign < 0;
    Planes(*v[0], *v[1], *v[2], numAttribs, true, out);
    return true;
}

void SetupAttributePlanes(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2,
                          int numAttribs, TriangleSetup* out) {
    if (out->swapped) {
        Planes(v1, v0, v2, numAttribs, false, out);
    } else {
        Planes(v0, v1, v2, numAttribs, false, out);
    }
}

}  // namespace pem::raster
