// SPDX-License-Identifier: MIT
// pem_pack.cpp — packed PEMs (pem_pack.h).
//
// Index: bytes of the file · packing · reading · unpacking.
#include "pipeline/pem_pack.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "base/atomic_file.h"
#include "base/input_error.h"
#include "base/sha256.h"
#include "infer/env_map.h"
#include "infer/pem_file.h"
#include "pipeline/json_values.h"
#include "pipeline/layout.h"
#include "pipeline/map_coding.h"
#include "pipeline/map_files.h"

namespace pem::pipeline {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Bytes = std::vector<uint8_t>;

constexpr char kMagic[8] = {'P', 'E', 'M', 'P', 'A', 'C', 'K', '1'};
constexpr const char* kFormat = "pemref_pack";
constexpr int kVersion = 1;

// Bytes of the file -----------------------------------------------------------------------------

Bytes ReadWholeFile(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw base::InputError(path, "cannot open");
    return Bytes(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

uint64_t FileBytes(const std::string& path) {
    std::error_code ec;
    const uintmax_t n = fs::file_size(path, ec);
    return ec ? 0 : static_cast<uint64_t>(n);
}

// A blob of the payload: its place and sizes as the header records them.
json BlobJson(uint64_t offset, size_t bytes, size_t rawBytes) {
    return {{"offset", offset}, {"bytes", bytes}, {"raw_bytes", rawBytes}};
}

// The bytes of the payload an entry of the header names, as stored.
std::span<const uint8_t> PayloadBytes(const json& entry, const Bytes& payload) {
    const uint64_t offset = IntAt<uint64_t>(entry, "offset");
    const uint64_t bytes = IntAt<uint64_t>(entry, "bytes");
    if (offset > payload.size() || bytes > payload.size() - offset)
        throw std::runtime_error("a blob lies outside the payload");
    return std::span(payload).subspan(offset, bytes);
}

// The same, decompressed by the pack's byte codec.
Bytes ReadBlob(const json& entry, const Bytes& payload, base::ByteCodec codec) {
    const uint64_t raw = IntAt<uint64_t>(entry, "raw_bytes");
    if (raw > (uint64_t{1} << 32)) throw std::runtime_error("a blob is too large");
    return base::Decompress(codec, PayloadBytes(entry, payload), raw);
}

// Packing ---------------------------------------------------------------------------------------

// The map names of a group directory: its .exr files, sorted.
std::vector<std::string> MapNamesIn(const std::string& groupDir) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(groupDir, ec))
        if (e.is_regular_file() && e.path().extension() == ".exr")
            names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Every file of the directory that is neither the manifest nor a map's EXR or PNG, by relative
// path (regular files only; temporaries and hidden files skipped).
std::vector<std::string> OtherFiles(const std::string& pemDir) {
    std::vector<std::string> out;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(pemDir)) {
        if (!e.is_regular_file() || e.is_symlink()) continue;
        const std::string rel = e.path().lexically_relative(pemDir).generic_string();
        const std::string name = e.path().filename().string();
        const std::string ext = e.path().extension().string();
        if (rel == kManifestJson || name.front() == '.' || name.find(".tmp") != std::string::npos)
            continue;
        if ((ext == ".exr" || ext == ".png") && rel.rfind("view_", 0) == 0 &&
            rel.find("/group_") != std::string::npos)
            continue;
        out.push_back(rel);
    }
    std::sort(out.begin(), out.end());
    return out;
}

int LargestError(const std::vector<raster::Texture>& a, const std::vector<raster::Texture>& b) {
    int worst = 0;
    for (size_t t = 0; t < a.size(); ++t)
        for (size_t l = 0; l < a[t].levels.size(); ++l)
            for (size_t i = 0; i < a[t].levels[l].size(); ++i)
                worst = std::max(worst,
                                 std::abs(static_cast<int>(a[t].levels[l][i]) - b[t].levels[l][i]));
    return worst;
}

// The header and payload of a pack, built entry by entry.
struct PackBuilder {
    base::ByteCodec codec;
    json header;
    Bytes payload;

    json Add(const Bytes& raw) {
        const Bytes packed = base::Compress(codec, raw);
        const json entry = BlobJson(payload.size(), packed.size(), raw.size());
        payload.insert(payload.end(), packed.begin(), packed.end());
        return entry;
    }

