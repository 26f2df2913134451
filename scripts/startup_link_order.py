#!/usr/bin/python3
"""The order in which `sealfe` names its shared libraries, for a faster process start.

    scripts/startup_link_order.py derive NATURAL [-o cmake/startup_link_order.txt]
    scripts/startup_link_order.py check REORDERED NATURAL

Debian's deal.II brings about 230 shared libraries into the process (PETSc, Trilinos, gmsh,
OpenCASCADE, ...), and most of a small run's start is the dynamic loader binding their ~190 000
symbol references (doc/performance.md "Process start-up"). Each reference is looked up along the
global scope, the executable's libraries in breadth-first order, until the first library that
defines it: a library deep in that list (gmsh, OpenCASCADE, OpenBLAS) pays a hash check in every
library before it, for each of its own references. Naming the libraries that receive the most
bindings first in the executable (DT_NEEDED order) shortens those walks.

Moving a library forward must not change which definition any reference binds to: where two
libraries define the same symbol (`libblas.so.3` and `libopenblas.so.0` both define dgemm_; libm
and libc both define modf), the first in the scope wins. `derive` starts from the libraries sorted
by the bindings they receive and, for every binding the candidate order moves, adds the constraint
that the natural winner comes first (bringing it into the list if it was not; a library that
others wait for is placed as early as the most bound-to of them), until no binding moves. It runs
NATURAL (an executable linked without the order, CMake target `sealfe_natural_link_order`) with
the candidate order preloaded, which builds the same scope. Copies of C++ vague-linkage
definitions (weak or unique in every library that has them: inline functions, template instances,
vtables) are interchangeable and may come from another library (interchangeable()). `check`
compares every binding of REORDERED against NATURAL's, with all references bound at start
(LD_BIND_NOW: the lazy function references too), and fails on any other difference (ctest
`startup_link_order_keeps_every_binding`).
"""
import argparse, collections, functools, os, re, subprocess, sys, tempfile

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
LOADER = "ld-linux-x86-64.so.2"


def bindings(binary, bind_now, preload=()):
    """{(referencing object, symbol, version): defining object} of a bare `solve` of `binary` in
    an empty directory, objects by file name (the executable as '<executable>'), and the number of
    bindings made."""
    with tempfile.TemporaryDirectory() as work:
        env = dict(ENV, LD_DEBUG="bindings", LD_DEBUG_OUTPUT=os.path.join(work, "ld"))
        if bind_now:
            env["LD_BIND_NOW"] = "1"
        if preload:
            env["LD_PRELOAD"] = ":".join(preload)
        run = os.path.join(work, "run")
        os.mkdir(run)
        r = subprocess.run([os.path.abspath(binary), "solve"], cwd=run, env=env,
                           capture_output=True, text=True)
        if r.returncode:
            sys.exit(f"{binary} solve failed: {r.stderr.strip()[-300:]}")
        exe = os.path.realpath(binary)

        @functools.lru_cache(maxsize=None)
        def name(path):
            return "<executable>" if os.path.realpath(path) == exe else os.path.basename(path)

        found, made = {}, 0
        for f in os.listdir(work):
            if not f.startswith("ld."):
                continue
            for line in open(os.path.join(work, f), errors="replace"):
                # "PID: binding file A [n] to B [n]: normal symbol `S' [VERSION]" (split, not a
                # regular expression: a bound-now run writes ~400 000 of these lines)
                parts = line.split()
                if len(parts) < 11 or parts[1] != "binding":
                    continue
                made += 1
                version = parts[11][1:-1] if len(parts) > 11 else None
                found[(name(parts[3]), parts[10][1:-1], version)] = name(parts[6])
        if not found:
            sys.exit("no bindings reported: is LD_DEBUG honoured (glibc's ld.so)?")
        return found, made


def paths(natural):
    """File name -> path of every library in NATURAL's process (from `ldd`)."""
    out = subprocess.run(["ldd", natural], capture_output=True, text=True, check=True).stdout
    return {m[1]: m[2] for m in re.finditer(r"^\s*(\S+) => (\S+)", out, re.M)}


_kinds = {}


def interchangeable(symbol, libraries, lib_path):
    """Whether every one of `libraries` defines `symbol` weakly or as a unique global: C++ vague
    linkage (inline functions, template instances, vtables, type information, static locals of
    inline functions), where any copy is the definition, which the compilers emit in every object
    that uses it, and which the loader then takes from the first library in the scope for every
    reference alike. A strong (global) definition in any of them is an interposition and keeps
    its winner."""
    for lib in libraries:
        if lib not in lib_path:
            return False
        if lib not in _kinds:
            out = subprocess.run(["nm", "-D", "--defined-only", lib_path[lib]],
                                 capture_output=True, text=True).stdout
            kinds = {}
            for line in out.splitlines():
                parts = line.split()
                if len(parts) == 3:
                    name = parts[2].split("@")[0]
                    kinds.setdefault(name, set()).add(parts[1])
            _kinds[lib] = kinds
        if not _kinds[lib].get(symbol) or not _kinds[lib][symbol] <= set("WVu"):
            return False
    return True


