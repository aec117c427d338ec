#!/usr/bin/env python3
"""Generate pemref's bundled glTF 2.0 scenes (deterministic; Python 3 standard library only).

    python3 scripts/make_scenes.py            # writes data/scenes/*.gltf + *.bin
    python3 scripts/make_scenes.py --check    # regenerate in memory, compare with the files on disk

Scenes (see data/README.md):
  hybrid_glass_teapot  scene of Hakura & Snyder 2001, Sec. 6: glass teapot, mirror cup, ring of
                       columns, distant walls, environment at infinity above the open room.
  pem_mirror_teapot    scene of Hakura, Snyder & Lengyel 2001, Sec. 6: mirror teapot in a closed room.

Determinism: only IEEE double arithmetic (+ - * / sqrt, all correctly rounded); the few sin/cos values are
rounded to 12 decimals so that a last-bit difference between libm versions cannot reach the float32 output;
JSON floats are printed as the shortest decimal that round-trips to the stored float32; no timestamps, no
set/dict-order dependence.

World units are metres, +Y up (glTF). The teapot is 1 unit tall.
"""
import json
import math
import os
import struct
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PATCH_FILE = os.path.join(ROOT, "data", "teapot", "teapot_patches.json")
OUT_DIR = os.path.join(ROOT, "data", "scenes")

TEAPOT_HEIGHT = 3.15  # Blinn-proportioned teapot data, z in [0, 3.15]
LIFT = 0.001          # lens objects float 1 mm above the floor (no coplanar contact with it)

# ----------------------------------------------------------------------------------------------------------
# Small vector helpers (tuples of floats)


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    return (a[0] / n, a[1] / n, a[2] / n) if n > 0.0 else (0.0, 0.0, 0.0)


def cos_sin(deg):
    """cos/sin of an angle in degrees, rounded so libm last-bit differences cannot leak into the output."""
    r = math.radians(deg)
    c, s = round(math.cos(r), 12), round(math.sin(r), 12)
    return (c + 0.0, s + 0.0)  # + 0.0 turns -0.0 into 0.0


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def f32_json(x):
    """Shortest decimal string that round-trips to the same float32 (deterministic, diff-friendly)."""
    v = f32(x)
    if v == 0.0:
        return 0.0
    for p in range(1, 10):
        s = "%.*g" % (p, v)
        if f32(float(s)) == v:
            return float(s)
    return v


# ----------------------------------------------------------------------------------------------------------
# Triangle mesh with per-vertex normals


class Mesh:
    def __init__(self):
        self.pos = []   # list of (x, y, z)
        self.nrm = []   # list of (x, y, z), unit length
        self.tri = []   # list of (i, j, k), counter-clockwise seen from outside

    def vertex(self, p, n):
        self.pos.append(p)
        self.nrm.append(normalize(n))
        return len(self.pos) - 1

    def append(self, other):
        base = len(self.pos)
        self.pos.extend(other.pos)
        self.nrm.extend(other.nrm)
        self.tri.extend((a + base, b + base, c + base) for a, b, c in other.tri)

    def transformed(self, fp, fn):
        m = Mesh()
        m.pos = [fp(p) for p in self.pos]
        m.nrm = [normalize(fn(n)) for n in self.nrm]
        m.tri = list(self.tri)
        return m

    def quad(self, p0, p1, p2, p3, n=None):
        """Flat quad with its own vertices (hard edges); p0..p3 counter-clockwise seen from the front."""
        if n is None:
            n = normalize(cross(sub(p1, p0), sub(p3, p0)))
        i = [self.vertex(p, n) for p in (p0, p1, p2, p3)]
        self.tri.append((i[0], i[1], i[2]))
        self.tri.append((i[0], i[2], i[3]))


def weld(points, tol=1e-9):
    """Map each point to the index of its first occurrence within tol (spatial hash; deterministic)."""
    cell = 1e-6
    grid = {}
    rep = []
    remap = []
    for p in points:
        key = (math.floor(p[0] / cell), math.floor(p[1] / cell), math.floor(p[2] / cell))
        found = -1
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in grid.get((key[0] + dx, key[1] + dy, key[2] + dz), ()):
                        q = rep[j]
                        if abs(q[0] - p[0]) <= tol and abs(q[1] - p[1]) <= tol and abs(q[2] - p[2]) <= tol:
                            found = j
                            break
                    if found >= 0:
                        break
                if found >= 0:
                    break
            if found >= 0:
                break
        if found < 0:
            found = len(rep)
            rep.append(p)
            grid.setdefault(key, []).append(found)
        remap.append(found)
    return rep, remap


def orient_outward(tri, pos):
    """Make winding consistent within each edge-connected component, then make each component's signed
    volume positive (outward normals, counter-clockwise seen from outside). Returns the new triangle list."""
    _, wid = weld(pos, 0.0)  # adjacency by position, so split (hard-edge) vertices still connect
    tri = [list(t) for t in tri]
    edge_tris = {}
    for ti, t in enumerate(tri):
        for k in range(3):
            a, b = wid[t[k]], wid[t[(k + 1) % 3]]
            edge_tris.setdefault((min(a, b), max(a, b)), []).append(ti)
    comp = [-1] * len(tri)
    ncomp = 0
    for seed in range(len(tri)):
        if comp[seed] >= 0:
            continue
        comp[seed] = ncomp
        stack = [seed]
        members = [seed]
        while stack:
            ti = stack.pop()
            t = [wid[i] for i in tri[ti]]
            for k in range(3):
                a, b = t[k], t[(k + 1) % 3]
                for tj in edge_tris[(min(a, b), max(a, b))]:
                    if tj == ti or comp[tj] >= 0:
                        continue
                    u = [wid[i] for i in tri[tj]]
                    same_dir = any(u[m] == a and u[(m + 1) % 3] == b for m in range(3))
                    if same_dir:
                        tri[tj].reverse()
                    comp[tj] = ncomp
                    stack.append(tj)
                    members.append(tj)
        vol = 0.0
        for ti in members:
            a, b, c = (pos[i] for i in tri[ti])
            vol += dot(a, cross(b, c))
        if vol < 0.0:
            for ti in members:
                tri[ti].reverse()
        ncomp += 1
    return [tuple(t) for t in tri]