    Bytes File() const {
        const std::string text = header.dump();
        Bytes out(kMagic, kMagic + 8);
        const uint64_t n = text.size();
        for (int b = 0; b < 8; ++b) out.push_back(static_cast<uint8_t>(n >> (8 * b)));
        out.insert(out.end(), text.begin(), text.end());
        out.insert(out.end(), payload.begin(), payload.end());
        return out;
    }
};

// Reading ---------------------------------------------------------------------------------------

struct RawPack {
    json header;
    Bytes payload;
};

RawPack SplitPack(const std::string& path) {
    const Bytes file = ReadWholeFile(path);
    if (file.size() < 16 || std::memcmp(file.data(), kMagic, 8) != 0)
        throw base::InputError(path, "not a packed PEM (pemref pack writes them)");
    uint64_t n = 0;
    for (int b = 0; b < 8; ++b)
        n |= static_cast<uint64_t>(file[8 + static_cast<size_t>(b)]) << (8 * b);
    if (n > file.size() - 16) throw base::InputError(path, "truncated header");
    RawPack raw;
    try {
        raw.header =
            json::parse(file.begin() + 16, file.begin() + 16 + static_cast<std::ptrdiff_t>(n));
    } catch (const json::exception& e) {
        throw base::InputError(path, std::string("malformed header: ") + e.what());
    }
    raw.payload.assign(file.begin() + 16 + static_cast<std::ptrdiff_t>(n), file.end());
    return raw;
}

void CheckHeader(const RawPack& raw) {
    const json& h = raw.header;
    if (h.value("format", "") != kFormat) throw std::runtime_error("not a pemref_pack header");
    if (h.at("version") != kVersion)
        throw std::runtime_error("version " + h.at("version").dump() + ", expected " +
                                 std::to_string(kVersion));
    if (IntAt<uint64_t>(h, "payload_bytes") != raw.payload.size())
        throw std::runtime_error("truncated: the payload is " + std::to_string(raw.payload.size()) +
                                 " bytes, the header says " + h.at("payload_bytes").dump());
    if (base::Sha256Hex(raw.payload.data(), raw.payload.size()) !=
        h.at("payload_sha256").get<std::string>())
        throw std::runtime_error("checksum mismatch: the payload is damaged");
}

// A map of the header that the manifest has: an inferred sample, an existing group, a name of
// letters, digits and '_' (it becomes a file name).
MapKey CheckedMapKey(const json& e, const PemManifest& m) {
    const MapKey key{IntAt<int>(e, "view"), IntAt<int>(e, "group"),
                     e.at("name").get<std::string>()};
    const auto& [view, group, name] = key;
    if (std::find(m.inferred.begin(), m.inferred.end(), view) == m.inferred.end())
        throw std::runtime_error("a map of sample " + std::to_string(view) +
                                 ", which the manifest does not list as inferred");
    if (group < 0 || group >= static_cast<int>(m.groups.size()))
        throw std::runtime_error("a map of lens group " + std::to_string(group) +
                                 ", which the manifest does not have");
    if (name.empty() || name.size() > 64 || !std::all_of(name.begin(), name.end(), [](char c) {
            return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
        }))
        throw std::runtime_error("a map named '" + name + "' (letters, digits and _ only)");
    return key;
}

// A file path of the pack, safe to create under a directory: relative, no "..".
std::string CheckedRelativePath(const std::string& rel) {
    const fs::path p = fs::path(rel).lexically_normal();
    if (rel.empty() || p.is_absolute() || p.empty() || *p.begin() == ".." || p.has_root_name())
        throw std::runtime_error("a file path leads outside the directory: " + rel);
    return p.generic_string();
}

// The shape of a map of the manifest's layout at `size` (LayoutOf's; a cube's face size).
MapShape ShapeFor(const PemManifest& m, int size) {
    if (m.parameterization == runtime::Parameterization::Cube)
        return {raster::TextureKind::Cube, 6, size, size};
    const runtime::MapLayout layout = runtime::LayoutOf(m.parameterization, size);
    return {layout.kind, layout.textures, layout.width, layout.height};
}

}  // namespace

bool IsPemPack(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return false;
    std::ifstream f(path, std::ios::binary);
    char magic[8] = {};
    return f.read(magic, 8) && std::memcmp(magic, kMagic, 8) == 0;
}

