#!/usr/bin/python3
"""Re-pin the regression values of prm examples after a deliberate change of the numbers.

    /usr/bin/python3 scripts/repin_examples.py [--sealfe build/sealfe] NAME [NAME ...]

For each prm/NAME.prm, runs its sub-command (as tests/regression/prm_examples.cc does), and
rewrites the "value" of every pin in prm/NAME.reference.json from the new summary.json or CSV
cell, keeping tolerances and reasons. Prints each pin's relative move, and next to it the run's
own error estimate of that quantity where summary.json has one (error_estimate/<same pointer>),
so that the commit can say whether the numbers moved within the discretisation error.
Refuses (exit 1, nothing written) if a run fails or a pinned value is missing.
"""
import argparse, csv, json, os, subprocess, sys, tempfile

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def pointer_get(doc, pointer):
    for part in pointer.lstrip("/").split("/"):
        doc = doc[int(part)] if isinstance(doc, list) else doc[part]
    return doc


def csv_cell(path, row, column):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return float(rows[row][column])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sealfe", default=os.path.join(REPO, "build", "sealfe"))
    ap.add_argument("names", nargs="+")
    args = ap.parse_args()
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    updates = {}
    for name in args.names:
        ref_path = os.path.join(REPO, "prm", name + ".reference.json")
        reference = json.load(open(ref_path))
        work = tempfile.mkdtemp()
        out = os.path.join(work, "out")
        prm = os.path.join(work, "case.prm")
        with open(prm, "w") as f:
            f.write(f"include {os.path.join(REPO, 'prm', name + '.prm')}\n"
                    f"set Output directory = {out}\n")
        r = subprocess.run([args.sealfe, reference["sub_command"], prm], capture_output=True,
                           text=True, env=env)
        if r.returncode:
            sys.exit(f"repin: {name} failed: {r.stderr.strip()[-300:]}")
        summary = json.load(open(os.path.join(out, "summary.json")))
        print(f"{name}:")
        for pin in reference["values"]:
            if "pointer" in pin:
                new = pointer_get(summary, pin["pointer"])
                label = pin["pointer"]
                try:
                    estimate = pointer_get(summary, "/error_estimate" + pin["pointer"])
                except (KeyError, IndexError, ValueError, TypeError):
                    estimate = None
            else:
                new = csv_cell(os.path.join(out, pin["file"]), pin["row"], pin["column"])
                label, estimate = f"{pin['file']} row {pin['row']} {pin['column']}", None
            old = pin["value"]
            if isinstance(old, (int, float)) and isinstance(new, (int, float)) and old != new:
                move = abs(new - old) / abs(old) if old else float("inf")
                extra = ""
                if isinstance(estimate, (int, float)) and estimate:
                    extra = f", move / error estimate {abs(new - old) / abs(estimate):.2e}"
                print(f"  {label}: {old!r} -> {new!r} (relative {move:.2e}{extra})")
            pin["value"] = new
        updates[ref_path] = reference
    for path, reference in updates.items():
        with open(path, "w") as f:
            json.dump(reference, f, indent=2, ensure_ascii=False)
            f.write("\n")


if __name__ == "__main__":
    main()