def boundary_edge_count(pos, tri):
    """Edges not shared by exactly two triangles, after welding vertices with identical positions."""
    _, remap = weld(pos, 0.0)
    count = {}
    for t in tri:
        for k in range(3):
            a, b = remap[t[k]], remap[t[(k + 1) % 3]]
            e = (min(a, b), max(a, b))
            count[e] = count.get(e, 0) + 1
    return sum(1 for c in count.values() if c != 2)


# ----------------------------------------------------------------------------------------------------------
# Utah teapot from Newell's Bezier patches


def bernstein(t):
    s = 1.0 - t
    return (s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t)


def bernstein_d(t):
    s = 1.0 - t
    return (-3.0 * s * s, 3.0 * s * s - 6.0 * t * s, 6.0 * t * s - 3.0 * t * t, 3.0 * t * t)


class Patch:
    """Bicubic Bezier patch; cp[r][c], u runs along a row (index c), v along a column (index r)."""

    def __init__(self, cp):
        self.cp = cp

    def eval(self, u, v):
        bu, bv, du, dv = bernstein(u), bernstein(v), bernstein_d(u), bernstein_d(v)
        p = [0.0, 0.0, 0.0]
        pu = [0.0, 0.0, 0.0]
        pv = [0.0, 0.0, 0.0]
        for r in range(4):
            for c in range(4):
                q = self.cp[r][c]
                w, wu, wv = bv[r] * bu[c], bv[r] * du[c], dv[r] * bu[c]
                for k in range(3):
                    p[k] += w * q[k]
                    pu[k] += wu * q[k]
                    pv[k] += wv * q[k]
        return tuple(p), tuple(pu), tuple(pv)

    def normal(self, u, v):
        """Unnormalized du x dv; where a derivative vanishes (the poles of lid and bottom) the normal is
        taken a tiny step toward the patch centre, which converges to the true limit normal."""
        p, pu, pv = self.eval(u, v)
        n = cross(pu, pv)
        if length(n) < 1e-9 * (length(pu) + length(pv) + 1e-30) or length(n) < 1e-12:
            step = 1e-4
            u2 = u + (step if u < 0.5 else -step)
            v2 = v + (step if v < 0.5 else -step)
            _, pu, pv = self.eval(u2, v2)
            n = cross(pu, pv)
        return n


def load_patches():
    with open(PATCH_FILE, encoding="utf-8") as f:
        data = json.load(f)
    verts = [tuple(float(x) for x in v) for v in data["vertices"]]
    patches = []
    for idx in data["patches"]:
        patches.append([[verts[idx[r * 4 + c]] for c in range(4)] for r in range(4)])
    return patches, data["groups"]


def fit_lid(patches, groups):
    """Weld the lid to the rim: the lid's outer flange (radius 1.3 at z 2.4..2.55) is widened to the rim's
    inner radius 1.4, so the lid's bottom edge coincides with the rim's inner edge (both at z = 2.4).
    Only the two outer control rows of the lower lid patches move; the knob keeps its shape."""
    lo, hi = groups["lid"]
    out = [list(map(list, p)) for p in patches]
    for pi in range(lo + 4, hi):
        for r in (2, 3):
            out[pi][r] = [(q[0] * 1.4 / 1.3, q[1] * 1.4 / 1.3, q[2]) for q in patches[pi][r]]
    return out


def body_profile(patches, groups):
    """Profile r(z) of the body (body patches' first column, y = 0): list of Bezier curves (x=r, z)."""
    lo, hi = groups["body"]
    curves = []
    for pi in (lo, lo + 4):  # upper and lower body patch of the first quadrant
        curves.append([(patches[pi][r][0][0], patches[pi][r][0][2]) for r in range(4)])
    return curves


def body_radius(curves, z):
    """Body radius at height z (z is monotonic along each profile curve); None outside the body."""
    for cv in curves:
        z0, z1 = cv[0][1], cv[3][1]
        if min(z0, z1) <= z <= max(z0, z1):
            a, b = 0.0, 1.0
            for _ in range(60):
                m = 0.5 * (a + b)
                bz = bernstein(m)
                zm = sum(bz[i] * cv[i][1] for i in range(4))
                if (zm - z) * (z1 - z0) < 0.0:
                    a = m
                else:
                    b = m
            bz = bernstein(0.5 * (a + b))
            return sum(bz[i] * cv[i][0] for i in range(4))
    return None


def tess_patch_grid(mesh, patch, n):
    """Tessellate one patch into an (n+1)^2 grid (welded with its neighbours later)."""
    base = len(mesh.pos)
    for j in range(n + 1):
        v = j / n
        for i in range(n + 1):
            u = i / n
            p, _, _ = patch.eval(u, v)
            mesh.vertex(p, patch.normal(u, v))
    for j in range(n):
        for i in range(n):
            a = base + j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            mesh.tri.append((a, b, c))
            mesh.tri.append((a, c, d))