PackStats PackPem(const std::string& pemDir, const std::string& packFile, const PackOptions& opt) {
    if (!(opt.map.ratio == 0.0 || (opt.map.ratio >= 1.0 && opt.map.ratio <= 1000.0)))
        throw base::InputError("--ratio " + std::to_string(opt.map.ratio),
                               "must be 0 or lie in [1, 1000]");
    if (opt.map.maxError < 0 || opt.map.maxError > kMaxMapError)
        throw base::InputError("--max-error " + std::to_string(opt.map.maxError),
                               "must lie in [0, " + std::to_string(kMaxMapError) + "]");
    const PemManifest m = ReadPemManifest(pemDir);
    if (m.hardware.format != raster::TexelFormat::Rgba8)
        throw base::InputError(pemDir + "/" + kManifestJson,
                               "a pack holds 8-bit maps; these maps are rgba32f (map_format)");
    const std::string packDir = fs::absolute(packFile).parent_path().string();
    PackBuilder b{opt.codec, json::object(), {}};
    PackStats stats;
    stats.samples = static_cast<int>(m.inferred.size());
    // Step 1: the maps, sample by sample, each predicted from its neighbour's decoded copy.
    std::map<std::pair<int, std::string>, std::pair<int, std::vector<raster::Texture>>>
        last;  // by (group, name)
    json maps = json::array();
    const raster::SamplerState sampler = m.hardware.Sampler();
    for (size_t done = 0; done < m.inferred.size(); ++done) {
        const int v = m.inferred[done];
        if (done > 0 && opt.progress) opt.progress(double(done) / double(m.inferred.size()));
        for (int g = 0; g < static_cast<int>(m.groups.size()); ++g)
            for (const std::string& name : MapNamesIn(GroupDir(pemDir, v, g))) {
                const std::string path = MapPath(pemDir, v, g, name);
                CheckInside(pemDir, path);
                const infer::EnvMapF map = infer::ReadEnvMapExr(path);
                const int size =
                    CheckMapShape(m, map.kind, map.size, map.LevelHeight(0), map.charts, path);
                const std::vector<raster::Texture> tex = infer::ToTextures8(map, sampler);
                const MapShape shape = ShapeOf(tex);
                const int levels = tex[0].NumLevels();
                auto prev = last.find({g, name});
                const std::span<const raster::Texture> previous =
                    prev == last.end() ? std::span<const raster::Texture>() : prev->second.second;
                const MapCode code = EncodeMap(tex, previous, opt.map);
                std::vector<raster::Texture> decoded =
                    DecodeMap(code, shape, levels, previous, opt.map.maxError);
                Bytes raw = code.predictors;
                raw.insert(raw.end(), code.residuals.begin(), code.residuals.end());
                json entry = b.Add(raw);
                entry["transformed"] = json::array();
                for (const Bytes& t : code.transformed) {
                    entry["transformed"].push_back(
                        t.empty() ? json(nullptr) : BlobJson(b.payload.size(), t.size(), t.size()));
                    b.payload.insert(b.payload.end(), t.begin(), t.end());
                    stats.mapBytes += t.size();
                }
                entry.update({{"view", v},
                              {"group", g},
                              {"name", name},
                              {"size", size},
                              {"levels", levels},
                              {"previous_view", previous.empty() ? -1 : prev->second.first}});
                maps.push_back(entry);
                stats.maps++;
                stats.mapBytes += IntAt<uint64_t>(entry, "bytes");
                stats.rawBytes += ResidualBytes(shape, levels);
                stats.exrBytes += FileBytes(path);
                stats.pngBytes += FileBytes(PreviewPath(path));
                stats.maxError = std::max(stats.maxError, LargestError(tex, decoded));
                last[{g, name}] = {v, std::move(decoded)};
            }
    }
    // Step 2: every other file verbatim.
    json files = json::array();
    for (const std::string& rel : OtherFiles(pemDir)) {
        json entry = b.Add(ReadWholeFile(pemDir + "/" + rel));
        entry["path"] = rel;
        files.push_back(entry);
    }
    // Step 3: the header and the file.
    b.header = {{"format", kFormat},
                {"version", kVersion},
                {"codec", base::ByteCodecName(opt.codec)},
                {"max_error", opt.map.maxError},
                {"ratio", opt.map.ratio},
                {"wavelet", opt.map.wavelet == base::J2kWavelet::Reversible53 ? "5/3" : "9/7"},
                {"manifest", PemManifestText(RelocatedPemManifest(m, packDir))},
                {"payload_bytes", b.payload.size()},
                {"payload_sha256", base::Sha256Hex(b.payload.data(), b.payload.size())},
                {"maps", maps},
                {"files", files}};
    const Bytes file = b.File();
    base::WriteAtomically(packFile, [&](const std::string& tmp) {
        std::ofstream f(tmp, std::ios::binary);
        f.write(reinterpret_cast<const char*>(file.data()),
                static_cast<std::streamsize>(file.size()));
        if (!f.flush()) throw std::runtime_error("cannot write");
    });
    stats.packBytes = file.size();
    return stats;
}

