#!/usr/bin/env python3
"""infer_bench.py TMP ROUNDS — the figures of bench/infer_bench.sh from its runs' infer.json files
and the exported systems (see the script's header)."""
import glob
import json
import os
import statistics
import sys
import time

import numpy as np
import scipy.io
import scipy.sparse
import scipy.sparse.linalg


def stats(values):
    return f"{statistics.median(values):.3f} ({min(values):.3f}..{max(values):.3f})"


def bandwidth():
    # Bytes read + written per second by a copy of a 256 MB array (best of 5).
    a = np.ones(32 << 20)
    b = np.empty_like(a)
    best = 1e9
    for _ in range(5):
        t = time.perf_counter()
        np.copyto(b, a)
        best = min(best, time.perf_counter() - t)
    return 2 * a.nbytes / best


def main():
    tmp, rounds = sys.argv[1], int(sys.argv[2])
    runs = [json.load(open(os.path.join(tmp, f"pem_{r}", "infer.json"))) for r in range(1, rounds + 1)]
    walls = [float(open(os.path.join(tmp, f"pem_{r}", "wall.txt")).read()) for r in range(1, rounds + 1)]
    maps = runs[0]["maps"]
    print(f"{len(maps)} maps, res {runs[0]['res']}, {runs[0]['threads']} threads; per sample "
          f"(s, median (min..max) of {rounds}): wall {stats(walls)}, "
          f"inside {stats([r['samples'][0]['seconds'] for r in runs])}")
    print("map           rows     cols      nnz  build  solve  its stop            rmse_8bit")
    for i, m in enumerate(maps):
        b = statistics.median([r["maps"][i]["build_seconds"] for r in runs])
        s = statistics.median([r["maps"][i]["solve_seconds"] for r in runs])
        print(f"g{m['group']} {m['term']:3s} l{m['layer']}  {m['rows']:8d} {m['cols']:8d} {m['nnz']:8d} "
              f"{b:6.2f} {s:6.2f} {m['iterations']:4d} {m['stop']:15s} {m['rmse_8bit']:.5f}")
    # (a) build A vs one forward render of the same passes.
    build = [sum(m["build_seconds"] for m in r["maps"]) for r in runs]
    matrix = [sum(m["timing"]["matrix_seconds"] for m in r["maps"]) for r in runs]
    render = [sum(m["timing"]["render_seconds"] for m in r["maps"]) for r in runs]
    print(f"(a) build A {stats(build)} s (raster's matrix {stats(matrix)} s) vs forward render "
          f"{stats(render)} s: ratio {stats([b / f for b, f in zip(build, render)])}")
    # (a') the same without the process's first map, whose build faults in the heap that every
    # later map reuses (on a virtual machine that returns freed memory to its host, fresh pages
    # cost far more than the work: docs/inference.md §3.7).
    rest_b = [sum(m["build_seconds"] for m in r["maps"][1:]) for r in runs]
    rest_f = [sum(m["timing"]["render_seconds"] for m in r["maps"][1:]) for r in runs]
    print(f"(a') without the first map: build A {stats(rest_b)} s vs forward render "
          f"{stats(rest_f)} s: ratio {stats([b / f for b, f in zip(rest_b, rest_f)])}")
    # (b) per iteration vs streaming A and A^T once each (an iteration's two products: issue 17's
    # measure), on the largest map; the ratio to A alone follows.
    big = max(range(len(maps)), key=lambda i: maps[i]["nnz"])
    m = maps[big]
    per_it = [r["maps"][big]["solve_seconds"] / max(1, r["maps"][big]["iterations"]) for r in runs]
    bw = bandwidth()
    stream_a = (12 * m["nnz"] + 8 * m["rows"]) / bw
    stream = stream_a + (12 * m["nnz"] + 8 * m["cols"]) / bw
    print(f"(b) largest map (g{m['group']} {m['term']} l{m['layer']}, nnz {m['nnz']}): "
          f"{1e3 * statistics.median(per_it):.2f} ms/iteration (K and K^T products, restarts "
          f"and logs included); memory bandwidth {bw / 1e9:.1f} GB/s (copy), A and A^T stream "
          f"once in {1e3 * stream:.2f} ms: ratio {stats([p / stream for p in per_it])} "
          f"(A alone {1e3 * stream_a:.2f} ms: {stats([p / stream_a for p in per_it])})")
    # (c) time to pemref's objective: pemref vs scipy lsmr on the exported system.
    name = f"v000_g{m['group']}_{m['name']}"  # as pemref infer --export-system names it
    base = os.path.join(tmp, "sys", name)
    meta = json.load(open(base + ".json"))
    k = scipy.sparse.csr_matrix(scipy.io.mmread(base + "_K.mtx"))
    h = np.asarray(scipy.io.mmread(base + "_h.mtx")).ravel()
    target = 1.01 * meta["objective"]
    its = 8  # doubled until scipy reaches the objective
    while True:
        t = time.perf_counter()
        x, _, itn = scipy.sparse.linalg.lsmr(k, h, atol=0, btol=0, maxiter=its)[:3]
        secs = time.perf_counter() - t
        obj = float(np.sum((k @ x - h) ** 2))
        if obj <= target or its >= 16 * max(8, meta["iterations"]):
            break
        its *= 2
    ours = statistics.median([r["maps"][big]["solve_seconds"] for r in runs])
    reached = "reached" if obj <= target else "NOT reached"
    print(f"(c) to objective {target:.6g} (pemref's + 1 %): pemref {ours:.3f} s "
          f"({meta['iterations']} its, bounded, from the splat); scipy lsmr {secs:.3f} s "
          f"({itn} its, objective {obj:.6g}, {reached}): ratio pemref/scipy {ours / secs:.2f}")


if __name__ == "__main__":
    main()
