// SPDX-License-Identifier: MIT
// suite.cpp — golden suites (suite.h).
#include "viewer_tty/golden/suite.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "base/input_error.h"
#include "pipeline/json_values.h"

namespace pem::golden {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string Absolute(const std::string& dir, const std::string& path) {
    return (fs::path(dir) / path).lexically_normal().string();
}

GoldenTest::Kind KindOf(const json& t) {
    const int n = int(t.contains("case")) + int(t.contains("scene")) + int(t.contains("pem"));
    if (n != 1) throw std::runtime_error("needs exactly one of case, scene or pem");
    return t.contains("case")
               ? GoldenTest::Kind::Case
               : (t.contains("scene") ? GoldenTest::Kind::Scene : GoldenTest::Kind::Pem);
}

// The tolerances and render settings every kind may carry.
void ReadSettings(const json& t, GoldenTest* g) {
    if (t.contains("fuzzy")) {
        const json& f = t.at("fuzzy");
        if (!f.is_array() || f.size() != 2)
            throw std::runtime_error("fuzzy must be [maxDifference 0..255, pixels >= 0]");
        g->fuzzy = {pipeline::IntFromJson<int>(f[0], "fuzzy"),
                    pipeline::IntFromJson<size_t>(f[1], "fuzzy")};
        if (g->fuzzy.maxDifference < 0 || g->fuzzy.maxDifference > 255)
            throw std::runtime_error("fuzzy must be [maxDifference 0..255, pixels >= 0]");
    }
    if (t.contains("bounds_lsb")) {
        g->boundsLsb = pipeline::IntAt<int>(t, "bounds_lsb");
        if (*g->boundsLsb < 0 || *g->boundsLsb > 255) throw std::runtime_error("bad bounds_lsb");
    }
    if (t.contains("size")) {
        g->width = pipeline::IntFromJson<int>(t.at("size").at(0), "size"),
        g->height = pipeline::IntFromJson<int>(t.at("size").at(1), "size");
        if (g->width < 1 || g->height < 1 || g->width > 4096 || g->height > 4096)
            throw std::runtime_error("size out of range");
    }
    g->spp = pipeline::IntAtOr<int>(t, "spp", 1);
    if (g->spp < 1 || g->spp > 16) throw std::runtime_error("spp out of range");
}

GoldenTest ReadTest(const json& t, const std::string& dir) {
    GoldenTest g;
    g.name = t.at("name").get<std::string>();
    if (g.name.empty() || g.name.find_first_of("/\\") != std::string::npos || g.name[0] == '.')
        throw std::runtime_error("a test name must be a plain file name");
    g.kind = KindOf(t);
    ReadSettings(t, &g);
    const char* key = g.kind == GoldenTest::Kind::Case    ? "case"
                      : g.kind == GoldenTest::Kind::Scene ? "scene"
                                                          : "pem";
    g.input = Absolute(dir, t.at(key).get<std::string>());
    if (g.kind == GoldenTest::Kind::Scene) {
        g.method = t.value("method", "traced");
        if (g.method != "traced" && g.method != "static")
            throw std::runtime_error("a scene's method is traced or static");
        const json& cam = t.contains("camera") ? t.at("camera") : json("scene");
        g.camera = cam.is_string() ? cam.get<std::string>() : cam.dump();
        if (g.width == 0) throw std::runtime_error("a scene test needs a size");
    } else if (g.kind == GoldenTest::Kind::Pem) {
        g.method = t.value("method", "hybrid");
        g.view = t.value("view", "sample:0");
    }
    return g;
}

std::vector<GoldenTest> ReadSuiteJson(const std::string& dir) {
    const std::string path = dir + "/suite.json";
    std::vector<GoldenTest> tests;
    if (!fs::exists(path)) return tests;
    std::ifstream f(path);
    json j;
    try {
        j = json::parse(f);
        if (j.value("format", "") != "pemref_golden_suite" || j.value("version", json()) != 1)
            throw std::runtime_error("not a pemref_golden_suite file (version 1)");
    } catch (const std::exception& e) {
        throw base::InputError(path, e.what());
    }
    size_t k = 0;
    for (const json& t : j.value("tests", json::array())) {
        try {
            tests.push_back(ReadTest(t, dir));
        } catch (const std::exception& e) {
            throw base::InputError(path, "tests[" + std::to_string(k) + "]: " + e.what());
        }
        ++k;
    }
    return tests;
}

}  // namespace

const GoldenTest* Suite::Find(const std::string& name) const {
    for (const GoldenTest& t : tests)
        if (t.name == name) return &t;
    return nullptr;
}

Suite ReadSuite(const std::string& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw base::InputError(dir, "not a suite folder");
    Suite s{dir, ReadSuiteJson(dir)};
    // The case files suite.json does not name, by file name.
    std::set<std::string> listed, names;
    for (const GoldenTest& t : s.tests) listed.insert(t.input), names.insert(t.name);
    std::vector<fs::path> cases;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file() && e.path().extension() == ".json" &&
            e.path().filename() != "suite.json")
            cases.push_back(e.path());
    std::sort(cases.begin(), cases.end());
    for (const fs::path& p : cases) {
        const std::string input = p.lexically_normal().string();
        if (listed.count(input)) continue;
        GoldenTest g;
        g.name = p.stem().string();
        g.input = input;
        if (!names.insert(g.name).second)
            throw base::InputError(input, "a test named " + g.name + " exists already");
        s.tests.push_back(g);
    }
    for (size_t i = 0; i < s.tests.size(); ++i)
        for (size_t k = i + 1; k < s.tests.size(); ++k)
            if (s.tests[i].name == s.tests[k].name)
                throw base::InputError(dir + "/suite.json", "two tests named " + s.tests[i].name);
    if (s.tests.empty()) throw base::InputError(dir, "no tests (no case files, no suite.json)");
    return s;
}

}  // namespace pem::golden