def tube(mesh, pats, n, trim_start, trim_end, curves, inset):
    """Handle or spout: 2 patches around (u) x 2 patches along (v) as one tube with parameters
    U in [0, 2) (periodic) and V in [0, 2]. The ends buried in the body are trimmed per U so that they stop
    'inset' inside the body surface (the tube no longer pokes through the inside of the body), and each
    open end is closed with a fan cap (hard edge: own vertices). Returns the mesh part."""
    around = 2 * n

    def patch_at(U, V):
        a = min(int(U), 1)
        b = min(int(V), 1)
        return pats[b][a], U - a, V - b

    def point(U, V):
        p, uu, vv = patch_at(U, V)
        return p.eval(uu, vv)[0]

    def outside(V, U):
        q = point(U, V)
        r = body_radius(curves, q[2])
        return r is None or math.sqrt(q[0] * q[0] + q[1] * q[1]) > r - inset

    def trim(U, v_end, v_mid):
        """V where the tube (along U) crosses the body surface offset inward by 'inset'. The Bezier tube is
        extended beyond its end (cubic extrapolation) where the original end is not buried deep enough."""
        a = v_end  # a: inside, b: outside
        step = 0.02 if v_end > v_mid else -0.02
        k = 0
        while outside(a, U):
            k += 1
            if k > 15:
                return v_end  # not buried at all: keep the original end
            a = v_end + step * k
        b = v_mid
        for _ in range(50):
            m = 0.5 * (a + b)
            if outside(m, U):
                b = m
            else:
                a = m
        return b

    along = 2 * n
    rows = []
    for i in range(around):
        U = i / n
        v0 = trim(U, 0.0, 1.0) if trim_start else 0.0
        v1 = trim(U, 2.0, 1.0) if trim_end else 2.0
        col = []
        for j in range(along + 1):
            V = v0 + (v1 - v0) * j / along
            p, uu, vv = patch_at(U, V)
            col.append(mesh.vertex(p.eval(uu, vv)[0], p.normal(uu, vv)))
        rows.append(col)
    for i in range(around):
        i2 = (i + 1) % around
        for j in range(along):
            a, b, c, d = rows[i][j], rows[i2][j], rows[i2][j + 1], rows[i][j + 1]
            mesh.tri.append((a, b, c))
            mesh.tri.append((a, c, d))
    # caps (orientation fixed later by orient_outward; normals from Newell's method, pointing away from tube)
    for j, inner in ((0, 1), (along, along - 1)):
        ring = [mesh.pos[rows[i][j]] for i in range(around)]
        centre = mul(ring[0], 0.0)
        for q in ring:
            centre = add(centre, q)
        centre = mul(centre, 1.0 / around)
        nrm = (0.0, 0.0, 0.0)
        for i in range(around):
            nrm = add(nrm, cross(ring[i], ring[(i + 1) % around]))
        inward = sub(mesh.pos[rows[0][inner]], ring[0])
        if dot(nrm, inward) > 0.0:
            nrm = mul(nrm, -1.0)
        c = mesh.vertex(centre, nrm)
        ids = [mesh.vertex(q, nrm) for q in ring]
        for i in range(around):
            mesh.tri.append((c, ids[i], ids[(i + 1) % around]))


def make_teapot(n):
    """Closed teapot in glTF frame (Y up, height 1, bottom at y=0, spout toward +X).
    Three closed shells: body+rim+lid+bottom (welded, watertight), handle, spout (each capped)."""
    patches, groups = load_patches()
    patches = fit_lid(patches, groups)
    curves = body_profile(patches, groups)
    P = [Patch(p) for p in patches]

    # Shell 1: rim, body, bottom and lid -> one closed surface. Samples are welded within two groups,
    # (rim, body, bottom) and (lid); the lid's edge ring coincides with the rim's inner edge in position,
    # but keeps its own vertices there, because the lid/rim joint is a sharp crease (hard edge).
    raw = Mesh()
    remap = []
    rep = []
    for names in (("rim", "body", "bottom"), ("lid",)):
        part = Mesh()
        for name in names:
            lo, hi = groups[name]
            for pi in range(lo, hi):
                tess_patch_grid(part, P[pi], n)
        prep, premap = weld(part.pos)
        remap += [len(rep) + i for i in premap]
        rep += prep
        raw.pos += part.pos
        raw.nrm += part.nrm
        raw.tri += [(a + len(raw.pos) - len(part.pos), b + len(raw.pos) - len(part.pos),
                     c + len(raw.pos) - len(part.pos)) for a, b, c in part.tri]
    # snap the lid's edge ring onto the rim's inner edge (equal within rounding) so positions are identical
    first, group_of = weld(rep)
    rep = [first[i] for i in group_of]
    tris = []
    for a, b, c in raw.tri:
        a, b, c = remap[a], remap[b], remap[c]
        if a != b and b != c and a != c:
            tris.append((a, b, c))
    tris = orient_outward(tris, rep)
    # smooth normals: average the analytic normals of all samples welded into a vertex, each sign-corrected
    # to agree with the (now outward) face normals around that vertex
    facesum = [(0.0, 0.0, 0.0)] * len(rep)
    for a, b, c in tris:
        fn = cross(sub(rep[b], rep[a]), sub(rep[c], rep[a]))
        for i in (a, b, c):
            facesum[i] = add(facesum[i], fn)
    acc = [(0.0, 0.0, 0.0)] * len(rep)
    for k, i in enumerate(remap):
        nk = raw.nrm[k]
        if dot(nk, facesum[i]) < 0.0:
            nk = mul(nk, -1.0)
        acc[i] = add(acc[i], nk)
    shell = Mesh()
    shell.pos = rep
    shell.nrm = [normalize(a) for a in acc]
    shell.tri = tris

    # Shells 2 and 3: handle and spout tubes, trimmed at the body and capped
    out = Mesh()
    out.append(shell)
    inset = 0.01  # teapot units (~3 mm at 1 m height)
    for name, trim_start, trim_end in (("handle", True, True), ("spout", True, False)):
        lo, _ = groups[name]
        pats = [[P[lo], P[lo + 1]], [P[lo + 2], P[lo + 3]]]
        t = Mesh()
        tube(t, pats, n, trim_start, trim_end, curves, inset)
        t.tri = orient_outward(t.tri, t.pos)
        # make side normals agree with the outward winding
        facesum = [(0.0, 0.0, 0.0)] * len(t.pos)
        for a, b, c in t.tri:
            fn = cross(sub(t.pos[b], t.pos[a]), sub(t.pos[c], t.pos[a]))
            for i in (a, b, c):
                facesum[i] = add(facesum[i], fn)
        t.nrm = [mul(nv, -1.0) if dot(nv, fs) < 0.0 else nv for nv, fs in zip(t.nrm, facesum)]
        out.append(t)

    s = 1.0 / TEAPOT_HEIGHT
    return out.transformed(lambda p: (p[0] * s, p[2] * s, -p[1] * s), lambda v: (v[0], v[2], -v[1]))


