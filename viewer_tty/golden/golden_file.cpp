// SPDX-License-Identifier: MIT
// golden_file.cpp — golden.json (golden_file.h).
#include "viewer_tty/golden/golden_file.h"

#include <nlohmann/json.hpp>
#include <utility>

#include "base/atomic_file.h"
#include "pipeline/json_values.h"

namespace pem::golden {

using nlohmann::json;

const GoldenEntry* GoldenRecord::Find(const std::string& name) const {
    for (const GoldenEntry& e : tests)
        if (e.name == name) return &e;
    return nullptr;
}

GoldenEntry* GoldenRecord::Find(const std::string& name) {
    return const_cast<GoldenEntry*>(std::as_const(*this).Find(name));
}

void WriteGoldenFile(const GoldenRecord& r) {
    json tests = json::array();
    for (const GoldenEntry& e : r.tests)
        tests.push_back({{"name", e.name},
                         {"png", e.png},
                         {"sha256", e.sha256},
                         {"input_sha256", e.inputSha256},
                         {"size", {e.width, e.height}}});
    const json j = {{"format", "pemref_golden"}, {"version", 1},       {"profile", r.profile},
                    {"model", r.model},          {"pemref", r.pemref}, {"tests", tests}};
    base::WriteTextAtomic(r.dir + "/golden.json", j.dump(2) + "\n");
}

GoldenRecord ReadGoldenFile(const std::string& dir) {
    GoldenRecord r = pipeline::ReadJsonFile(
        dir + "/golden.json", "run pemref golden generate first", [](const json& j) {
            if (j.value("format", "") != "pemref_golden" || j.value("version", json()) != 1)
                throw std::runtime_error("not a pemref_golden file (version 1)");
            GoldenRecord rec;
            rec.profile = pipeline::ProfileAt(j, "profile");
            rec.model = j.at("model").get<std::string>();
            rec.pemref = j.at("pemref").get<std::string>();
            for (const json& t : j.at("tests")) {
                GoldenEntry e{t.at("name").get<std::string>(),
                              t.at("png").get<std::string>(),
                              t.at("sha256").get<std::string>(),
                              t.at("input_sha256").get<std::string>(),
                              pipeline::IntFromJson<int>(t.at("size").at(0), "size"),
                              pipeline::IntFromJson<int>(t.at("size").at(1), "size")};
                if (e.png.find("..") != std::string::npos || e.png.find('/') != std::string::npos)
                    throw std::runtime_error("test " + e.name + ": png must be a file name");
                rec.tests.push_back(e);
            }
            return rec;
        });
    r.dir = dir;
    return r;
}

}  // namespace pem::golden
