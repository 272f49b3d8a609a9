#!/usr/bin/env python3
"""Tabulates the band's runs: the elastic assembly's peak von Mises (which part, where) and the
total deformation and H's deflection, static study and over the motion.

    python3 cases/sensitivity/as_built_band/tabulate.py RESULTS_DIR [KINETOFEM]

RESULTS_DIR is the batch's output folder; with KINETOFEM (the program), the peaks' places are
read from each results file by `kinetofem post`.
"""
import pathlib
import re
import subprocess
import sys
import tomllib

ASSEMBLY_PART = re.compile(r"^\s{4}(\w+)\s+max von Mises ([\d.]+) MPa over the motion, ([\d.]+) MPa static")
POST_STATIC = re.compile(r"^\s+assembly\.(\w+) static_von_mises\s+([\d.]+) MPa\s+static\s+node \d+ \(([^)]*)\) mm")


def peaks(log_text):
    parts = {}
    for line in log_text.splitlines():
        m = ASSEMBLY_PART.match(line)
        if m:
            parts[m.group(1)] = (float(m.group(2)), float(m.group(3)))
    return parts


def static_places(program, results):
    out = subprocess.run([program, "post", str(results)], capture_output=True, text=True).stdout
    return {m.group(1): m.group(3) for m in map(POST_STATIC.match, out.splitlines()) if m}


def main():
    folder = pathlib.Path(sys.argv[1])
    program = sys.argv[2] if len(sys.argv) > 2 else None
    print("| run | static peak vM [MPa] (part, place mm) | peak vM over the motion [MPa] (part) "
          "| static total deformation [mm] | H static [mm] | H max over the motion [mm] |")
    print("|---|---|---|---:|---:|---:|")
    for summary in sorted(folder.glob("*.summary.toml")):
        s = tomllib.loads(summary.read_text())
        name = s["name"]
        p = peaks((folder / f"{name}.log").read_text())
        if not p:
            continue
        static_part = max(p, key=lambda k: p[k][1])
        motion_part = max(p, key=lambda k: p[k][0])
        place = ""
        if program:
            place = ", " + static_places(program, s["results_file"]).get(static_part, "?")
        print(f"| {name.removeprefix('band_')} | {p[static_part][1]:.1f} ({static_part}{place}) "
              f"| {p[motion_part][0]:.1f} ({motion_part}) | {s['static_total_deformation_mm']:.3f} "
              f"| {s['static_deflection_H_mm']:.3f} | {s['max_deflection_H_mm']:.3f} |")


if __name__ == "__main__":
    main()
