#!/usr/bin/env python3
"""Snapshot every user-visible output of one pfgen binary, to compare two binaries byte for byte.

A change that means to leave the outputs alone (a restructuring) is checked by running this with the
binary before and after it and diffing the two directories:

    scripts/compare-outputs.py --pfgen OLD/pfgen --out /tmp/before
    scripts/compare-outputs.py --pfgen NEW/pfgen --out /tmp/after
    diff -r /tmp/before /tmp/after && echo identical

What it runs, for every example model under examples/ and every filter kind the model supports
(plus the opt-in ukf): derive in text, LaTeX and JSON; eval at one point; latex; codegen in C++
(template, float, double, with the Eigen layers and --stats), C and Rust (float, double); then simulate
(seeded, small) on a set of models with CSVs, stops and the particle reference, and the recorded-data
commands (estimate's CSV and report, fit's report and JSON) on the records of examples/records/.
Each command's stdout, stderr (with the binary's own path and timings removed) and exit code are kept.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# simulate: (model, extra options); small, seeded, so the whole snapshot takes minutes.
SIMULATIONS = [
    ("examples/van_der_pol.yaml", ["--runs", "6", "--T", "2", "--reference", "particles:50", "--x0", "prior"]),
    ("examples/basin2006_quadratic.yaml", ["--runs", "8", "--T", "1"]),
    ("examples/basin_skliar_partial.yaml", ["--runs", "6", "--T", "2"]),
    ("examples/delay_linear.yaml", ["--runs", "6", "--T", "2"]),
    ("examples/polynomial/cubic_sensor.yaml", ["--runs", "6", "--T", "2", "--reference", "particles:50"]),
    ("examples/polynomial/range_squared_sampled.yaml", ["--runs", "6", "--T", "2"]),
    ("examples/allahyani_date_example1_gamma1.yaml", ["--runs", "6", "--T", "2"]),
    ("examples/paper002/reactor.yaml", ["--runs", "4", "--T", "1"]),
    ("examples/paper004/quadratic_009.yaml", ["--runs", "4", "--T", "1"]),
    ("examples/reference/double_well.yaml", ["--runs", "6", "--T", "2", "--reference", "particles:50"]),
    ("examples/leqg_tracking.yaml", ["--runs", "6", "--T", "2"]),
]

RECORDS = [
    ["estimate", "examples/van_der_pol.yaml", "--data", "examples/records/van_der_pol_increments.csv",
     "--filters", "optimal,ekf,additive", "--full-covariance"],
    ["estimate", "examples/delay_linear.yaml", "--data", "examples/records/delay_linear_increments.csv"],
    ["estimate", "examples/records/nile.yaml", "--data", "examples/records/nile.csv", "--time-column", "year"],
    ["estimate", "examples/records/boarding_school.yaml", "--data", "examples/records/boarding_school.csv",
     "--time-column", "day", "--t0", "0", "--set", "s=0", "--filters", "cd-optimal"],
    ["fit", "examples/van_der_pol.yaml", "--data", "examples/records/van_der_pol_increments.csv",
     "--estimate", "mu", "--bounds", "mu=0:5"],
    ["fit", "examples/records/nile.yaml", "--data", "examples/records/nile.csv", "--time-column", "year",
     "--estimate", "q,h", "--bounds", "q=0:,h=0:", "--profile"],
]

# Lines whose content is a measurement of this run, not an output: timings and the cache's paths.
VOLATILE = re.compile(r"(\d+(\.\d+)?\s*(s|ms|µs|us)\b)|(cache)|(compil)", re.IGNORECASE)


def run(pfgen, args, out_dir, name, files=()):
    """Runs pfgen ARGS in out_dir/work, keeps stdout, stderr, the exit code and the named files."""
    work = out_dir / "work"
    if work.exists():
        shutil.rmtree(work)
    work.mkdir()
    proc = subprocess.run([pfgen] + args, cwd=work, capture_output=True, timeout=3600)
    stderr = proc.stderr.decode("utf-8", "replace").replace(pfgen, "PFGEN").replace(str(ROOT), "ROOT")
    stderr = "\n".join(line for line in stderr.splitlines() if not VOLATILE.search(line))
    target = out_dir / name
    target.mkdir(parents=True, exist_ok=True)
    (target / "command").write_text(" ".join(args).replace(str(ROOT), "ROOT") + "\n")
    (target / "stdout").write_bytes(proc.stdout)
    (target / "stderr").write_text(stderr)
    (target / "exit").write_text(f"{proc.returncode}\n")
    for path in sorted(work.rglob("*")):
        if path.is_file():
            relative = path.relative_to(work)
            destination = target / "files" / relative
            destination.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(path, destination)
    shutil.rmtree(work)
    return proc


def kinds_of(pfgen, model, out_dir):
    proc = subprocess.run([pfgen, "codegen", "--stats", "-o", str(out_dir / "kinds_probe"), str(model)],
                          capture_output=True)
    shutil.rmtree(out_dir / "kinds_probe", ignore_errors=True)
    kinds = [json.loads(line)["filter"] for line in proc.stdout.decode().splitlines() if line.startswith("{")]
    return kinds + (["ukf"] if "ukf" not in kinds else [])


def model_size(pfgen, model, kind):
    proc = subprocess.run([pfgen, "derive", "--format", "json", "--filter", kind, str(model)], capture_output=True)
    try:
        document = json.loads(proc.stdout)
    except json.JSONDecodeError:
        return None
    drift = document.get("m_drift") if isinstance(document, dict) else None
    return len(drift) if isinstance(drift, list) else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pfgen", required=True, help="the pfgen binary")
    parser.add_argument("--out", required=True, help="a new directory for the snapshot")
    parser.add_argument("--skip-simulate", action="store_true", help="leave out simulate and the record commands")
    options = parser.parse_args()
    pfgen = str(Path(options.pfgen).resolve())
    out_dir = Path(options.out).resolve()
    if out_dir.exists():
        sys.exit(f"compare-outputs: --out {out_dir} exists; give a new directory")
    out_dir.mkdir(parents=True)
    os.environ.setdefault("PFGEN_CACHE_DIR", str(out_dir.parent / "pfgen-compare-cache"))

    models = sorted(p.relative_to(ROOT) for p in (ROOT / "examples").rglob("*.yaml")
                    if "consumer" not in p.parts and "api_project" not in p.parts)
    for model in models:
        source = str(ROOT / model)
        stem = str(model).replace("/", "_").removesuffix(".yaml")
        kinds = kinds_of(pfgen, source, out_dir)
        run(pfgen, ["latex", "-o", "model.tex", source], out_dir, f"{stem}/latex", ["model.tex"])
        run(pfgen, ["derive", "--coefficients", source], out_dir, f"{stem}/coefficients")
        for kind in kinds:
            for fmt in ("text", "latex", "json"):
                run(pfgen, ["derive", "--filter", kind, "--format", fmt, source], out_dir, f"{stem}/derive/{kind}.{fmt}")
            n = model_size(pfgen, source, kind)
            if n:
                m = ",".join(str(0.3 + 0.2 * i) for i in range(n))
                P = ";".join(",".join("1" if i == j else "0.1" for j in range(n)) for i in range(n))
                run(pfgen, ["eval", "--filter", kind, "--t", "0.5", f"--m={m}", "--P", P, source],
                    out_dir, f"{stem}/eval/{kind}")
        for scalar in ("template", "float", "double"):
            run(pfgen, ["codegen", "--stats", "--eigen", "--scalar", scalar, "-o", "code", source],
                out_dir, f"{stem}/codegen/cpp-{scalar}")
        for scalar in ("float", "double"):
            run(pfgen, ["codegen", "--language", "c", "--scalar", scalar, "-o", "code", source],
                out_dir, f"{stem}/codegen/c-{scalar}")
            run(pfgen, ["codegen", "--language", "rust", "--scalar", scalar, "-o", "code", source],
                out_dir, f"{stem}/codegen/rust-{scalar}")
        print(f"compare-outputs: {model}: {len(kinds)} kinds", file=sys.stderr)

    if options.skip_simulate:
        return
    for model, extra in SIMULATIONS:
        stem = model.replace("/", "_").removesuffix(".yaml")
        run(pfgen, ["simulate", str(ROOT / model), "--seed", "7", "--threads", "2", "-o", "series.csv",
                    "--stops-csv", "stops.csv", "-q"] + extra, out_dir, f"simulate/{stem}")
        print(f"compare-outputs: simulate {model}", file=sys.stderr)
    for index, command in enumerate(RECORDS):
        args = [str(ROOT / a) if a.startswith("examples/") else a for a in command]
        output = ["-o", "out.csv"] if command[0] == "estimate" else ["-o", "fit.json"]
        run(pfgen, args + output + ["-q"], out_dir, f"records/{index}-{command[0]}")
        print(f"compare-outputs: {command[0]} {command[1]}", file=sys.stderr)


if __name__ == "__main__":
    main()