# ----------------------------------------------------------------------------------------------------------
# Other shapes


def revolve(profile, segments):
    """Closed surface of revolution about +Y. profile: list of (r, y, nr, ny) from one pole to the other;
    a point with r == 0 is a pole (single vertex). Smooth normals from the profile normal."""
    m = Mesh()
    rings = []
    cs = [cos_sin(360.0 * k / segments) for k in range(segments)]
    for r, y, nr, ny in profile:
        if r == 0.0:
            rings.append([m.vertex((0.0, y, 0.0), (0.0, ny, 0.0))] * segments)
        else:
            rings.append([m.vertex((r * c, y, -r * s), (nr * c, ny, -nr * s)) for c, s in cs])
    for j in range(len(rings) - 1):
        A, B = rings[j], rings[j + 1]
        for k in range(segments):
            k2 = (k + 1) % segments
            for t in ((A[k], A[k2], B[k2]), (A[k], B[k2], B[k])):
                if len(set(t)) == 3:
                    m.tri.append(t)
    m.tri = orient_outward(m.tri, m.pos)
    return m


def arc(cx, cy, rad, a0, a1, steps, concave=False):
    """Profile samples on a circular arc (angles in degrees); normal radial (outward or, if concave, inward)."""
    out = []
    for k in range(steps + 1):
        c, s = cos_sin(a0 + (a1 - a0) * k / steps)
        sign = -1.0 if concave else 1.0
        out.append((cx + rad * c, cy + rad * s, sign * c, sign * s))
    return out


def line(r0, y0, r1, y1, nr, ny, steps):
    return [(r0 + (r1 - r0) * k / steps, y0 + (y1 - y0) * k / steps, nr, ny) for k in range(steps + 1)]


def make_cup(R=0.26, H=0.5, wall=0.024, floor_t=0.04, segments=64):
    """Closed mug without a handle: outer wall, rounded rim, inner wall, inner floor, rounded outer base.
    Every profile joint is tangent-continuous, so all normals are smooth and each position is one vertex."""
    rb = 0.03           # outer bottom fillet radius
    ri = 0.02           # inner bottom fillet radius
    Ri = R - wall
    w2 = wall / 2.0
    prof = []

    def extend(pts):
        for q in pts:
            if prof and abs(prof[-1][0] - q[0]) < 1e-12 and abs(prof[-1][1] - q[1]) < 1e-12:
                continue
            prof.append(q)

    extend(line(0.0, 0.0, R - rb, 0.0, 0.0, -1.0, 4))
    extend(arc(R - rb, rb, rb, -90.0, 0.0, 6))
    extend(line(R, rb, R, H - w2, 1.0, 0.0, 8))
    extend(arc(R - w2, H - w2, w2, 0.0, 180.0, 8))
    extend(line(Ri, H - w2, Ri, floor_t + ri, -1.0, 0.0, 8))
    extend(arc(Ri - ri, floor_t + ri, ri, 0.0, -90.0, 6, concave=True))
    extend(line(Ri - ri, floor_t, 0.0, floor_t, 0.0, 1.0, 4))
    return revolve(prof, segments)


def make_cylinder(radius, height, segments=32, stacks=4):
    """Closed cylinder standing on y=0: smooth side, flat caps with their own vertices (hard edges)."""
    m = Mesh()
    cs = [cos_sin(360.0 * k / segments) for k in range(segments)]
    rings = []
    for j in range(stacks + 1):
        y = height * j / stacks
        rings.append([m.vertex((radius * c, y, -radius * s), (c, 0.0, -s)) for c, s in cs])
    for j in range(stacks):
        for k in range(segments):
            k2 = (k + 1) % segments
            a, b, c, d = rings[j][k], rings[j][k2], rings[j + 1][k2], rings[j + 1][k]
            m.tri += [(a, b, c), (a, c, d)]
    for y, ny in ((0.0, -1.0), (height, 1.0)):
        c0 = m.vertex((0.0, y, 0.0), (0.0, ny, 0.0))
        ids = [m.vertex((radius * c, y, -radius * s), (0.0, ny, 0.0)) for c, s in cs]
        for k in range(segments):
            m.tri.append((c0, ids[k], ids[(k + 1) % segments]))
    m.tri = orient_outward(m.tri, m.pos)
    return m


