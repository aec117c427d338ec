// SPDX-License-Identifier: MIT
// texgen.h — per-vertex texture coordinates and modulation for layered EMs, and the raster/
// passes they make (PEM §4 and hybrid §5: "texgen").
//
//   std::vector<ExitRay> exits = TermExits(lp.tess.paths, /*term=*/0);          // hybrid mode
//   std::vector<ExitRay> exits = ReflectionExits(mesh, camera.eye, f0);         // PEM mode
//   std::vector<glm::vec3> coords = ShellCoords(exits, shell, emOrigin);
//   raster::Pass pass = LayerPass(mesh, DrawOrder(mesh, camera), coords, exits, camera, opts);
//
// Exit rays: hybrid mode takes each vertex's greedy path of the term (its exit ray, weight F·G);
// PEM mode reflects the eye ray off the vertex normal (weight: Schlick's F with the mirror's F0,
// per vertex, interpolated by the rasterizer as the paper does). Texture coordinate of a layer:
// the exit ray's hit on the layer's shell minus the EM origin (cube maps need no normalization);
// a ray that misses the shell (it starts outside, running away) uses its direction (the layer
// at infinity). Vertices without a path get weight 0.
// Passes: clip-space positions from the camera's ViewProjection (near/far from the mesh depth
// range, depth clamped); back-facing triangles (every vertex normal away from the eye) left out;
// the rest drawn in mesh order (a triangle whose centroid distance is not a number is left out).
// Every lens pass tests depth (LayerDepthTest), so the order decides only exact depth ties (the
// first drawn wins); mesh order keeps consecutive triangles close on the screen.
// Colour = (F·G, 1) when modulating, white otherwise; alpha stays the texture's coverage.
// Not here: the vertex rays (lens_paths.h), compositing of layers and terms (renderer.h).
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <vector>

#include "raster/camera.h"
#include "raster/frame.h"
#include "runtime/lens_paths.h"
#include "runtime/parameterization.h"
#include "trace/shell.h"

namespace pem::runtime {

struct ExitRay {
    glm::vec3 origin{0.0f};
    glm::vec3 dir{0.0f, 0.0f, 1.0f};  // unit
    glm::vec3 weight{0.0f};           // F·G per channel
    bool valid = false;               // false: no path (weight 0)
};

// The mesh a pass draws: positions, normals and triangles (a LensMesh or a tessellation).
struct PassMesh {
    const std::vector<glm::vec3>* positions = nullptr;
    const std::vector<glm::vec3>* normals = nullptr;
    const std::vector<glm::uvec3>* triangles = nullptr;
};
PassMesh MeshOf(const LensMesh& mesh);
PassMesh MeshOf(const trace::TessellationResult& tess);

// Threads: the functions taking `threads` split their vertices or triangles into chunks done in
// parallel; the result is the same for any thread count.

// Step: exit rays.
std::vector<ExitRay> TermExits(const std::vector<std::optional<trace::VertexPaths>>& paths,
                               int term, int threads = 1);
std::vector<ExitRay> ReflectionExits(const PassMesh& mesh, const glm::vec3& eye,
                                     const glm::vec3& f0);

// Step: texture coordinates on a layer's shell.
std::vector<glm::vec3> ShellCoords(const std::vector<ExitRay>& exits, const trace::Shell& shell,
                                   const glm::vec3& emOrigin, int threads = 1);

// Step: the triangles drawn, in mesh order (front-facing, finite).
std::vector<uint32_t> DrawOrder(const PassMesh& mesh, const raster::Camera& camera,
                                int threads = 1);

struct PassOptions {
    int texture = 0;        // raster::Frame::textures index for unit 0
    bool modulate = false;  // colour = (F·G, 1) instead of white
    raster::BlendState blend = raster::BlendState::None();
    std::optional<raster::DepthTest> depthTest;  // LayerDepthTest(...) in a frame with kLensDepth
    // The map's layout (parameterization.h): other than the cube, the pass's cube coordinates
    // become the layout's (ToLayout), the sphere map's in the eye space of eyeFromWorld (the
    // drawing camera's view rotation, as GL's texgen uses the current modelview).
    Parameterization parameterization = Parameterization::Cube;
    glm::mat3 eyeFromWorld{1.0f};
};

// The papers' multipass hardware, with a Z-buffer: the first (outermost) pass of a lens group
// writes depth (LESS), the passes that draw the same geometry after it test EQUAL without
// writing, so every layer lands on the visible surface only — hidden parts of a non-convex lens
// (a cup's inner wall behind its outer wall) add nothing, to the frames and to the rendering
// matrices alike.
inline constexpr raster::DepthBuffer kLensDepth{raster::DepthFormat::Z24, 1.0f};
raster::DepthTest LayerDepthTest(bool firstPass);

// The first pass of a frame that fits one inner layer alone (the PEM split's local map, drawn
// on fewer triangles than the layer under it): every triangle of `order`, untextured, colour 0,
// depth written (LESS), so that the layer's pass after it (EQUAL) lands where the renderer's does.
raster::Pass DepthOnlyPass(const PassMesh& mesh, const std::vector<uint32_t>& order,
                           const glm::mat4& viewProjection);

// Clip-space transform shared by every pass of a frame: near/far around the mesh.
glm::mat4 PassViewProjection(const PassMesh& mesh, const raster::Camera& camera);

// A layer's passes: one per texture of the map (MapLayout::textures; ToLayout), the first
// binding options.texture, the next options.texture + 1.
std::vector<raster::Pass> LayerPass(const PassMesh& mesh, const std::vector<uint32_t>& order,
                                    const std::vector<glm::vec3>& coords,
                                    const std::vector<ExitRay>& exits,
                                    const glm::mat4& viewProjection, const PassOptions& options);

// LayerPass in two steps, for many passes over one mesh: what every layer shares (clip-space
// positions, the index list), then each layer's passes written into `passes` (as many as the
// layout's textures), reusing their storage.
struct PassGeometry {
    std::vector<glm::vec4> clip;
    std::vector<uint32_t> indices;
};
PassGeometry MakePassGeometry(const PassMesh& mesh, const std::vector<uint32_t>& order,
                              const glm::mat4& viewProjection, int threads = 1);
void FillLayerPass(const PassGeometry& geometry, const std::vector<glm::vec3>& coords,
                   const std::vector<ExitRay>& exits, const PassOptions& options,
                   std::span<raster::Pass> passes, int threads = 1);

}  // namespace pem::runtime
