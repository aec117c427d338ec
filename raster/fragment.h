// SPDX-License-Identifier: MIT
// fragment.h — the fragment stage (interpolation, texture sampling, shading, blending) as
// render.cpp calls it, in two builds of the same source: a baseline x86-64/aarch64 build and, on
// x86-64, a build for CPUs with AVX2 and FMA (std::fma and floor become single instructions instead
// of library calls). Both give the same bits: the code only uses IEEE operations whose results do
// not depend on the instruction set, and the compiler never contracts a*b+c (-ffp-contract=off).
// The implementation is in shade_impl.h (and the *_impl.h headers it includes), compiled with
// internal linkage into fragment_base.cpp and fragment_fma.cpp. PEM_ISA=base forces the baseline.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "raster/matrix_rows.h"
#include "raster/render.h"
#include "raster/triangle_setup.h"

namespace pem::raster {

// What a band worker writes into: the picture, and (matrix mode) the rows of A too; and the depth
// buffer when the frame has one (depth.h values, rows top-down like the picture).
struct FragmentTarget {
    const PreparedFrame* frame;
    RenderOptions options;
    Image8* image8;
    ImageF* imageF;                          // a float colour buffer (FloatTarget)
    RenderingMatrix* matrix;                 // matrix mode: offsets per row
    MatrixRows* rows;                        // matrix mode: taps per pixel
    std::vector<uint32_t>* depth = nullptr;  // Frame::depth set: its buffer
    PixelBox box;  // the pixels the buffers hold (frame.h DrawnBox), rows top-down
    // Another target of the same draw whose depth buffer equals this one's after every fragment
    // (the same positions, depth tests and order: render.cpp SameDepthHistory): the tests are
    // made on its buffer only, and this one has none (`depth` null) until it is copied at the end.
    const FragmentTarget* depthTwin = nullptr;

    // Index of pixel (x, y) (GL window coordinates, inside `box`) in the buffers.
    size_t Index(int x, int y) const {
        return static_cast<size_t>(box.y + box.height - 1 - y) * static_cast<size_t>(box.width) +
               static_cast<size_t>(x - box.x);
    }
};

constexpr int kBandQuadRows = 4;  // rows of 2x2 quads per band (8 pixel rows)

// One draw of a pass into one target.
using PassDraw = std::pair<const FragmentTarget*, const Pass*>;

// Set-up triangles of one pass geometry, per variant (render.cpp DrawPass): chunk[k][i] of every
// k is the same triangle with variant k's attribute planes.
using SetupChunk = std::vector<std::vector<TriangleSetup>>;

// Draws the triangles of one pass geometry into the row bands owned by `worker` of `workers`
// (band b of kBandQuadRows quad rows belongs to worker b % workers), for every draw. The passes
// of all draws have the same positions and indices, so coverage and fragment depth are computed
// once per lane group (each draw tests its own depth buffer); the draws of one variant have equal
// vertices, so interpolation and the filter footprints of equally shaped textures are computed
// once per lane group and variant.
using DrawBandsFn = void (*)(const std::vector<std::vector<PassDraw>>& variants,
                             const SetupChunk& triangles, int worker, int workers);

DrawBandsFn DrawBandsBase();
DrawBandsFn DrawBandsFma();  // nullptr when not built (non-x86-64 or unoptimised builds)

// The variant for this CPU (honouring PEM_ISA=base), and its name ("base" or "avx2-fma").
DrawBandsFn SelectDrawBands(const char** name = nullptr);

}  // namespace pem::raster