PemPack ReadPemPack(const std::string& packFile) {
    const RawPack raw = SplitPack(packFile);
    PemPack p;
    try {
        CheckHeader(raw);
        const json& h = raw.header;
        const base::ByteCodec codec = base::ByteCodecNamed(h.at("codec").get<std::string>());
        p.codec = base::ByteCodecName(codec);
        p.maxError = IntAt<int>(h, "max_error");
        if (p.maxError < 0 || p.maxError > kMaxMapError) throw std::runtime_error("bad max_error");
        const std::string dir = fs::absolute(packFile).parent_path().string();
        p.manifest = PemManifestFromText(h.at("manifest").get<std::string>(), dir, packFile);
        const raster::SamplerState sampler = MapSampler(p.manifest);
        for (const json& e : h.at("maps")) {
            const MapKey key = CheckedMapKey(e, p.manifest);
            const int size = IntAt<int>(e, "size"), levels = IntAt<int>(e, "levels");
            CheckMapSize(p.manifest, size, packFile);
            const int prevView = IntAt<int>(e, "previous_view");
            std::span<const raster::Texture> previous;
            if (prevView >= 0) {
                auto it = p.maps.find({prevView, std::get<1>(key), std::get<2>(key)});
                if (it == p.maps.end()) throw std::runtime_error("a map's neighbour is missing");
                previous = it->second;
            }
            const Bytes blob = ReadBlob(e, raw.payload, codec);
            const size_t np = 4 * static_cast<size_t>(std::clamp(levels, 0, 16));
            if (blob.size() < np) throw std::runtime_error("a map's blob is too short");
            MapCode code{Bytes(blob.begin(), blob.begin() + static_cast<std::ptrdiff_t>(np)),
                         Bytes(blob.begin() + static_cast<std::ptrdiff_t>(np), blob.end()),
                         {}};
            for (const json& t : e.at("transformed")) {
                const std::span<const uint8_t> bytes =
                    t.is_null() ? std::span<const uint8_t>() : PayloadBytes(t, raw.payload);
                code.transformed.emplace_back(bytes.begin(), bytes.end());
            }
            std::vector<raster::Texture> tex =
                DecodeMap(code, ShapeFor(p.manifest, size), levels, previous, p.maxError);
            for (raster::Texture& t : tex) t.sampler = sampler;
            if (!p.maps.emplace(key, std::move(tex)).second)
                throw std::runtime_error("a map appears twice");
        }
        for (const json& e : h.at("files")) {
            const Bytes blob = ReadBlob(e, raw.payload, codec);
            p.files[CheckedRelativePath(e.at("path").get<std::string>())] =
                std::string(blob.begin(), blob.end());
        }
    } catch (const base::InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw base::InputError(packFile, e.what());
    }
    return p;
}

void UnpackPem(const std::string& packFile, const std::string& outDir, int threads) {
    const PemPack p = ReadPemPack(packFile);
    std::error_code ec;
    if (fs::exists(outDir, ec))
        throw base::InputError(outDir, "exists: unpack makes a new directory");
    // Step 1: everything into a temporary sibling directory.
    const std::string tmp = base::TemporaryPath(fs::path(outDir).lexically_normal().string());
    if (!fs::create_directories(tmp, ec) || ec)
        throw base::InputError(outDir, "cannot create the directory: " + ec.message());
    try {
        const PemManifest m = RelocatedPemManifest(p.manifest, outDir);
        base::WriteTextAtomic(tmp + "/" + kManifestJson, PemManifestText(m));
        for (const auto& [rel, text] : p.files) {
            fs::create_directories(fs::path(tmp + "/" + rel).parent_path());
            base::WriteTextAtomic(tmp + "/" + rel, text);
        }
        for (const auto& [key, tex] : p.maps) {
            const auto& [view, group, name] = key;
            fs::create_directories(GroupDir(tmp, view, group));
            WriteMapImages(infer::FromTextures8(tex), tex, MapStem(tmp, view, group, name),
                           threads);
        }
        // Step 2: the directory appears whole.
        fs::rename(tmp, outDir);
    } catch (const fs::filesystem_error& e) {
        fs::remove_all(tmp, ec);
        throw base::InputError(outDir, e.code().message());
    } catch (...) {
        fs::remove_all(tmp, ec);
        throw;
    }
}

}  // namespace pem::pipeline
