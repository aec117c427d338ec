// SPDX-License-Identifier: MIT
// stability_scene.cpp — the scene family of the stability suite (stability.h): a glTF with
// sliver, tiny and degenerate triangles loaded by trace::LoadScene and traced by Embree and the
// brute-force oracle; glTF files with NaN / Inf (generated here, plus tests/data/bad_scenes)
// that must give a one-line pem::base::InputError.
// Generated files go to a fresh folder under the system temp directory, removed afterwards.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "base/input_error.h"
#include "trace/brute_force.h"
#include "trace/embree_scene.h"
#include "trace/scene.h"
#include "viewer_tty/stability/stability_internal.h"

namespace pem::stability {
namespace {

namespace fs = std::filesystem;
using stability::Checks;
using stability::Format;

// A temp folder for one case, removed when the case ends.
class TempDir {
  public:
    explicit TempDir(const std::string& tag) {
        path_ = fs::temp_directory_path() /
                ("pemref_stability_" + tag + "_" + std::to_string(::getpid()));
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

struct MeshSpec {
    std::vector<float> positions;  // xyz per vertex
    std::vector<float> normals;    // xyz per vertex, or empty
    std::vector<uint32_t> indices;
    std::string nodeExtra;  // raw JSON members added to the node, e.g. "\"scale\": [...]"
};

std::string FloatList(const float* v, int n) {
    std::string s = "[";
    for (int k = 0; k < n; ++k)
        s += Format("%s%.9g", k ? ", " : "", std::isfinite(v[k]) ? static_cast<double>(v[k]) : 0.0);
    return s + "]";
}

// Writes dir/name.gltf and dir/name.bin (positions, normals, uint32 indices) and returns the
// .gltf path.
std::string WriteGltf(const fs::path& dir, const std::string& name, const MeshSpec& m) {
    const size_t nv = m.positions.size() / 3;
    std::vector<char> bin;
    const auto append = [&bin](const void* data, size_t bytes) {
        const char* p = static_cast<const char*>(data);
        bin.insert(bin.end(), p, p + bytes);
    };
    append(m.positions.data(), m.positions.size() * 4);
    const size_t normalOffset = bin.size();
    append(m.normals.data(), m.normals.size() * 4);
    const size_t indexOffset = bin.size();
    append(m.indices.data(), m.indices.size() * 4);
    std::ofstream(dir / (name + ".bin"), std::ios::binary)
        .write(bin.data(), static_cast<long>(bin.size()));
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const float v = m.positions[i];
        if (!std::isfinite(v)) continue;
        lo[i % 3] = std::min(lo[i % 3], v), hi[i % 3] = std::max(hi[i % 3], v);
    }
    std::string attributes = "\"POSITION\": 0", views, accessors;
    views = Format("{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": %zu}", normalOffset);
    accessors = Format(
        "{\"bufferView\": 0, \"componentType\": 5126, \"count\": %zu, \"type\": \"VEC3\", "
        "\"min\": %s, \"max\": %s}",
        nv, FloatList(lo, 3).c_str(), FloatList(hi, 3).c_str());
    int next = 1;
    if (!m.normals.empty()) {
        attributes += ", \"NORMAL\": 1";
        views += Format(", {\"buffer\": 0, \"byteOffset\": %zu, \"byteLength\": %zu}", normalOffset,
                        indexOffset - normalOffset);
        accessors += Format(
            ", {\"bufferView\": 1, \"componentType\": 5126, \"count\": %zu, \"type\": \"VEC3\"}",
            nv);
        next = 2;
    }
    views += Format(", {\"buffer\": 0, \"byteOffset\": %zu, \"byteLength\": %zu}", indexOffset,
                    m.indices.size() * 4);
    accessors += Format(
        ", {\"bufferView\": %d, \"componentType\": 5125, \"count\": %zu, \"type\": \"SCALAR\"}",
        next, m.indices.size());
    const std::string node =
        "{\"name\": \"mesh\", \"mesh\": 0" + (m.nodeExtra.empty() ? "" : ", " + m.nodeExtra) + "}";
    const std::string json = Format(
        "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}], "
        "\"nodes\": [%s], \"meshes\": [{\"primitives\": [{\"attributes\": {%s}, \"indices\": %d, "
        "\"mode\": 4}]}], \"buffers\": [{\"byteLength\": %zu, \"uri\": \"%s.bin\"}], "
        "\"bufferViews\": [%s], \"accessors\": [%s]}",
        node.c_str(), attributes.c_str(), next, bin.size(), name.c_str(), views.c_str(),
        accessors.c_str());
    const std::string path = (dir / (name + ".gltf")).string();
    std::ofstream(path) << json << "\n";
    return path;
}

MeshSpec Triangles(const std::vector<std::array<float, 9>>& tris) {
    MeshSpec m;
    for (const auto& t : tris) {
        for (float v : t) m.positions.push_back(v);
        for (int k = 0; k < 3; ++k) m.indices.push_back(static_cast<uint32_t>(m.indices.size()));
    }
    return m;
}

// Sliver and degenerate triangles ------------------------------------------------------------

bool Finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Longest edge squared over twice the area: 1 for a right isoceles triangle, huge for slivers.
double Aspect(const trace::Object& o, int prim) {
    const trace::TriangleCorners c = trace::CornersOf(o, prim);
    const glm::dvec3 a(c.p[0]), b(c.p[1]), d(c.p[2]);
    const double area2 = glm::length(glm::cross(b - a, d - a));
    const double longest =
        std::max({glm::dot(b - a, b - a), glm::dot(d - b, d - b), glm::dot(a - d, a - d)});
    return longest / area2;
}

// Rays at every triangle's centroid and vertices and along its plane, Embree against the
// brute-force intersector: hit/miss agreement, finite hits and surface points, worst |Δt|.
struct ProbeResult {
    int rays = 0, agree = 0, hits = 0;
    double dt = 0.0;
};
ProbeResult ProbeSlivers(const trace::Scene& scene, const StabilityOptions& options,
                         Checks* checksOut) {
    Checks& checks = *checksOut;
    trace::EmbreeOptions eo;
    eo.threads = std::max(1, options.threads);
    const trace::EmbreeDevice device(eo);
    const trace::EmbreeScene embree(device, scene);
    int rays = 0, agree = 0, hits = 0;
    double dt = 0.0;
    for (const trace::Object& o : scene.objects)
        for (size_t p = 0; p < o.triangles.size(); ++p) {
            const trace::TriangleCorners k = trace::CornersOf(o, static_cast<int>(p));
            const glm::vec3 centroid = (k.p[0] + k.p[1] + k.p[2]) / 3.0f;
            const bool control =
                Aspect(o, static_cast<int>(p)) < 10.0 && glm::distance(k.p[0], k.p[1]) > 0.1f;
            std::vector<raster::Ray> probe;
            for (const glm::vec3& q : {centroid, k.p[0], k.p[1], k.p[2]})
                probe.push_back({q + glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)});
            probe.push_back({glm::vec3(centroid.x - 50.0f, centroid.y, 0.0f), glm::vec3(1, 0, 0)});
            for (size_t r = 0; r < probe.size(); ++r) {
                const trace::Hit e = embree.Intersect(probe[r]);
                const trace::Hit b = trace::BruteForceIntersect(scene, probe[r], 0.0f, INFINITY);
                ++rays;
                agree += e.valid == b.valid;
                for (const trace::Hit* h : {&e, &b}) {
                    if (!h->valid) continue;
                    ++hits;
                    checks.Expect(std::isfinite(h->t) && Finite(h->ng), "non-finite hit");
                    const trace::SurfacePoint sp = trace::SurfaceAt(
                        scene.objects[static_cast<size_t>(h->object)], h->prim, h->u, h->v);
                    checks.Expect(Finite(sp.position) && Finite(sp.normal),
                                  "non-finite surface point");
                }
                if (e.valid && b.valid)
                    dt = std::max(dt, static_cast<double>(std::fabs(e.t - b.t)));
                if (control && r == 0)
                    checks.Expect(e.valid && b.valid, "control triangle's centroid missed");
            }
        }
    return {rays, agree, hits, dt};
}

void SliverScene(const StabilityOptions& options, StabilityCase* c) {
    TempDir dir("sliver");
    const std::string path =
        WriteGltf(dir.path(), "slivers",
                  Triangles({{20, 0, 0, 21, 0, 0, 20, 1, 0},                // control
                             {2, 0, 0, 3, 0, 0, 3, 1e-6f, 0},               // needle
                             {4, 0, 0, 5, 0, 0, 6, 0, 0},                   // collinear: dropped
                             {7, 0, 0, 7, 0, 0, 8, 1, 0},                   // repeated: dropped
                             {0, 0, 0, 1e-20f, 0, 0, 0, 1e-20f, 0},         // tiny
                             {0, 10, 0, 100, 10, 0, 100, 10.00001f, 0}}));  // long sliver
    Checks checks;
    const trace::Scene scene = trace::LoadScene(path);
    checks.Expect(scene.droppedDegenerate == 2,
                  Format("%d degenerate triangles dropped (want 2)", scene.droppedDegenerate));
    double aspect = 1.0;
    for (const trace::Object& o : scene.objects) {
        for (const glm::vec3& n : o.normals)
            checks.Expect(Finite(n) && std::fabs(glm::length(n) - 1.0f) < 1e-5f,
                          "non-finite or non-unit normal");
        for (size_t p = 0; p < o.triangles.size(); ++p)
            aspect = std::max(aspect, Aspect(o, static_cast<int>(p)));
    }
    const ProbeResult pr = ProbeSlivers(scene, options, &checks);
    const int rays = pr.rays, agree = pr.agree, hits = pr.hits;
    const double dt = pr.dt;
    checks.Expect(dt < 1e-5, Format("Embree and brute force t differ by %.3g", dt));
    c->residual = dt;
    c->condition = aspect;
    c->detail = Format(
        "glTF with a control triangle, a 1e-6 needle, a 1e-20 tiny triangle, a 100:1e-5 sliver, a "
        "collinear and a repeated-vertex triangle: %zu kept, %d dropped as degenerate; %d rays "
        "(centroid, vertices, in-plane), Embree and brute force agree on hit/miss for %d, %d hits "
        "in all; residual = worst |t_embree - t_brute| on common hits; condition = worst "
        "triangle aspect (longest edge^2 / 2 area)",
        scene.NumTriangles(), scene.droppedDegenerate, rays, agree, hits);
    stability::Conclude(
        checks, Format("loaded, degenerate dropped, finite hits (%d/%d rays agree)", agree, rays),
        c);
}

// NaN / Inf in scene files -----------------------------------------------------------------------

struct BadFile {
    std::string path, cause;  // cause: a substring the message must contain ("" = any)
};

std::vector<BadFile> GeneratedBadFiles(const fs::path& dir) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<BadFile> out;
    out.push_back(
        {WriteGltf(dir, "nan_position", Triangles({{0, 0, 0, nan, 0, 0, 0, 1, 0}})), "non-finite"});
    out.push_back({WriteGltf(dir, "inf_position", Triangles({{0, 0, 0, 1, 0, 0, 0, -inf, 0}})),
                   "non-finite"});
    MeshSpec normals = Triangles({{0, 0, 0, 1, 0, 0, 0, 1, 0}});
    normals.normals = {0, 0, 1, 0, 0, 1, nan, 0, 1};
    out.push_back({WriteGltf(dir, "nan_normal", normals), "non-finite"});
    MeshSpec scaled = Triangles({{0, 0, 0, 1, 0, 0, 0, 1, 0}});
    scaled.nodeExtra = "\"scale\": [1e300, 1e300, 1e300]";
    out.push_back({WriteGltf(dir, "overflow_scale", scaled), "out of range"});
    MeshSpec literal = Triangles({{0, 0, 0, 1, 0, 0, 0, 1, 0}});
    literal.nodeExtra = "\"translation\": [1e400, 0, 0]";
    out.push_back({WriteGltf(dir, "inf_literal", literal), ""});
    return out;
}

void NonFiniteScenes(const StabilityOptions& options, StabilityCase* c) {
    TempDir dir("nonfinite");
    std::vector<BadFile> files = GeneratedBadFiles(dir.path());
    if (!options.dataDir.empty()) {
        const std::string bad = options.dataDir + "/bad_scenes/";
        files.push_back({bad + "nan_position.gltf", "non-finite"});
        files.push_back({bad + "inf_translation.gltf", ""});
        files.push_back({bad + "huge_matrix.gltf", "out of range"});
    }
    Checks checks;
    std::string sample;
    for (const BadFile& f : files) {
        const std::string name = fs::path(f.path).filename().string();
        try {
            (void)trace::LoadScene(f.path);
            checks.Expect(false, name + " loaded without an error");
        } catch (const pem::base::InputError& e) {
            checks.Expect(stability::IsOneLineError(e.what(), f.path, f.cause),
                          Format("%s: message \"%s\" is not one line naming the file and \"%s\"",
                                 name.c_str(), e.what(), f.cause.c_str()));
            if (sample.empty() || name == "nan_normal.gltf") sample = e.what() + std::string(" | ");
        } catch (const std::exception& e) {
            checks.Expect(false, name + ": not a pem::base::InputError: " + e.what());
        }
    }
    c->detail = Format(
        "%zu files (generated: NaN and -Inf positions, a NaN normal, a 1e300 node scale, a 1e400 "
        "JSON literal; %s); e.g. %s residual and condition not applicable",
        files.size(),
        options.dataDir.empty() ? "no dataDir: bad_scenes not read"
                                : "tests/data/bad_scenes: nan_position, inf_translation, "
                                  "huge_matrix",
        sample.c_str());
    stability::Conclude(checks, Format("%zu one-line pem::base::InputError messages", files.size()),
                        c);
}

}  // namespace

std::vector<StabilityCase> RunSceneStabilityCases(const StabilityOptions& options) {
    return {
        stability::RunCase(
            "scenes: sliver and degenerate triangles traced", "extreme",
            "loads; zero-area triangles dropped and counted; finite unit normals; Embree and "
            "brute-force hits finite and equal in t; condition (aspect) reported",
            [&](StabilityCase* c) { SliverScene(options, c); }),
        stability::RunCase(
            "scenes: NaN / Inf in scene files", "extreme",
            "clear error: pem::base::InputError with one line \"<file>: <cause>\" naming "
            "the non-finite or out-of-range value",
            [&](StabilityCase* c) { NonFiniteScenes(options, c); }),
    };
}

}  // namespace pem::stability