def make_box(sx, sy, sz):
    """Closed box standing on y=0, centred in x and z; 24 vertices (hard edges)."""
    x, z = sx / 2.0, sz / 2.0
    m = Mesh()
    v = [(-x, 0.0, -z), (x, 0.0, -z), (x, sy, -z), (-x, sy, -z), (-x, 0.0, z), (x, 0.0, z), (x, sy, z), (-x, sy, z)]
    for a, b, c, d in ((4, 5, 6, 7), (1, 0, 3, 2), (5, 1, 2, 6), (0, 4, 7, 3), (7, 6, 2, 3), (0, 1, 5, 4)):
        m.quad(v[a], v[b], v[c], v[d])
    return m


def make_sphere(radius, segments=32, rings=16):
    prof = []
    for j in range(rings + 1):
        c, s = cos_sin(-90.0 + 180.0 * j / rings)
        prof.append((0.0 if j in (0, rings) else radius * c, radius * s, c, s))
    m = revolve(prof, segments)
    return m.transformed(lambda p: (p[0], p[1] + radius, p[2]), lambda n: n)


def checker_floor(x0, x1, z0, z1, tiles_x, tiles_z, y=0.0):
    """Two meshes (light and dark tiles) of an upward-facing checkerboard."""
    light, dark = Mesh(), Mesh()
    for i in range(tiles_x):
        for j in range(tiles_z):
            xa, xb = x0 + (x1 - x0) * i / tiles_x, x0 + (x1 - x0) * (i + 1) / tiles_x
            za, zb = z0 + (z1 - z0) * j / tiles_z, z0 + (z1 - z0) * (j + 1) / tiles_z
            m = light if (i + j) % 2 == 0 else dark
            m.quad((xa, y, zb), (xb, y, zb), (xb, y, za), (xa, y, za), (0.0, 1.0, 0.0))
    return light, dark


def wall_panels(corner, right, up, width, height, cols, rows, skip=()):
    """Wall facing the room split into cols x rows panels, alternating between 2 meshes.
    corner: bottom-left corner seen from inside; right/up: unit vectors along the wall. Panels whose
    (col, row) is in 'skip' are left out (openings)."""
    n = normalize(cross(right, up))
    a_mesh, b_mesh = Mesh(), Mesh()
    for i in range(cols):
        for j in range(rows):
            if (i, j) in skip:
                continue
            u0, u1 = width * i / cols, width * (i + 1) / cols
            v0, v1 = height * j / rows, height * (j + 1) / rows
            p = [add(corner, add(mul(right, u), mul(up, v))) for u, v in ((u0, v0), (u1, v0), (u1, v1), (u0, v1))]
            (a_mesh if (i + j) % 2 == 0 else b_mesh).quad(p[0], p[1], p[2], p[3], n)
    return a_mesh, b_mesh


# ----------------------------------------------------------------------------------------------------------
# glTF writer


def look_at_quat(eye, target, up=(0.0, 1.0, 0.0)):
    """Rotation quaternion (x, y, z, w) of a glTF camera node at eye looking at target (camera looks -Z)."""
    f = normalize(sub(target, eye))
    z = mul(f, -1.0)
    x = normalize(cross(up, z))
    y = cross(z, x)
    m00, m01, m02 = x[0], y[0], z[0]
    m10, m11, m12 = x[1], y[1], z[1]
    m20, m21, m22 = x[2], y[2], z[2]
    tr = m00 + m11 + m22
    if tr > 0.0:
        s = 0.5 / math.sqrt(tr + 1.0)
        q = ((m21 - m12) * s, (m02 - m20) * s, (m10 - m01) * s, 0.25 / s)
    elif m00 > m11 and m00 > m22:
        s = 2.0 * math.sqrt(1.0 + m00 - m11 - m22)
        q = (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    elif m11 > m22:
        s = 2.0 * math.sqrt(1.0 + m11 - m00 - m22)
        q = ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    else:
        s = 2.0 * math.sqrt(1.0 + m22 - m00 - m11)
        q = ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)
    return normalize4(q)


def normalize4(q):
    n = math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    return tuple(c / n for c in q)


