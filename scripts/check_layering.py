#!/usr/bin/env python3
"""check_layering.py [--root DIR] — every #include and every target_link_libraries of pemref's
own code points down the layers, so no folder cycle can form:

    base → raster → trace → infer, runtime (siblings) → pipeline → viewer_tty
    viewer_tty rooms: tty, conformance, stability (each on its own) → report, golden → cli

Each folder may include (and link) only the folders listed for it in ALLOWED; Embree only in
trace/, Eigen only in infer/. tests/ and bench/ sit on top and may use anything. Prints one line
per violation, `file:line: <what>`, and exits 1 if there is any."""
import os, re, sys

ALLOWED = {
    "base": {"base"},
    "raster": {"base", "raster"},
    "trace": {"base", "raster", "trace"},
    "infer": {"base", "raster", "infer"},
    "runtime": {"base", "raster", "trace", "runtime"},
    "pipeline": {"base", "raster", "trace", "infer", "runtime", "pipeline"},
    "viewer_tty/tty": {"base", "viewer_tty/tty"},
    "viewer_tty/conformance": {"base", "raster", "viewer_tty/conformance"},
    "viewer_tty/stability": {"base", "raster", "trace", "infer", "viewer_tty/stability"},
    "viewer_tty/report": {"base", "raster", "trace", "infer", "runtime", "pipeline",
                          "viewer_tty/stability", "viewer_tty/report"},
    "viewer_tty/golden": {"base", "raster", "trace", "infer", "runtime", "pipeline",
                          "viewer_tty/conformance", "viewer_tty/golden"},
    "viewer_tty/cli": {"base", "raster", "trace", "infer", "runtime", "pipeline",
                       "viewer_tty/tty", "viewer_tty/conformance", "viewer_tty/stability",
                       "viewer_tty/report", "viewer_tty/golden", "viewer_tty/cli"},
}
# Library targets and the folder that owns each.
TARGETS = {"pem_base": "base", "pem_raster": "raster", "pem_trace": "trace",
           "pem_infer": "infer", "pem_runtime": "runtime", "pem_pipeline": "pipeline",
           "pem_tty": "viewer_tty/tty", "pem_conformance": "viewer_tty/conformance",
           "pem_gl": "viewer_tty/conformance", "pem_stability": "viewer_tty/stability",
           "pem_report": "viewer_tty/report", "pem_golden": "viewer_tty/golden"}
THIRD_PARTY = [(re.compile(r"#\s*include\s*<embree"), "trace", "Embree"),
               (re.compile(r"#\s*include\s*<Eigen"), "infer", "Eigen")]
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
LINK = re.compile(r"target_link_libraries\s*\(\s*(\S+)([^)]*)\)", re.S)


def module_of(rel):
    """The layer a path belongs to (the longest ALLOWED key that prefixes it), or None."""
    best = None
    for m in ALLOWED:
        if rel == m or rel.startswith(m + "/"):
            if best is None or len(m) > len(best):
                best = m
    return best


def check_sources(root, problems):
    for m in ALLOWED:
        for dirpath, _, files in os.walk(os.path.join(root, m)):
            for f in sorted(files):
                if not f.endswith((".h", ".cpp")):
                    continue
                path = os.path.join(dirpath, f)
                rel = os.path.relpath(path, root)
                own = module_of(rel)
                with open(path, encoding="utf-8", errors="replace") as fh:
                    for n, line in enumerate(fh, 1):
                        for pattern, home, name in THIRD_PARTY:
                            if pattern.search(line) and own != home:
                                problems.append(f"{rel}:{n}: includes {name}, which only {home}/ may use")
                        inc = INCLUDE.match(line)
                        if not inc:
                            continue
                        target = module_of(inc.group(1))
                        if target is None:
                            if "/" in inc.group(1):
                                problems.append(f"{rel}:{n}: includes \"{inc.group(1)}\", outside every layer")
                            continue
                        if target not in ALLOWED[own]:
                            problems.append(f"{rel}:{n}: {own}/ includes \"{inc.group(1)}\" "
                                            f"({target}/ is not below {own}/)")


def check_links(root, problems):
    for m in ALLOWED:
        path = os.path.join(root, m, "CMakeLists.txt")
        if not os.path.exists(path):
            continue
        text = open(path, encoding="utf-8").read()
        for match in LINK.finditer(text):
            line = text.count("\n", 0, match.start()) + 1
            for word in match.group(2).split():
                dep = TARGETS.get(word)
                if dep and dep not in ALLOWED[m]:
                    problems.append(f"{m}/CMakeLists.txt:{line}: {match.group(1)} links {word} "
                                    f"({dep}/ is not below {m}/)")


def main():
    root = sys.argv[sys.argv.index("--root") + 1] if "--root" in sys.argv else \
        os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    problems = []
    check_sources(root, problems)
    check_links(root, problems)
    for p in problems:
        print(p)
    if problems:
        print(f"layering: {len(problems)} include(s) or link(s) point up or sideways")
        return 1
    print("layering: every include and link points down")
    return 0


if __name__ == "__main__":
    sys.exit(main())
