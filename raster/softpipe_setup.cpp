// SPDX-License-Identifier: MIT
// softpipe_setup.cpp — sp_setup.c's triangle path in our own words (softpipe_setup.h): vertex
// sort, plane coefficients, edges, the two half-triangles and the span-to-quad flush.
#include "raster/softpipe_setup.h"

#include <algorithm>
#include <cmath>

#include "raster/numeric.h"

namespace pem::raster {
namespace {

// The three vertices by window y, as sp_setup.c's setup_sort_vertices compares them.
void SortByY(const WindowVertex* v0, const WindowVertex* v1, const WindowVertex* v2,
             const WindowVertex* sorted[3]) {
    const float y0 = v0->y, y1 = v1->y, y2 = v2->y;
    if (y0 <= y1) {
        if (y1 <= y2) {
            sorted[0] = v0, sorted[1] = v1, sorted[2] = v2;
        } else if (y2 <= y0) {
            sorted[0] = v2, sorted[1] = v0, sorted[2] = v1;
        } else {
            sorted[0] = v0, sorted[1] = v2, sorted[2] = v1;
        }
    } else {
        if (y0 <= y2) {
            sorted[0] = v1, sorted[1] = v0, sorted[2] = v2;
        } else if (y2 <= y1) {
            sorted[0] = v2, sorted[1] = v1, sorted[2] = v0;
        } else {
            sorted[0] = v1, sorted[1] = v2, sorted[2] = v0;
        }
    }
}

// tri_linear_coeff: the plane through (vmin, a[0]), (vmid, a[1]), (vmax, a[2]).
Plane LinearPlane(const SpTriangle& t, const WindowVertex& vmin, float ooa, const float a[3]) {
    const float botda = a[1] - a[0];
    const float majda = a[2] - a[0];
    const float pa = t.ebot.dy * majda - botda * t.emaj.dy;
    const float pb = t.emaj.dx * botda - majda * t.ebot.dx;
    Plane p;
    p.dadx = pa * ooa;
    p.dady = pb * ooa;
    p.a0 = a[0] - (p.dadx * (vmin.x - 0.5f) + p.dady * (vmin.y - 0.5f));
    return p;
}

// setup_tri_edges: where each edge starts, its slope and its number of rows.
void SetupEdge(SpEdge* e, float startX, float startY, float endY) {
    e->sy = std::ceil(startY);
    e->lines = TruncI32(std::ceil(endY - e->sy));
    e->dxdy = e->dy != 0.0f ? e->dx / e->dy : 0.0f;  // NaN dy divides, as C's `dy ? :` does
    e->sx = startX + (e->sy - startY) * e->dxdy;
}

// The two rows of one quad row being gathered (sp_setup.c's setup->span).
struct Spans {
    int y = 0;
    int left[2] = {1000000, 1000000};
    int right[2] = {0, 0};
};

constexpr int kSpanStep = 16;  // MAX_QUADS pixels per flush chunk

unsigned RowMask(int left, int right, int x) {
    const unsigned skipLeft = static_cast<unsigned>(std::clamp(left - x, 0, kSpanStep));
    const unsigned skipRight =
        static_cast<unsigned>(std::clamp(x + kSpanStep - right, 0, kSpanStep));
    const unsigned skipMaskLeft = (1u << skipLeft) - 1u;
    const unsigned skipMaskRight = ~0u << (kSpanStep - skipRight);
    return ~skipMaskLeft & ~skipMaskRight;
}

// flush_spans: the gathered row pair as quads, in chunks of 16 pixels, left to right.
void FlushSpans(Spans* s, const std::function<void(int, int, unsigned)>& quad) {
    const int minLeft = std::min(s->left[0], s->left[1]) & ~(kSpanStep - 1);
    const int maxRight = std::max(s->right[0], s->right[1]);
    for (int x = minLeft; x < maxRight; x += kSpanStep) {
        unsigned mask0 = RowMask(s->left[0], s->right[0], x);
        unsigned mask1 = RowMask(s->left[1], s->right[1], x);
        for (int lx = x; mask0 | mask1; lx += 2, mask0 >>= 2, mask1 >>= 2) {
            const unsigned quadMask = (mask0 & 3u) | ((mask1 & 3u) << 2);
            if (quadMask) quad(lx, s->y, quadMask);
        }
    }
    *s = Spans{};
}

// subtriangle: `lines` rows between two edges starting at the same row, clipped to the
// framebuffer; both edges are then advanced past them.
void HalfTriangle(SpEdge* left, SpEdge* right, int lines, int width, int height, Spans* spans,
                  const std::function<void(int, int, unsigned)>& quad) {
    const int sy = TruncI32(left->sy);
    const int64_t start = std::max<int64_t>(sy, 0) - sy;
    const int64_t finish = std::min<int64_t>(int64_t{sy} + lines, height) - sy;
    for (int64_t y = start; y < finish; ++y) {
        const float fy = static_cast<float>(y);
        const int l = std::max(TruncI32(left->sx + fy * left->dxdy), 0);
        const int r = std::min(TruncI32(right->sx + fy * right->dxdy), width);
        if (l >= r) continue;
        const int row = static_cast<int>(sy + y);
        if ((row & ~1) != spans->y) {
            FlushSpans(spans, quad);
            spans->y = row & ~1;
        }
        spans->left[row & 1] = l;
        spans->right[row & 1] = r;
    }
    const float fl = static_cast<float>(lines);
    left->sx += fl * left->dxdy;
    right->sx += fl * right->dxdy;
    left->sy += fl;
    right->sy += fl;
}

}  // namespace

bool SetupSoftpipeTriangle(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2,
                           int numAttribs, SpTriangle* out) {
    SpTriangle& t = *out;
    // Step 1: sort by y; the edges' extents and the area.
    const WindowVertex* v[3];
    SortByY(&v0, &v1, &v2, v);
    const WindowVertex &vmin = *v[0], &vmid = *v[1], &vmax = *v[2];
    t.ebot.dx = vmid.x - vmin.x, t.ebot.dy = vmid.y - vmin.y;
    t.emaj.dx = vmax.x - vmin.x, t.emaj.dy = vmax.y - vmin.y;
    t.etop.dx = vmax.x - vmid.x, t.etop.dy = vmax.y - vmid.y;
    const float area = t.emaj.dx * t.ebot.dy - t.ebot.dx * t.emaj.dy;
    const float ooa = 1.0f / area;
    if (std::isinf(ooa) || std::isnan(ooa)) return false;
    t.majorLeft = ooa < 0.0f;
    // Step 2: plane coefficients (z and 1/w linear, the attributes times 1/w).
    const float z[3] = {vmin.z, vmid.z, vmax.z};
    const float w[3] = {vmin.oow, vmid.oow, vmax.oow};
    t.z = LinearPlane(t, vmin, ooa, z);
    t.oow = LinearPlane(t, vmin, ooa, w);
    t.numAttribs = numAttribs;
    for (int k = 0; k < numAttribs; ++k) {
        const auto i = static_cast<size_t>(k);
        const float a[3] = {vmin.attr[i] * vmin.oow, vmid.attr[i] * vmid.oow,
                            vmax.attr[i] * vmax.oow};
        t.attr[i] = LinearPlane(t, vmin, ooa, a);
    }
    // Step 3: edges, with the half-pixel offsets of sp_setup.c (x + 0.5, y - 0.5).
    const float minX = vmin.x + 0.5f, midX = vmid.x + 0.5f;
    const float minY = vmin.y - 0.5f, midY = vmid.y - 0.5f, maxY = vmax.y - 0.5f;
    SetupEdge(&t.emaj, minX, minY, maxY);
    SetupEdge(&t.etop, midX, midY, maxY);
    SetupEdge(&t.ebot, minX, minY, midY);
    return true;
}

void ScanSoftpipeTriangle(const SpTriangle& setup, int width, int height,
                          const std::function<void(int, int, unsigned)>& quad) {
    SpTriangle t = setup;  // the edges advance
    Spans spans;
    const int botLines = t.ebot.lines, topLines = t.etop.lines;
    if (t.majorLeft) {
        HalfTriangle(&t.emaj, &t.ebot, botLines, width, height, &spans, quad);
        HalfTriangle(&t.emaj, &t.etop, topLines, width, height, &spans, quad);
    } else {
        HalfTriangle(&t.ebot, &t.emaj, botLines, width, height, &spans, quad);
        HalfTriangle(&t.etop, &t.emaj, topLines, width, height, &spans, quad);
    }
    FlushSpans(&spans, quad);
}

}  // namespace pem::raster