class GltfBuilder:
    def __init__(self, name):
        self.name = name
        self.bin = bytearray()
        self.doc = {
            "asset": {"version": "2.0", "generator": "pemref scripts/make_scenes.py",
                      "copyright": "pemref authors, MIT (generated); teapot geometry from Newell's patch data"},
            "extensionsUsed": [],
            "scene": 0,
            "scenes": [],
            "nodes": [],
            "meshes": [],
            "materials": [],
            "cameras": [],
            "accessors": [],
            "bufferViews": [],
            "buffers": [],
        }
        self.material_index = {}
        self.lights = []
        self.stats = []  # (node name, triangles, vertices)

    def use_ext(self, ext):
        if ext not in self.doc["extensionsUsed"]:
            self.doc["extensionsUsed"].append(ext)

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        off = len(self.bin)
        self.bin += data
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": off, "byteLength": len(data), "target": target})
        return len(self.doc["bufferViews"]) - 1

    def _accessor(self, acc):
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def material(self, name, mat):
        if name not in self.material_index:
            m = {"name": name}
            m.update(mat)
            self.doc["materials"].append(m)
            self.material_index[name] = len(self.doc["materials"]) - 1
            for ext in mat.get("extensions", {}):
                self.use_ext(ext)
        return self.material_index[name]

    def primitive(self, mesh, material):
        pos = [tuple(f32(c) for c in p) for p in mesh.pos]
        nrm = [tuple(f32(c) for c in normalize(n)) for n in mesh.nrm]
        pdata = b"".join(struct.pack("<3f", *p) for p in pos)
        ndata = b"".join(struct.pack("<3f", *n) for n in nrm)
        idata = b"".join(struct.pack("<3I", *t) for t in mesh.tri)
        pv = self._view(pdata, 34962)
        nv = self._view(ndata, 34962)
        iv = self._view(idata, 34963)
        mn = [f32_json(min(p[k] for p in pos)) for k in range(3)]
        mx = [f32_json(max(p[k] for p in pos)) for k in range(3)]
        pa = self._accessor({"bufferView": pv, "componentType": 5126, "count": len(pos), "type": "VEC3",
                             "min": mn, "max": mx})
        na = self._accessor({"bufferView": nv, "componentType": 5126, "count": len(nrm), "type": "VEC3"})
        ia = self._accessor({"bufferView": iv, "componentType": 5125, "count": 3 * len(mesh.tri), "type": "SCALAR"})
        return {"attributes": {"POSITION": pa, "NORMAL": na}, "indices": ia, "material": material, "mode": 4}

    def mesh_node(self, name, parts, translation=None, extras=None):
        """parts: list of (Mesh, material index); one glTF mesh with one primitive per part."""
        prims = [self.primitive(m, mat) for m, mat in parts if m.tri]
        self.doc["meshes"].append({"name": name, "primitives": prims})
        node = {"name": name, "mesh": len(self.doc["meshes"]) - 1}
        if translation is not None:
            node["translation"] = [f32_json(c) for c in translation]
        if extras:
            node["extras"] = extras
        self.doc["nodes"].append(node)
        open_edges = ""
        if extras and extras.get("pemref_role") == "lens":  # lens objects must be closed volumes
            open_edges = sum(boundary_edge_count(m.pos, m.tri) for m, _ in parts)
            assert open_edges == 0, "%s: %d boundary edges" % (name, open_edges)
        self.stats.append((name, sum(len(m.tri) for m, _ in parts), sum(len(m.pos) for m, _ in parts), open_edges))
        return len(self.doc["nodes"]) - 1

    def camera_node(self, name, eye, target, yfov_deg, aspect, znear=0.05, zfar=100.0):
        self.doc["cameras"].append({"name": name, "type": "perspective", "perspective": {
            "aspectRatio": f32_json(aspect), "yfov": f32_json(math.radians(yfov_deg)),
            "znear": f32_json(znear), "zfar": f32_json(zfar)}})
        self.doc["nodes"].append({"name": name, "camera": len(self.doc["cameras"]) - 1,
                                  "rotation": [f32_json(c) for c in look_at_quat(eye, target)],
                                  "translation": [f32_json(c) for c in eye],
                                  "extras": {"pemref_look_at": [f32_json(c) for c in target]}})
        return len(self.doc["nodes"]) - 1

    def point_light_node(self, name, pos, color, intensity):
        self.use_ext("KHR_lights_punctual")
        self.lights.append({"name": name, "type": "point", "color": [f32_json(c) for c in color],
                            "intensity": f32_json(intensity)})
        self.doc["nodes"].append({"name": name, "translation": [f32_json(c) for c in pos],
                                  "extensions": {"KHR_lights_punctual": {"light": len(self.lights) - 1}}})
        return len(self.doc["nodes"]) - 1

    def finish(self, scene_extras=None):
        nodes = list(range(len(self.doc["nodes"])))
        scene = {"name": self.name, "nodes": nodes}
        if scene_extras:
            scene["extras"] = scene_extras
        self.doc["scenes"].append(scene)
        if self.lights:
            self.doc["extensions"] = {"KHR_lights_punctual": {"lights": self.lights}}
        if not self.doc["extensionsUsed"]:
            del self.doc["extensionsUsed"]
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["buffers"].append({"uri": self.name + ".bin", "byteLength": len(self.bin)})
        text = json.dumps(self.doc, indent=1, ensure_ascii=True, allow_nan=False) + "\n"
        return text.encode("ascii"), bytes(self.bin)


# ----------------------------------------------------------------------------------------------------------
# Materials


def diffuse(rgb):
    return {"pbrMetallicRoughness": {"baseColorFactor": [f32_json(c) for c in rgb] + [1.0],
                                     "metallicFactor": 0.0, "roughnessFactor": 1.0}}


def mirror(f0):
    return {"pbrMetallicRoughness": {"baseColorFactor": [f32_json(c) for c in f0] + [1.0],
                                     "metallicFactor": 1.0, "roughnessFactor": 0.0}}


GLASS = {
    "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
    "extensions": {
        "KHR_materials_transmission": {"transmissionFactor": 1.0},
        "KHR_materials_ior": {"ior": 1.5},
        "KHR_materials_volume": {"thicknessFactor": 0.3, "attenuationDistance": 1.5,
                                 "attenuationColor": [0.82, 0.95, 0.9]},
    },
}

# ----------------------------------------------------------------------------------------------------------
# Scenes


def viewpoint_circle(center, radius, height, start_deg, step_deg, count):
    return {"kind": "circle", "center": [f32_json(c) for c in center], "radius": f32_json(radius),
            "height": f32_json(height), "start_deg": f32_json(start_deg), "step_deg": f32_json(step_deg),
            "count": count}


