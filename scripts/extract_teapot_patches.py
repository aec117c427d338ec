#!/usr/bin/env python3
"""Extract the Utah teapot Bezier patch table from three.js into data/teapot/teapot_patches.json.

One-off helper; its output is committed, so make_scenes.py does not need npm. To rerun:

    cd /tmp && npm pack three@0.187.0 && \
      tar xzf three-0.187.0.tgz package/examples/jsm/geometries/TeapotGeometry.js
    python3 scripts/extract_teapot_patches.py \
      /tmp/package/examples/jsm/geometries/TeapotGeometry.js data/teapot/teapot_patches.json
"""
import json
import re
import sys


def js_array(src, name):
    m = re.search(r"const " + name + r"\s*=\s*\[(.*?)\];", src, re.S)
    body = re.sub(r"/\*.*?\*/", "", m.group(1))
    return [x.replace(" ", "").replace("\t", "").replace("\n", "") for x in body.split(",") if x.strip()]


def main():
    src = open(sys.argv[1], encoding="utf-8").read()
    patches = [int(x) for x in js_array(src, "teapotPatches")]
    verts = [float(x) for x in js_array(src, "teapotVertices")]
    assert len(patches) == 32 * 16 and len(verts) == 290 * 3
    out = {
        "source": "three.js r187 (npm three@0.187.0), examples/jsm/geometries/TeapotGeometry.js, "
                  "arrays teapotPatches and teapotVertices",
        "origin": "Martin Newell's Utah teapot (1975), Bezier patch data as distributed with Eric Haines' "
                  "SPD and used by three.js; includes the 4 bottom patches; Blinn proportions (height 3.15)",
        "license": "MIT (three.js, Copyright 2010-2026 three.js authors); see data/LICENSES",
        "frame": "Z up, spout toward +X, bottom at z=0, lid knob top at z=3.15",
        "layout": "patches[i] = 16 control point indices in row-major order (4 rows x 4 columns); "
                  "for body-like patches the columns go around the axis and the rows go along the profile",
        "groups": {"rim": [0, 4], "body": [4, 12], "handle": [12, 16], "spout": [16, 20],
                   "lid": [20, 28], "bottom": [28, 32]},
        "patches": [patches[i:i + 16] for i in range(0, len(patches), 16)],
        "vertices": [verts[i:i + 3] for i in range(0, len(verts), 3)],
    }
    # One patch / vertex per line: diff-friendly and deterministic.
    lines = ["{"]
    keys = list(out.keys())
    for k in keys:
        v = out[k]
        comma = "," if k != keys[-1] else ""
        if k in ("patches", "vertices"):
            lines.append('  "%s": [' % k)
            for j, row in enumerate(v):
                lines.append("    " + json.dumps(row) + ("," if j + 1 < len(v) else ""))
            lines.append("  ]" + comma)
        else:
            lines.append("  %s: %s%s" % (json.dumps(k), json.dumps(v), comma))
    lines.append("}")
    with open(sys.argv[2], "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