def moved(reference, other, lib_path=None):
    """Bindings of `other` whose definition differs from `reference`'s: [(key, was, now)]; with
    `lib_path`, only those not between interchangeable copies (interchangeable())."""
    return [(k, reference[k], other[k]) for k in reference
            if k in other and other[k] != reference[k]
            and not (lib_path and interchangeable(k[1], (reference[k], other[k]), lib_path))]


def order(weights, before, candidates):
    """Candidates by descending weight, each placed only after every library that must precede it
    (Kahn's sort, heaviest ready library first); a library that must follow one not among the
    candidates is dropped (it keeps its natural place behind that one)."""
    keep = set(candidates)
    changed = True
    while changed:
        changed = False
        for lib in list(keep):
            if any(a not in keep for a in before[lib]):
                keep.discard(lib)
                changed = True
    # a library others wait for is as urgent as the most bound-to of them (liblapack before
    # OpenBLAS: placing it late would hold OpenBLAS back too)
    urgency = {l: weights[l] for l in keep}
    changed = True
    while changed:
        changed = False
        for lib in keep:
            for first in before[lib]:
                if urgency[first] < urgency[lib]:
                    urgency[first] = urgency[lib]
                    changed = True
    result, placed = [], set()
    while len(result) < len(keep):
        ready = [l for l in keep if l not in placed and before[l] <= placed]
        if not ready:
            sys.exit("the constraints form a cycle: " + ", ".join(sorted(keep - placed)))
        best = max(ready, key=lambda l: (urgency[l], weights[l], l))
        result.append(best)
        placed.add(best)
    return result


def derive(natural, output):
    lib_path = paths(natural)
    start, made = bindings(natural, bind_now=False)
    weights = collections.Counter(start.values())
    complete, _ = bindings(natural, bind_now=True)
    candidates = [l for l in weights if l in lib_path and l != LOADER]
    before = collections.defaultdict(set)
    for attempt in range(50):
        candidate = order(weights, before, candidates)
        preloaded, _ = bindings(natural, True, [lib_path[l] for l in candidate])
        diff = moved(complete, preloaded, lib_path)
        print(f"order {attempt}: {len(candidate)} libraries first, {len(diff)} bindings moved",
              file=sys.stderr, flush=True)
        if not diff:
            break
        for _, was, now in diff:
            before[now].add(was)
            # the natural winner joins the list when it can (a preloaded library's dependencies
            # enter the scope's tail in another order, which can reorder two libraries neither
            # of which was moved)
            for lib in (was, now):
                if lib in lib_path and lib != LOADER and lib not in candidates:
                    candidates.append(lib)
    else:
        sys.exit("no order without moved bindings after 50 rounds")
    with open(output, "w") as f:
        f.write("# The shared libraries sealfe names first (DT_NEEDED order), most bound-to first;\n"
                "# written by scripts/startup_link_order.py derive, which says why. A library\n"
                "# missing on this system is skipped at configure time.\n")
        f.write("".join(l + "\n" for l in candidate))
    print(f"wrote {output}: {len(candidate)} libraries; {made} bindings at start", file=sys.stderr)


def check(reordered, natural):
    want, _ = bindings(natural, bind_now=True)
    got, _ = bindings(reordered, bind_now=True)
    diff = moved(want, got, paths(natural))
    copies = len(moved(want, got)) - len(diff)
    missing = len(set(want) ^ set(got))
    for (obj, sym, ver), was, now in diff[:20]:
        print(f"{obj}: {sym}{'@' + ver if ver else ''} bound to {now}, naturally {was}")
    print(f"{len(want)} bindings compared: {len(diff)} moved, {missing} present in one run only; "
          f"{copies} bound to another copy of an interchangeable (weak or unique) definition")
    return 1 if diff or missing else 0


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="what", required=True)
    d = sub.add_parser("derive")
    d.add_argument("natural")
    d.add_argument("-o", "--output", default=os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "cmake", "startup_link_order.txt"))
    c = sub.add_parser("check")
    c.add_argument("reordered")
    c.add_argument("natural")
    a = p.parse_args()
    if a.what == "derive":
        derive(a.natural, a.output)
    else:
        sys.exit(check(a.reordered, a.natural))