def circle_eye(center, radius, height, deg):
    c, s = cos_sin(deg)
    return (center[0] + radius * s, height, center[2] + radius * c)


def room_walls(g, x0, x1, z0, z1, h, palette, cols, rows, skip=None):
    """Four inward-facing walls. palette: {wall name: (colour A, colour B)}; skip: {wall: set of panels}."""
    skip = skip or {}
    walls = (
        ("wall_north", (x0, 0.0, z0), (1.0, 0.0, 0.0), x1 - x0),   # at z = z0, seen from +z
        ("wall_east", (x1, 0.0, z0), (0.0, 0.0, 1.0), z1 - z0),    # at x = x1, seen from -x
        ("wall_south", (x1, 0.0, z1), (-1.0, 0.0, 0.0), x1 - x0),  # at z = z1, seen from -z
        ("wall_west", (x0, 0.0, z1), (0.0, 0.0, -1.0), z1 - z0),   # at x = x0, seen from +x
    )
    for name, corner, right, width in walls:
        ca, cb = palette[name]
        a, b = wall_panels(corner, right, (0.0, 1.0, 0.0), width, h, cols, rows, skip.get(name, ()))
        g.mesh_node(name, [(a, g.material(name + "_a", diffuse(ca))), (b, g.material(name + "_b", diffuse(cb)))])


def scene_hybrid(n):
    """Hybrid paper, Sec. 6: glass teapot, reflective cup, ring of columns, distant walls."""
    g = GltfBuilder("hybrid_glass_teapot")
    teapot = make_teapot(n)
    g.mesh_node("glass_teapot", [(teapot, g.material("glass", GLASS))], translation=(0.0, LIFT, 0.0),
                extras={"pemref_role": "lens"})
    cup = make_cup()
    g.mesh_node("mirror_cup", [(cup, g.material("mirror_cup", mirror((0.9, 0.9, 0.9))))],
                translation=(1.45, LIFT, -0.75), extras={"pemref_role": "lens"})

    ring_r, col_r, col_h = 4.0, 0.2, 3.0
    col_colours = [(0.75, 0.72, 0.62), (0.55, 0.6, 0.72)]
    for k in range(8):
        c, s = cos_sin(22.5 + 45.0 * k)
        mat = g.material("column_%s" % ("stone", "slate")[k % 2], diffuse(col_colours[k % 2]))
        g.mesh_node("column_%d" % k, [(make_cylinder(col_r, col_h), mat)], translation=(ring_r * s, 0.0, ring_r * c))

    half, wall_h = 9.0, 4.0
    light, dark = checker_floor(-half, half, -half, half, 18, 18)
    g.mesh_node("floor", [(light, g.material("floor_light", diffuse((0.8, 0.8, 0.78)))),
                          (dark, g.material("floor_dark", diffuse((0.25, 0.25, 0.27))))])
    palette = {"wall_north": ((0.8, 0.2, 0.15), (0.9, 0.75, 0.3)),
               "wall_east": ((0.15, 0.55, 0.25), (0.85, 0.85, 0.8)),
               "wall_south": ((0.15, 0.3, 0.75), (0.9, 0.6, 0.2)),
               "wall_west": ((0.6, 0.25, 0.6), (0.3, 0.7, 0.75))}
    # no ceiling, and a 2-panel opening in the west wall: the environment map shows above and through it
    room_walls(g, -half, half, -half, half, wall_h, palette, 6, 2, skip={"wall_west": {(2, 1), (3, 1)}})

    g.point_light_node("light_key", (2.5, 3.5, 3.0), (1.0, 0.96, 0.9), 80.0)
    g.point_light_node("light_fill", (-3.0, 2.5, -1.5), (0.85, 0.9, 1.0), 30.0)

    center = (0.25, 0.45, 0.0)
    radius, height = 3.3, 1.4
    eye = circle_eye(center, radius, height, 0.0)
    g.camera_node("camera", eye, center, 40.0, 4.0 / 3.0)
    extras = {
        "pemref_environment": {"uri": "../env/studio.exr", "mapping": "latlong", "intensity": 1.0},
        "pemref_viewpoints": viewpoint_circle(center, radius, height, 0.0, 8.0, 45),
    }
    return g, extras


