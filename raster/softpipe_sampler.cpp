// SPDX-License-Identifier: MIT
// softpipe_sampler.cpp — sp_tex_sample.c's path for TEX with implicit derivatives on cube maps
// and 2D textures (softpipe_sampler.h): LOD per quad, cube faces per pixel, wrap modes, image
// filters, MIP filters.
#include "raster/softpipe_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "raster/aniso.h"
#include "raster/numeric.h"
#include "raster/softpipe_tables.h"

namespace pem::raster {
namespace {

// The C macros and helpers softpipe uses, with their exact NaN behaviour.
// CLAMP(X, MIN, MAX) = X > MIN ? (X > MAX ? MAX : X) : MIN: a NaN gives MIN.
float Clamp(float x, float lo, float hi) {
    return x > lo ? (x > hi ? hi : x) : lo;
}
float Max2(float a, float b) {
    return a > b ? a : b;
}
float Frac(float f) {
    return f - std::floor(f);
}
float Lerp(float a, float v0, float v1) {
    return v0 + a * (v1 - v0);
}
float Lerp2(float a, float b, float v00, float v10, float v01, float v11) {
    const float t0 = Lerp(a, v00, v10);
    const float t1 = Lerp(a, v01, v11);
    return Lerp(b, t0, t1);
}
// (coord + size * 1024) % size in unsigned arithmetic: always inside [0, size).
int Repeat(int coord, int size) {
    const auto u = static_cast<uint32_t>(coord) + static_cast<uint32_t>(size) * 1024u;
    return static_cast<int>(u % static_cast<uint32_t>(size));
}

// One level (and face) of the texture: float texels (ubyte_to_float), w x h.
struct Image {
    const float* texels;
    int w, h;
    // The texel, or the border colour (0, 0, 0, 0) outside the image.
    RgbaF At(int x, int y) const {
        if (x < 0 || x >= w || y < 0 || y >= h) return {0.0f, 0.0f, 0.0f, 0.0f};
        const float* p =
            texels + 4 * (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x));
        return {p[0], p[1], p[2], p[3]};
    }
};

// Level `level` (a face of it for a cube). A level outside the texture (softpipe reads
// whatever lies there: only a NaN LOD gets one) gives an empty image, all border colour.
Image LevelImage(const PreparedTexture& t, int level, int face) {
    const Texture& src = *t.source;
    if (level < 0 || level >= src.NumLevels()) return {nullptr, 0, 0};
    const int w = src.LevelWidth(level), h = src.LevelHeight(level);
    const size_t faceFloats = 4 * static_cast<size_t>(w) * static_cast<size_t>(h);
    return {t.levelsF[static_cast<size_t>(level)].data() + static_cast<size_t>(face) * faceFloats,
            w, h};
}

// Wrap functions (sp_tex_sample.c wrap_nearest_* / wrap_linear_*, texel offset 0).
int WrapNearest(Wrap mode, float s, int size) {
    const auto fsize = static_cast<float>(size);
    switch (mode) {
        case Wrap::Repeat:
            return Repeat(SoftpipeIfloor(s * fsize), size);
        case Wrap::MirroredRepeat: {
            const float min = 1.0f / (2.0f * fsize);
            const float max = 1.0f - min;
            s = s + 0.0f / fsize;
            const int flr = SoftpipeIfloor(s);
            float u = Frac(s);
            if (flr & 1) u = 1.0f - u;
            if (u < min) return 0;
            if (u > max) return size - 1;
            return SoftpipeIfloor(u * fsize);
        }
        case Wrap::ClampToEdge:
        default: {
            s = s * fsize + 0.0f;
            if (s < 0.5f) return 0;
            if (s > fsize - 0.5f) return size - 1;
            return SoftpipeIfloor(s);
        }
    }
}

struct LinearTaps {
    int i0, i1;
    float w;
};

LinearTaps WrapLinear(Wrap mode, float s, int size) {
    const auto fsize = static_cast<float>(size);
    LinearTaps r;
    switch (mode) {
        case Wrap::Repeat: {
            const float u = s * fsize - 0.5f;
            r.i0 = Repeat(SoftpipeIfloor(u), size);
            r.i1 = Repeat(r.i0 + 1, size);
            r.w = Frac(u);
            return r;
        }
        case Wrap::MirroredRepeat: {
            s = s + 0.0f / fsize;
            const int flr = SoftpipeIfloor(s);
            const bool noMirror = !(flr & 1);
            float u = Frac(s);
            if (noMirror) {
                u = u * fsize - 0.5f;
            } else {
                u = 1.0f - u;
                u = u * fsize + 0.5f;
            }
            r.i0 = SoftpipeIfloor(u);
            r.i1 = noMirror ? r.i0 + 1 : r.i0 - 1;
            if (r.i0 < 0) r.i0 = 1 + r.i0;
            if (r.i0 >= size) r.i0 = size - 1;
            if (r.i1 >= size) r.i1 = size - 1;
            if (r.i1 < 0) r.i1 = 1 + r.i1;
            r.w = noMirror ? Frac(u) : Frac(1.0f - u);
            return r;
        }
        case Wrap::ClampToEdge:
        default: {
            const float u = Clamp(s * fsize + 0.0f, 0.0f, fsize) - 0.5f;
            r.i0 = SoftpipeIfloor(u);
            r.i1 = r.i0 + 1;
            if (r.i0 < 0) r.i0 = 0;
            if (r.i1 >= size) r.i1 = size - 1;
            r.w = Frac(u);
            return r;
        }
    }
}

// wrap_linear_clamp_to_border: the seamless cube's wrap (the taps may leave the face).
LinearTaps WrapLinearBorder(float s, int size) {
    const auto fsize = static_cast<float>(size);
    const float u = Clamp(s * fsize + 0.0f, -1.0f, fsize + 0.5f) - 0.5f;
    LinearTaps r;
    r.i0 = SoftpipeIfloor(u);
    r.i1 = r.i0 + 1;
    r.w = Frac(u);
    return r;
}

// Seamless neighbours: the face across each side (0 s-, 1 s+, 2 t-, 3 t+), and where a tap that
// fell off lands on it (get_next_face, get_next_xcoord, get_next_ycoord).
constexpr int kNextFace[6][4] = {{4, 5, 2, 3}, {5, 4, 2, 3}, {1, 0, 5, 4},
                                 {1, 0, 4, 5}, {1, 0, 2, 3}, {0, 1, 2, 3}};

int NextX(int face, int side, int max, int x, int y) {
    if ((face == 0 && side != 1) || (face == 1 && side == 0) || (face == 4 && side == 0) ||
        (face == 5 && side == 0))
        return max;
    if ((face == 1 && side != 0) || (face == 0 && side == 1) || (face == 4 && side == 1) ||
        (face == 5 && side == 1))
        return 0;
    if ((face == 4 && side >= 2) || (face == 2 && side == 3) || (face == 3 && side == 2)) return x;
    if ((face == 5 && side >= 2) || (face == 2 && side == 2) || (face == 3 && side == 3))
        return max - x;
    if ((face == 2 && side == 0) || (face == 3 && side == 1)) return y;
    return max - y;
}

int NextY(int face, int side, int max, int x, int y) {
    if (side <= 1 && (face <= 1 || face >= 4)) return y;
    if (face == 2 || (face == 4 && side == 3) || (face == 5 && side == 2)) return 0;
    if (face == 3 || (face == 4 && side == 2) || (face == 5 && side == 3)) return max;
    if ((face == 0 && side == 3) || (face == 1 && side == 2)) return x;
    return max - x;
}

// A texel a filter tap names: face (0 for 2D), x, y at one level; outside the level: border.
struct TexelRef {
    int face, x, y;
};

// Where a sample's texels and their weights go (matrix mode), each weight times `scale`: the
// weight of the filter that called this one. Null `out`: not recorded.
struct TapSink {
    std::vector<SoftpipeTap>* out = nullptr;
    double scale = 1.0;
    TapSink Scaled(double w) const { return {out, scale * w}; }
    void Add(int level, const TexelRef& r, double w) const {
        if (out) out->push_back({level, r.face, r.x, r.y, scale * w});
    }
};

// get_texel_cube_seamless: a tap off the face is read from the neighbour face; at a corner the
// coordinate along the edge is clamped first (no three-texel average).
TexelRef SeamlessRef(int size, int face, int x, int y) {
    const int max = size - 1;
    int side = -1;
    if (x < 0 || x >= size) {
        side = x < 0 ? 0 : 1;
        if (y < 0 || y >= size) y = std::clamp(y, 0, max);
    } else if (y < 0) {
        side = 2;
    } else if (y >= size) {
        side = 3;
    }
    if (side < 0) return {face, x, y};
    return {kNextFace[face][side], NextX(face, side, max, x, y), NextY(face, side, max, x, y)};
}

// The four taps of a bilinear filter as softpipe reads them (sp_tex_tile_cache.c): each tap
// fetches its 32x32 tile into a 16-entry direct-mapped cache (slot = tile x + 9 tile y + face +
// 7 level, mod 16) and keeps a pointer into the slot; the texels are read after all four
// fetches, so a tap whose slot a later tap refilled with another tile reads that tile at its
// own position within a tile. Taps outside the level read the border colour (not cached).
std::array<RgbaF, 4> ReadTaps(const PreparedTexture& t, int level,
                              const std::array<TexelRef, 4>& taps, std::array<TexelRef, 4>* read) {
    constexpr int kTile = 32, kTileMask = kTile - 1;
    std::array<RgbaF, 4> out;
    std::array<int, 4> slot;
    std::array<bool, 4> inside;
    for (size_t k = 0; k < 4; ++k) {
        const TexelRef& r = taps[k];
        const Image img = LevelImage(t, level, r.face);
        inside[k] = img.texels && r.x >= 0 && r.x < img.w && r.y >= 0 && r.y < img.h;
        slot[k] = (r.x / kTile + 9 * (r.y / kTile) + r.face + 7 * level) & 15;
    }
    for (size_t k = 0; k < 4; ++k) {
        if (!inside[k]) {
            out[k] = {0.0f, 0.0f, 0.0f, 0.0f};
            (*read)[k] = {-1, 0, 0};
            continue;
        }
        size_t m = k;  // the last tap that filled k's slot
        for (size_t j = k + 1; j < 4; ++j)
            if (inside[j] && slot[j] == slot[k]) m = j;
        const TexelRef& a = taps[m];
        const int x = (a.x & ~kTileMask) | (taps[k].x & kTileMask);
        const int y = (a.y & ~kTileMask) | (taps[k].y & kTileMask);
        out[k] = LevelImage(t, level, a.face).At(x, y);
        (*read)[k] = {a.face, x, y};
    }
    return out;
}

// One pixel's image filter at one level (img_filter_cube_* / img_filter_2d_*).
RgbaF ImageFilter(const PreparedTexture& t, Filter filter, int level, int face, float s, float tt,
                  const TapSink& sink) {
    const Texture& src = *t.source;
    const SamplerState& st = src.sampler;
    const bool cube = src.kind == TextureKind::Cube;
    const Image img = LevelImage(t, level, cube ? face : 0);
    if (!img.texels) return {0.0f, 0.0f, 0.0f, 0.0f};
    const int w = img.w, h = img.h;
    if (filter == Filter::Nearest) {
        // Cubes clamp to the edge (seamless: always; otherwise their wrap is clamp-to-edge).
        const Wrap ws = cube ? Wrap::ClampToEdge : st.wrapS,
                   wt = cube ? Wrap::ClampToEdge : st.wrapT;
        TexelRef r{cube ? face : 0, 0, 0};
        if (!cube && ws == Wrap::Repeat && wt == Wrap::Repeat) {
            // img_filter_2d_nearest_repeat_POT.
            r.x = SoftpipeIfloor(s * static_cast<float>(w) + 0.0f) & (w - 1);
            r.y = SoftpipeIfloor(tt * static_cast<float>(h) + 0.0f) & (h - 1);
        } else {
            r.x = WrapNearest(ws, s, w), r.y = WrapNearest(wt, tt, h);
        }
        if (r.x >= 0 && r.x < w && r.y >= 0 && r.y < h) sink.Add(level, r, 1.0);
        return img.At(r.x, r.y);
    }
    // Step 1: the taps' coordinates and weights.
    LinearTaps ls, lt;
    if (!cube && st.wrapS == Wrap::Repeat && st.wrapT == Wrap::Repeat) {
        // img_filter_2d_linear_repeat_POT: the weight is u - (float) ifloor(u).
        const float u = (s * static_cast<float>(w) - 0.5f) + 0.0f;
        const float v = (tt * static_cast<float>(h) - 0.5f) + 0.0f;
        const int uf = SoftpipeIfloor(u), vf = SoftpipeIfloor(v);
        ls = {uf & (w - 1), ((uf & (w - 1)) + 1) & (w - 1), u - static_cast<float>(uf)};
        lt = {vf & (h - 1), ((vf & (h - 1)) + 1) & (h - 1), v - static_cast<float>(vf)};
    } else if (cube && st.seamless) {
        ls = WrapLinearBorder(s, w);
        lt = WrapLinearBorder(tt, h);
    } else {
        ls = WrapLinear(cube ? Wrap::ClampToEdge : st.wrapS, s, w);
        lt = WrapLinear(cube ? Wrap::ClampToEdge : st.wrapT, tt, h);
    }
    // Step 2: the texels (seamless taps move to the neighbour face), read through the cache.
    const int f = cube ? face : 0;
    std::array<TexelRef, 4> taps = {TexelRef{f, ls.i0, lt.i0}, TexelRef{f, ls.i1, lt.i0},
                                    TexelRef{f, ls.i0, lt.i1}, TexelRef{f, ls.i1, lt.i1}};
    if (cube && st.seamless)
        for (TexelRef& r : taps) r = SeamlessRef(w, face, r.x, r.y);
    std::array<TexelRef, 4> read;
    const std::array<RgbaF, 4> tx = ReadTaps(t, level, taps, &read);
    if (sink.out) {  // Lerp2 as the weights of its four texels
        // A weight outside [0, 1] (coordinates beyond util_ifloor's range) makes the float lerps
        // no longer linear in the texels: NaN, as the llvmpipe rows of such pixels.
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const bool valid = ls.w >= 0.0f && ls.w <= 1.0f && lt.w >= 0.0f && lt.w <= 1.0f;
        const double wx[2] = {valid ? 1.0 - double(ls.w) : nan, valid ? double(ls.w) : nan};
        const double wy[2] = {1.0 - double(lt.w), double(lt.w)};
        for (size_t k = 0; k < 4; ++k)
            if (read[k].face >= 0) sink.Add(level, read[k], wx[k & 1] * wy[k >> 1]);
    }
    RgbaF out;
    for (size_t c = 0; c < 4; ++c)
        out[c] = Lerp2(ls.w, lt.w, tx[0][c], tx[1][c], tx[2][c], tx[3][c]);
    return out;
}

// The quad's LOD: compute_lambda_2d / compute_lambda_cube, bias, [min_lod, max_lod].
float QuadLod(const PreparedTexture& t, const QuadCoords& q) {
    const Texture& src = *t.source;
    constexpr int kTL = 0, kBL = 2, kBR = 3;
    const float dsdx = std::fabs(q.s[kBR] - q.s[kBL]), dsdy = std::fabs(q.s[kTL] - q.s[kBL]);
    const float dtdx = std::fabs(q.t[kBR] - q.t[kBL]), dtdy = std::fabs(q.t[kTL] - q.t[kBL]);
    float rho;
    if (src.kind == TextureKind::Cube) {
        const float dpdx = std::fabs(q.p[kBR] - q.p[kBL]), dpdy = std::fabs(q.p[kTL] - q.p[kBL]);
        const float m = Max2(Max2(Max2(dsdx, dsdy), Max2(dtdx, dtdy)), Max2(dpdx, dpdy));
        rho = m * static_cast<float>(src.width) / 2.0f;
    } else {
        const float mx = Max2(dsdx, dsdy) * static_cast<float>(src.width);
        const float my = Max2(dtdx, dtdy) * static_cast<float>(src.height);
        rho = Max2(mx, my);
    }
    const float lambda = SoftpipeFastLog2(rho) + t.lod.lodBias;
    return Clamp(lambda, t.lod.minLod, t.lod.maxLod);
}

// One pixel through the MIP filter (mip_filter_none / _nearest / _linear, and the 2D
// linear-repeat power-of-two path).
RgbaF FilterAtLod(const PreparedTexture& t, float lod, int face, float s, float tt,
                  const TapSink& sink) {
    const Texture& src = *t.source;
    const SamplerState& st = src.sampler;
    const int last = src.NumLevels() - 1;
    const bool potRepeatLinear = src.kind == TextureKind::Tex2D &&
                                 st.mipFilter == MipFilter::Linear &&
                                 st.minFilter == Filter::Linear && st.magFilter == Filter::Linear &&
                                 st.wrapS == Wrap::Repeat && st.wrapT == Wrap::Repeat;
    if (potRepeatLinear) {
        const int level0 = TruncI32(lod);
        if (static_cast<unsigned>(level0) >= static_cast<unsigned>(last))
            return ImageFilter(t, Filter::Linear, level0 < 0 ? 0 : last, face, s, tt, sink);
        const float blend = Frac(lod);
        const RgbaF a =
            ImageFilter(t, Filter::Linear, level0, face, s, tt, sink.Scaled(1.0 - double(blend)));
        const RgbaF b =
            ImageFilter(t, Filter::Linear, level0 + 1, face, s, tt, sink.Scaled(double(blend)));
        RgbaF out;
        for (size_t c = 0; c < 4; ++c) out[c] = Lerp(blend, a[c], b[c]);
        return out;
    }
    switch (st.mipFilter) {
        case MipFilter::None:
            if (st.minFilter == st.magFilter || lod <= 0.0f)
                return ImageFilter(t, st.magFilter, 0, face, s, tt, sink);
            return ImageFilter(t, st.minFilter, 0, face, s, tt, sink);
        case MipFilter::Nearest: {
            if (lod <= 0.0f) return ImageFilter(t, st.magFilter, 0, face, s, tt, sink);
            const int level = std::min(TruncI32(lod + 0.5f), last);
            return ImageFilter(t, st.minFilter, level, face, s, tt, sink);
        }
        case MipFilter::Linear:
        default: {
            if (lod <= 0.0f) return ImageFilter(t, st.magFilter, 0, face, s, tt, sink);
            const int level0 = TruncI32(lod);
            if (level0 >= last) return ImageFilter(t, st.minFilter, last, face, s, tt, sink);
            const float blend = Frac(lod);
            const RgbaF a =
                ImageFilter(t, st.minFilter, level0, face, s, tt, sink.Scaled(1.0 - double(blend)));
            const RgbaF b =
                ImageFilter(t, st.minFilter, level0 + 1, face, s, tt, sink.Scaled(double(blend)));
            RgbaF out;
            for (size_t c = 0; c < 4; ++c) out[c] = Lerp(blend, a[c], b[c]);
            return out;
        }
    }
}

// convert_cube: the face of a direction (x wins ties, then y) and its face coordinates.
void CubeFace(float rx, float ry, float rz, int* face, float* s, float* t) {
    const float arx = std::fabs(rx), ary = std::fabs(ry), arz = std::fabs(rz);
    if (arx >= ary && arx >= arz) {
        const float sign = rx >= 0.0f ? 1.0f : -1.0f;
        *face = rx >= 0.0f ? 0 : 1;
        const float ima = -0.5f / std::fabs(rx);
        *s = sign * rz * ima + 0.5f;
        *t = ry * ima + 0.5f;
    } else if (ary >= arx && ary >= arz) {
        const float sign = ry >= 0.0f ? 1.0f : -1.0f;
        *face = ry >= 0.0f ? 2 : 3;
        const float ima = -0.5f / std::fabs(ry);
        *s = -rx * ima + 0.5f;
        *t = sign * -rz * ima + 0.5f;
    } else {
        const float sign = rz >= 0.0f ? 1.0f : -1.0f;
        *face = rz >= 0.0f ? 4 : 5;
        const float ima = -0.5f / std::fabs(rz);
        *s = sign * -rx * ima + 0.5f;
        *t = ry * ima + 0.5f;
    }
}

// img_filter_2d_ewa: Heckbert's elliptical weighted average at one level. The ellipse
// A u^2 + B u v + C v^2 = F from the texel-space derivatives (scaled to the level), scaled so F
// is 1023; every texel of its bounding box with q < 1024 (q stepped incrementally along the
// row) adds kEwaWeights[trunc(q)] times its nearest-filtered texel; no texel: the pixel's own
// nearest texel.
std::array<RgbaF, 4> Ewa(const PreparedTexture& tex, int level, const std::array<float, 4>& s,
                         const std::array<float, 4>& t, const std::array<int, 4>& face, float dudx,
                         float dvdx, float dudy, float dvdy,
                         std::array<std::vector<SoftpipeTap>, 4>* taps, SoftpipeBudget* budget) {
    const Texture& src = *tex.source;
    // Step 1: the ellipse at the level, its bounding box and the scaled form.
    const float scaling = 1.0f / static_cast<float>(1 << level);
    const auto width = static_cast<float>(src.LevelWidth(level));
    const auto height = static_cast<float>(src.LevelHeight(level));
    const float ux = dudx * scaling, vx = dvdx * scaling;
    const float uy = dudy * scaling, vy = dvdy * scaling;
    float a = vx * vx + vy * vy + 1.0f;
    float b = -2.0f * (ux * vx + uy * vy);
    float c = ux * ux + uy * uy + 1.0f;
    const float f = a * c - b * b / 4.0f;
    const float d = -b * b + 4.0f * c * a;
    const float boxU = 2.0f / d * std::sqrt(d * c * f);
    const float boxV = 2.0f / d * std::sqrt(a * d * f);
    const double formScale = 1023.0 / static_cast<double>(f);
    a = static_cast<float>(static_cast<double>(a) * formScale);
    b = static_cast<float>(static_cast<double>(b) * formScale);
    c = static_cast<float>(static_cast<double>(c) * formScale);
    const float ddq = 2.0f * a;
    // Step 2: per pixel, the weighted texels of the box.
    std::array<RgbaF, 4> out;
    for (size_t j = 0; j < 4; ++j) {
        const float texU = -0.5f + s[j] * static_cast<float>(src.width) * scaling;
        const float texV = -0.5f + t[j] * static_cast<float>(src.height) * scaling;
        const int u0 = TruncI32(std::floor(texU - boxU)), u1 = TruncI32(std::ceil(texU + boxU));
        const int v0 = TruncI32(std::floor(texV - boxV)), v1 = TruncI32(std::ceil(texV + boxV));
        // softpipe scans any box; pemref stops when a frame's boxes exceed its budget.
        // (Sides are below 2^33, empty when the bounds cross; a side beyond the budget ends it,
        // so the product never overflows.)
        const int64_t su = std::max(int64_t{0}, int64_t{u1} - u0 + 1);
        const int64_t sv = std::max(int64_t{0}, int64_t{v1} - v0 + 1);
        const int64_t boxTexels =
            std::max(su, sv) > SoftpipeBudget::kEwaTexels ? std::max(su, sv) : su * sv;
        budget->ewaTexels -= boxTexels;
        if (budget->ewaTexels < 0)
            throw std::invalid_argument(
                "softpipe profile: the frame's anisotropic footprints exceed " +
                std::to_string(SoftpipeBudget::kEwaTexels) + " texels (one of " +
                std::to_string(boxTexels) + " at level " + std::to_string(level) +
                "): a LOD clamped far below the footprint");
        const float uStart = static_cast<float>(u0) - texU;
        RgbaF num = {0.0f, 0.0f, 0.0f, 0.0f};
        float den = 0.0f;
        const TapSink sink{taps ? &(*taps)[j] : nullptr, 1.0};
        for (int v = v0; v <= v1; ++v) {
            const float vv = static_cast<float>(v) - texV;
            float dq = a * (2.0f * uStart + 1.0f) + b * vv;
            float q = (c * vv + b * uStart) * vv + a * uStart * uStart;
            for (int u = u0; u <= u1; ++u) {
                if (q < 1024.0f) {
                    const float weight = kEwaWeights[q >= 0.0f ? TruncI32(q) : 0];
                    const RgbaF texel = ImageFilter(
                        tex, Filter::Nearest, level, face[j], static_cast<float>(u) / width,
                        static_cast<float>(v) / height, sink.Scaled(double(weight)));
                    for (size_t k = 0; k < 4; ++k) num[k] += weight * texel[k];
                    den += weight;
                }
                q += dq;
                dq += ddq;
            }
        }
        if (den <= 0.0f) {
            num = ImageFilter(tex, Filter::Nearest, level, face[j], s[j], t[j], sink);
            den = 1.0f;
        }
        if (sink.out)  // the weights of num / den
            for (SoftpipeTap& tap : *sink.out) tap.weight = tap.weight / double(den);
        for (size_t k = 0; k < 4; ++k) out[j][k] = num[k] / den;
    }
    return out;
}

// mip_filter_linear_aniso (GL_LINEAR_MIPMAP_LINEAR with max anisotropy >= 2): the LOD from the
// ellipse's minor axis (its squared length at least major^2 / max_aniso^2), lambda = 0.5 fast
// log2(minor^2) + bias, clamped; one level trunc(lambda), no blend between levels; at or past
// the last level the last level's nearest texel.
std::array<RgbaF, 4> SampleAniso(const PreparedTexture& tex, const std::array<float, 4>& s,
                                 const std::array<float, 4>& t, const std::array<int, 4>& face,
                                 std::array<std::vector<SoftpipeTap>, 4>* taps,
                                 SoftpipeBudget* budget) {
    const Texture& src = *tex.source;
    constexpr size_t kTL = 0, kBL = 2, kBR = 3;
    // Step 1: texel-space derivatives and the minor axis.
    const auto sToU = static_cast<float>(src.width), tToV = static_cast<float>(src.height);
    const float dudx = (s[kBR] - s[kBL]) * sToU, dudy = (s[kTL] - s[kBL]) * sToU;
    const float dvdx = (t[kBR] - t[kBL]) * tToV, dvdy = (t[kTL] - t[kBL]) * tToV;
    const float px2 = dudx * dudx + dvdx * dvdx, py2 = dudy * dudy + dvdy * dvdy;
    const int maxAniso = PipeMaxAnisotropy(src.sampler.maxAnisotropy);
    const auto maxEccentricity = static_cast<float>(maxAniso * maxAniso);
    const float pmax2 = px2 < py2 ? py2 : px2;
    float pmin2 = px2 < py2 ? px2 : py2;
    if (pmax2 / pmin2 > maxEccentricity) pmin2 = pmax2 / maxEccentricity;
    // Step 2: the level.
    const float lambda = 0.5f * SoftpipeFastLog2(pmin2) + tex.lod.lodBias;
    const int level = TruncI32(Clamp(lambda, tex.lod.minLod, tex.lod.maxLod));
    const int last = src.NumLevels() - 1;
    if (level < last) return Ewa(tex, level, s, t, face, dudx, dvdx, dudy, dvdy, taps, budget);
    std::array<RgbaF, 4> out;
    for (size_t j = 0; j < 4; ++j)
        out[j] = ImageFilter(tex, Filter::Nearest, last, face[j], s[j], t[j],
                             {taps ? &(*taps)[j] : nullptr, 1.0});
    return out;
}

}  // namespace

