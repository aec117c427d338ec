#!/usr/bin/env python3
"""Writes the malformed glTF/EXR inputs of tests/trace/scene_test.cpp (and one valid triangle).

Each bad file breaks exactly one rule; expected.tsv lists, per file, a substring that the one-line
pem::InputError message must contain. Deterministic output, Python standard library only:
    python3 tests/data/bad_scenes/make_bad_scenes.py
"""
import base64, copy, json, os, struct

HERE = os.path.dirname(os.path.abspath(__file__))
GOOD_DIR = os.path.join(HERE, "..", "trace_scenes")
STUDIO = os.path.join(HERE, "..", "..", "..", "data", "env", "studio.exr")


def buffer_bytes(positions, indices):
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    data += struct.pack("<%dH" % len(indices), *indices)
    return data + b"\0" * (-len(data) % 4)


def triangle(positions=((0, 0, 0), (1, 0, 0), (0, 1, 0)), indices=(0, 1, 2)):
    """A valid one-triangle glTF (float3 positions + uint16 indices in one data-URI buffer)."""
    data = buffer_bytes(positions, indices)
    npos = len(positions)
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "tri", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * npos},
                        {"buffer": 0, "byteOffset": 12 * npos, "byteLength": 2 * len(indices)}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": npos, "type": "VEC3",
             "min": [min(p[i] for p in positions) for i in range(3)],
             "max": [max(p[i] for p in positions) for i in range(3)]},
            {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"}],
    }


def variant(fn):
    g = triangle()
    fn(g)
    return g


def with_env(uri):
    def fn(g):
        g["scenes"][0]["extras"] = {"pemref_environment": {"uri": uri, "mapping": "latlong", "intensity": 1.0}}
    return fn


def main():
    cases = []  # (file name, bytes, expected substring)

    def add_json(name, obj, expect):
        cases.append((name, json.dumps(obj, indent=1).encode(), expect))

    text = json.dumps(triangle(), indent=1).encode()
    cases.append(("truncated_json.gltf", text[: len(text) // 2], "parse error"))
    cases.append(("empty_file.gltf", b"", "parse error"))
    cases.append(("not_json.gltf", b"solid cube\nfacet normal 0 0 1\n", "parse error"))
    cases.append(("garbage.glb", b"glTF\x02\x00\x00\x00\xff\xff\xff\x7f" + b"\x00" * 20, "parse error"))

    g = triangle()
    g["buffers"][0]["uri"] = "data:application/octet-stream;base64,@@@not*base64!!"
    add_json("bad_base64.gltf", g, "parse error")
    add_json("missing_bin.gltf", variant(lambda g: g["buffers"][0].update(uri="does_not_exist.bin")), "parse error")
    add_json("huge_accessor_count.gltf", variant(lambda g: g["accessors"][0].update(count=4000000000)), "accessor")
    add_json("short_buffer_view.gltf", variant(lambda g: g["bufferViews"][0].update(byteLength=4096)), "")
    add_json("index_out_of_range.gltf", triangle(indices=(0, 1, 7)), "out of range")
    add_json("accessor_index_bad.gltf", variant(lambda g: g["meshes"][0]["primitives"][0].update(indices=9)), "")
    add_json("all_degenerate.gltf", triangle(positions=((0, 0, 0), (1, 1, 1), (2, 2, 2))), "degenerate")
    nan = struct.unpack("<f", b"\x00\x00\xc0\x7f")[0]
    add_json("nan_position.gltf", triangle(positions=((0, 0, 0), (nan, 0, 0), (0, 1, 0))), "non-finite")
    add_json("huge_matrix.gltf", variant(lambda g: g["nodes"][0].update(
        matrix=[1e300, 0, 0, 0, 0, 1e300, 0, 0, 0, 0, 1e300, 0, 0, 0, 0, 1])), "out of range")
    add_json("inf_translation.gltf", variant(lambda g: g["nodes"][0].update(translation=[1e400, 0, 0])), "")
    add_json("draco_required.gltf", variant(lambda g: g.update(
        extensionsUsed=["KHR_draco_mesh_compression"], extensionsRequired=["KHR_draco_mesh_compression"])),
        "KHR_draco_mesh_compression")
    add_json("meshopt_required.gltf", variant(lambda g: g.update(
        extensionsUsed=["EXT_meshopt_compression"], extensionsRequired=["EXT_meshopt_compression"])),
        "EXT_meshopt_compression")
    add_json("unknown_required_extension.gltf", variant(lambda g: g.update(
        extensionsUsed=["EXT_pemref_bogus"], extensionsRequired=["EXT_pemref_bogus"])), "EXT_pemref_bogus")
    add_json("no_position.gltf", variant(lambda g: g["meshes"][0]["primitives"][0].update(attributes={})), "POSITION")
    add_json("points_only.gltf", variant(lambda g: g["meshes"][0]["primitives"][0].update(mode=0)), "no triangles")
    add_json("bad_mode.gltf", variant(lambda g: g["meshes"][0]["primitives"][0].update(mode=9)), "mode")
    add_json("wrong_position_type.gltf", variant(lambda g: g["accessors"][0].update(type="SCALAR", componentType=5123)),
             "VEC3")
    add_json("node_cycle.gltf", variant(lambda g: g.update(nodes=[{"name": "a", "mesh": 0, "children": [1]},
                                                                  {"name": "b", "children": [0]}])), "twice")
    add_json("bad_ior.gltf", variant(lambda g: (g.update(materials=[{"extensions": {
        "KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 0.5}}}]),
        g["meshes"][0]["primitives"][0].update(material=0))), "ior")
    add_json("bad_light_type.gltf", variant(lambda g: (
        g.update(extensions={"KHR_lights_punctual": {"lights": [{"type": "area", "intensity": 1.0}]}}),
        g["nodes"].append({"name": "l", "extensions": {"KHR_lights_punctual": {"light": 0}}}),
        g["scenes"][0]["nodes"].append(1))), "light")
    add_json("camera_zero_fov.gltf", variant(lambda g: (
        g.update(cameras=[{"type": "perspective", "perspective": {"yfov": 0.0, "znear": 0.1}}]),
        g["nodes"].append({"name": "cam", "camera": 0}), g["scenes"][0]["nodes"].append(1))), "yfov")
    add_json("env_missing_file.gltf", variant(with_env("no_such_env.exr")), "pemref_environment")
    add_json("env_not_exr.gltf", variant(with_env("not_an_exr.exr")), "OpenEXR")
    add_json("env_truncated_exr.gltf", variant(with_env("truncated.exr")), "pemref_environment")
    add_json("env_bad_mapping.gltf", variant(lambda g: g["scenes"][0].update(
        extras={"pemref_environment": {"uri": "not_an_exr.exr", "mapping": "sphere"}})), "mapping")
    cases.append(("not_an_exr.exr", b"v/1\x01\x02\x00\x00\x00this is not an OpenEXR file", "OpenEXR"))
    with open(STUDIO, "rb") as f:
        studio = f.read()
    cases.append(("truncated.exr", studio[:3000], ""))

    for name, data, _ in cases:
        with open(os.path.join(HERE, name), "wb") as f:
            f.write(data)
    with open(os.path.join(HERE, "expected.tsv"), "w") as f:
        f.write("# file\tsubstring the InputError message must contain (besides the path)\n")
        for name, _, expect in cases:
            f.write("%s\t%s\n" % (name, expect))
    os.makedirs(GOOD_DIR, exist_ok=True)
    with open(os.path.join(GOOD_DIR, "triangle.gltf"), "w") as f:
        json.dump(triangle(), f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