def scene_pem(n):
    """PEM paper, Sec. 6: mirror teapot in a room environment."""
    g = GltfBuilder("pem_mirror_teapot")
    teapot = make_teapot(n)
    g.mesh_node("mirror_teapot", [(teapot, g.material("mirror_silver", mirror((0.95, 0.93, 0.88))))],
                translation=(0.0, LIFT, 0.0), extras={"pemref_role": "lens"})

    x0, x1, z0, z1, h = -4.0, 4.0, -4.0, 4.0, 3.0
    light, dark = checker_floor(x0, x1, z0, z1, 16, 16)
    g.mesh_node("floor", [(light, g.material("floor_light", diffuse((0.78, 0.76, 0.7)))),
                          (dark, g.material("floor_dark", diffuse((0.3, 0.22, 0.18))))])
    ceiling = Mesh()
    ceiling.quad((x0, h, z0), (x1, h, z0), (x1, h, z1), (x0, h, z1), (0.0, -1.0, 0.0))
    g.mesh_node("ceiling", [(ceiling, g.material("ceiling", diffuse((0.85, 0.85, 0.85))))])
    palette = {"wall_north": ((0.75, 0.25, 0.2), (0.85, 0.8, 0.7)),
               "wall_east": ((0.2, 0.5, 0.3), (0.8, 0.8, 0.7)),
               "wall_south": ((0.2, 0.3, 0.7), (0.85, 0.8, 0.7)),
               "wall_west": ((0.85, 0.65, 0.2), (0.8, 0.8, 0.7))}
    room_walls(g, x0, x1, z0, z1, h, palette, 4, 2)

    window = Mesh()
    wz = z0 + 0.005
    window.quad((-1.0, 1.0, wz), (1.0, 1.0, wz), (1.0, 2.2, wz), (-1.0, 2.2, wz), (0.0, 0.0, 1.0))
    g.mesh_node("window_light", [(window, g.material("window_emissive", {
        "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0,
                                 "roughnessFactor": 1.0},
        "emissiveFactor": [1.0, 0.97, 0.9],
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4.0}}}))])

    g.mesh_node("box_red", [(make_box(0.6, 0.6, 0.6), g.material("box_red", diffuse((0.8, 0.15, 0.1))))],
                translation=(-2.0, 0.0, -1.6))
    g.mesh_node("box_tall_blue", [(make_box(0.4, 1.3, 0.4), g.material("box_blue", diffuse((0.15, 0.3, 0.8))))],
                translation=(2.0, 0.0, -2.2))
    g.mesh_node("ball_yellow", [(make_sphere(0.25), g.material("ball_yellow", diffuse((0.9, 0.75, 0.15))))],
                translation=(1.6, 0.0, 1.2))
    g.mesh_node("box_green", [(make_box(0.5, 0.35, 0.8), g.material("box_green", diffuse((0.2, 0.6, 0.25))))],
                translation=(-1.8, 0.0, 1.5))

    g.point_light_node("light_ceiling", (0.3, 2.7, 1.2), (1.0, 0.97, 0.92), 30.0)

    center = (0.1, 0.45, 0.0)
    radius, height = 3.3, 1.3
    eye = circle_eye(center, radius, height, 0.0)
    g.camera_node("camera", eye, center, 45.0, 1.0)
    extras = {"pemref_viewpoints": viewpoint_circle(center, radius, height, -50.0, 1.0, 100)}
    return g, extras


def scene_sphere(n):
    """A convex reflector: a mirror sphere on a checker floor in a small room (the case where
    the PEM split needs no local layer and no refraction term)."""
    g = GltfBuilder("mirror_sphere")
    g.mesh_node("mirror_sphere", [(make_sphere(0.5, 48, 24), g.material("mirror_chrome", mirror((0.9, 0.9, 0.9))))],
                translation=(0.0, 0.0, 0.0), extras={"pemref_role": "lens"})
    x0, x1, z0, z1, h = -3.0, 3.0, -3.0, 3.0, 2.5
    light, dark = checker_floor(x0, x1, z0, z1, 12, 12)
    g.mesh_node("floor", [(light, g.material("floor_light", diffuse((0.8, 0.78, 0.72)))),
                          (dark, g.material("floor_dark", diffuse((0.25, 0.2, 0.18))))])
    palette = {"wall_north": ((0.75, 0.25, 0.2), (0.85, 0.8, 0.7)),
               "wall_east": ((0.2, 0.5, 0.3), (0.8, 0.8, 0.7)),
               "wall_south": ((0.2, 0.3, 0.7), (0.85, 0.8, 0.7)),
               "wall_west": ((0.85, 0.65, 0.2), (0.8, 0.8, 0.7))}
    room_walls(g, x0, x1, z0, z1, h, palette, 3, 2)
    g.mesh_node("box_red", [(make_box(0.5, 0.5, 0.5), g.material("box_red", diffuse((0.8, 0.15, 0.1))))],
                translation=(-1.2, 0.0, -0.8))
    g.point_light_node("light_ceiling", (0.3, 2.2, 1.0), (1.0, 0.97, 0.92), 20.0)
    center = (0.0, 0.5, 0.0)
    radius, height = 2.2, 1.0
    eye = circle_eye(center, radius, height, 0.0)
    g.camera_node("camera", eye, center, 45.0, 4.0 / 3.0)
    extras = {"pemref_environment": {"uri": "../env/sky.exr", "mapping": "latlong", "intensity": 1.0},
              "pemref_viewpoints": viewpoint_circle(center, radius, height, -30.0, 10.0, 7)}
    return g, extras


# ----------------------------------------------------------------------------------------------------------


def build_all():
    outputs = []
    for fn, n in ((scene_hybrid, 16), (scene_pem, 25), (scene_sphere, 0)):
        g, extras = fn(n)
        gltf, binary = g.finish(extras)
        outputs.append((g.name, gltf, binary, g.stats))
    return outputs


def main():
    check = "--check" in sys.argv[1:]
    ok = True
    for name, gltf, binary, stats in build_all():
        files = ((os.path.join(OUT_DIR, name + ".gltf"), gltf), (os.path.join(OUT_DIR, name + ".bin"), binary))
        for path, data in files:
            if check:
                same = os.path.exists(path) and open(path, "rb").read() == data
                ok = ok and same
                print("%-40s %s" % (os.path.relpath(path, ROOT), "ok" if same else "DIFFERS"))
            else:
                os.makedirs(os.path.dirname(path), exist_ok=True)
                with open(path, "wb") as f:
                    f.write(data)
                print("wrote %-40s %9d bytes" % (os.path.relpath(path, ROOT), len(data)))
        if not check:
            for node, tris, verts, open_edges in stats:
                closed = "" if open_edges == "" else "  boundary edges: %d" % open_edges
                print("    %-16s %7d triangles %7d vertices%s" % (node, tris, verts, closed))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