float SoftpipeFastLog2(float x) {
    const uint32_t bits = FloatBits(x);
    const auto epart = static_cast<float>(static_cast<int32_t>((bits & 0x7f800000u) >> 23) - 127);
    const uint32_t index = ((bits & 0x007fffffu) + (1u << 14)) >> 15;
    return epart + kLog2Table[index];
}

int32_t SoftpipeIfloor(float x) {
    const double af = (3 << 22) + 0.5 + static_cast<double>(x);
    const double bf = (3 << 22) + 0.5 - static_cast<double>(x);
    const uint32_t ai = FloatBits(static_cast<float>(af));
    const uint32_t bi = FloatBits(static_cast<float>(bf));
    return static_cast<int32_t>(ai - bi) >> 1;
}

void SampleSoftpipeQuad(const PreparedTexture& texture, const QuadCoords& q,
                        std::array<RgbaF, 4>* colour, SoftpipeBudget* budget,
                        std::array<std::vector<SoftpipeTap>, 4>* taps) {
    const SamplerState& st = texture.source->sampler;
    const float lod = QuadLod(texture, q);
    // Step 1: cube faces and face coordinates per pixel (convert_cube).
    std::array<int, 4> face{};
    std::array<float, 4> s = q.s, t = q.t;
    if (texture.source->kind == TextureKind::Cube)
        for (size_t j = 0; j < 4; ++j) CubeFace(q.s[j], q.t[j], q.p[j], &face[j], &s[j], &t[j]);
    // Step 2: the MIP filter.
    if (taps)
        for (std::vector<SoftpipeTap>& v : *taps) v.clear();
    if (st.mipFilter == MipFilter::Linear && PipeMaxAnisotropy(st.maxAnisotropy) > 1) {
        *colour = SampleAniso(texture, s, t, face, taps, budget);
        return;
    }
    for (size_t j = 0; j < 4; ++j)
        (*colour)[j] =
            FilterAtLod(texture, lod, face[j], s[j], t[j], {taps ? &(*taps)[j] : nullptr, 1.0});
}

}  // namespace pem::raster
