#!/usr/bin/env python3
"""infer_cli_check.py PEM_DIR SYSTEM_DIR — checks of `pemref infer` output (infer_cli.sh).

infer.json: every field for every map, texels in [0, 1], nothing NaN; manifest.json present; the
EXR and PNG files exist. One exported system (K, h, x + json) is solved again with scipy
(lsq_linear with bounds [0, 1] and lsmr inside, or lsmr when no bound is active at pemref's
solution); its objective |K x - h|^2 must be within 1 % of pemref's (and pemref's must be what
its own x gives)."""
import glob
import json
import math
import os
import sys

import numpy as np
import scipy.io
import scipy.sparse
import scipy.sparse.linalg
from scipy.optimize import lsq_linear

FIELDS = ["rows", "cols", "nnz", "build_seconds", "solve_seconds", "iterations", "rmse",
          "rmse_8bit", "texel_min", "texel_max"]


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def check_infer_json(pem):
    path = os.path.join(pem, "infer.json")
    if not os.path.exists(path):
        fail("no infer.json")
    j = json.load(open(path))
    if not j.get("maps"):
        fail("infer.json has no maps")
    for m in j["maps"]:
        for f in FIELDS:
            if f not in m:
                fail(f"map {m.get('file')}: field {f} missing")
            v = m[f]
            if not isinstance(v, (int, float)) or isinstance(v, bool) or math.isnan(v):
                fail(f"map {m.get('file')}: {f} = {v!r}")
        if not (0.0 <= m["texel_min"] <= m["texel_max"] <= 1.0):
            fail(f"map {m['file']}: texels [{m['texel_min']}, {m['texel_max']}] outside [0, 1]")
        if m["rows"] <= 0 or m["cols"] <= 0 or m["nnz"] <= 0:
            fail(f"map {m['file']}: empty system")
        exr = os.path.join(pem, m["file"])
        if not os.path.exists(exr) or os.path.getsize(exr) == 0:
            fail(f"{exr} missing")
        if not os.path.exists(exr[:-4] + ".png"):
            fail(f"{exr[:-4]}.png missing")
    if not os.path.exists(os.path.join(pem, "manifest.json")):
        fail("no manifest.json")
    json.load(open(os.path.join(pem, "manifest.json")))
    print(f"infer.json: {len(j['maps'])} maps, every field present, texels in [0, 1]")
    return j


def load_vector(path):
    return np.asarray(scipy.io.mmread(path)).ravel()


def check_system(sysdir):
    metas = sorted(glob.glob(os.path.join(sysdir, "*.json")))
    if not metas:
        fail("no exported system")
    # The largest exported system.
    meta_path = max(metas, key=lambda p: json.load(open(p))["cols"])
    meta = json.load(open(meta_path))
    base = meta_path[:-5]
    k = scipy.sparse.csr_matrix(scipy.io.mmread(base + "_K.mtx"))
    h = load_vector(base + "_h.mtx")
    x = load_vector(base + "_x.mtx")
    if k.shape != (meta["rows"], meta["cols"]) or h.size != k.shape[0] or x.size != k.shape[1]:
        fail(f"{base}: sizes differ from the json")
    if not (np.all(np.isfinite(k.data)) and np.all(np.isfinite(h)) and np.all(np.isfinite(x))):
        fail(f"{base}: NaN or inf in the exported system")
    own = float(np.sum((k @ x - h) ** 2))
    ref = float(meta["objective"])
    if abs(own - ref) > 1e-9 * max(1.0, ref):
        fail(f"{base}: objective of the exported x {own} differs from pemref's {ref}")
    lo, hi = {"unit": (0.0, 1.0), "hdr": (0.0, np.inf), "none": (-np.inf, np.inf)}[meta["bounds"]]
    on_bound = int(np.sum((x <= lo) | (x >= hi)))
    if on_bound == 0:
        sol = scipy.sparse.linalg.lsmr(k, h, atol=1e-10, btol=1e-10, maxiter=20000)[0]
        how = "lsmr (no bound active)"
    else:
        sol = lsq_linear(k, h, bounds=(lo, hi), method="trf", lsmr_tol="auto", tol=1e-10,
                         max_iter=200).x
        how = f"lsq_linear trf/lsmr ({on_bound} unknowns on a bound)"
    obj = float(np.sum((k @ sol - h) ** 2))
    rel = (ref - obj) / obj if obj > 0 else 0.0
    print(f"{os.path.basename(base)}: {k.shape[0]}x{k.shape[1]}, nnz {k.nnz}; pemref objective "
          f"{ref:.6g}, scipy {how} {obj:.6g}, pemref/scipy - 1 = {rel:+.4%}")
    if ref > obj * 1.01:
        fail("pemref's objective is more than 1 % above scipy's")
    if obj > ref * 1.01:
        print("note: scipy's objective is above pemref's (pemref is the better solution)")


def main():
    if len(sys.argv) != 3:
        fail("usage: infer_cli_check.py PEM_DIR SYSTEM_DIR")
    check_infer_json(sys.argv[1])
    check_system(sys.argv[2])
    print("PASS")


if __name__ == "__main__":
    main()
