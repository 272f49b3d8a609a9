#!/usr/bin/env pvpython
"""Check that ParaView's three XDMF readers read kinetofem results files alike.

    pvpython scripts/check_xdmf_paraview.py [options] RESULT.xdmf [RESULT2.xdmf ...]

For every file and every reader -- "XDMFReader" (Xdmf2, the GUI's "XDMF Reader"),
"Xdmf3ReaderS" and "Xdmf3ReaderT" -- a child pvpython process opens the file,
updates the pipeline at the first, middle and last time step
(UpdatePipeline(t) with the time given: without one the Xdmf3 readers load every
step of a temporal collection at once) and reports per block the number of
points and cells and every point, cell and field array (components, tuples,
per-component range, a few sample tuples). Everything the reader prints
(warnings such as "Skipping unrecognized array type [None]", HDF5 or Xdmf errors,
crashes) is captured. The check fails if a reader prints anything, crashes, or
if the readers disagree on the time steps, the blocks, the point or cell counts,
the arrays or their values. A 9-component array in one reader and a
6-component one in another (Xdmf2 expands an XDMF Tensor6 to a full 3x3, the
Xdmf3 readers keep its 6 values) are compared as the same symmetric tensor
(XX, YY, ZZ, XY, YZ, XZ): the two libraries order a Tensor6 differently, which
shows here as a difference (kinetofem writes 6-component fields as Matrix).

Options:
  --expect FILE.json   also compare with expectations (written by the unit test
                       XdmfParaViewSample: times, blocks, counts, arrays, samples)
  --times N            the file must have N time steps
  --require-blocks A,B every reader must give these blocks (by the XDMF Reader's
                       names; the Xdmf3 readers name none, theirs are matched by
                       position) at every time step read, none of them empty
  --summary FILE.toml  compare what every reader shows at every time step read with
                       the run's own key results (kinetofem's .summary.toml): the
                       peak von Mises (max of von_mises_max over the per-link
                       blocks), each link's fatigue utilization, the assembly's
                       total deformation (no displacement above it), and mode
                       shapes that are not zero in the vibration blocks
  --screenshot PNG     render FIELD on the deformed bodies (Warp By Vector of
                       "displacement") at the last time step and save PNG; fails
                       if the picture shows (almost) nothing but background
  --field NAME         field of the screenshot (default von_mises)
  --screenshot-reader  reader for the screenshot (default Xdmf3ReaderT)
  --pvpython PATH      pvpython for the child processes (default: from PATH)
  --readers A,B,C      readers to run (default all three)
  -v                   print every block and array

Exit status 0 when everything agrees, 1 on a difference, 2 on bad usage.
The screenshot needs a display (run under `xvfb-run -a`); reading does not.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys

READERS = ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT")
RESULT_MARK = "@@KINETOFEM_XDMF_SUMMARY@@"
VOIGT_FROM_9 = (0, 4, 8, 1, 5, 2)  # xx yy zz xy yz xz in a row-major 3x3


# ----------------------------------------------------------------------------- child

def open_reader(name, path):
    from paraview import simple
    if name == "XDMFReader":
        return simple.XDMFReader(FileNames=[path])
    return getattr(simple, name)(FileName=[path])


def time_steps(reader):
    values = reader.TimestepValues
    if values is None:
        return []
    try:
        return [float(t) for t in values]
    except TypeError:
        return [float(values)]


def probe_indices(count):
    """The first, middle and last time step."""
    return sorted({0, (count - 1) // 2, count - 1}) if count else []


def sample_indices(tuples):
    if tuples == 0:
        return []
    return sorted({0, tuples // 3, (2 * tuples) // 3, tuples - 1})


def describe_array(array):
    tuples = array.GetNumberOfTuples()
    components = array.GetNumberOfComponents()
    entry = {"components": components, "tuples": tuples}
    if array.IsA("vtkDataArray"):
        entry["range"] = [list(array.GetRange(c)) for c in range(components)]
        entry["samples"] = {str(i): list(array.GetTuple(i)) for i in sample_indices(tuples)}
    return entry


def leaves(data, name=""):
    """(name, dataset) of every leaf, in order; the name from the block metadata."""
    if data is None:
        return
    if data.IsA("vtkDataObjectTree"):
        pieces = data.IsA("vtkMultiPieceDataSet")
        count = data.GetNumberOfPieces() if pieces else data.GetNumberOfBlocks()
        for i in range(count):
            child_name = ""
            if data.HasMetaData(i):
                meta = data.GetMetaData(i)
                if meta.Has(data.NAME()):
                    child_name = meta.Get(data.NAME())
            child = data.GetPiece(i) if pieces else data.GetBlock(i)
            yield from leaves(child, child_name)
        return
    yield name, data


def describe_output(data):
    blocks = []
    for name, block in leaves(data):
        entry = {"name": name, "class": block.GetClassName(),
                 "points": block.GetNumberOfPoints(), "cells": block.GetNumberOfCells(),
                 "arrays": {}}
        for label, attributes in (("point", block.GetPointData()), ("cell", block.GetCellData()),
                                  ("field", block.GetFieldData())):
            arrays = {}
            for i in range(attributes.GetNumberOfArrays()):
                array = attributes.GetAbstractArray(i)
                if array is None or not array.GetName():
                    continue
                if label == "field" and array.GetName().startswith("vtk"):
                    continue  # VTK's own bookkeeping arrays, if any
                arrays[array.GetName()] = describe_array(array)
            entry["arrays"][label] = arrays
        blocks.append(entry)
    return blocks


def child_main(reader_name, path):
    reader = open_reader(reader_name, path)
    times = time_steps(reader)
    steps = []
    for k in probe_indices(len(times)) if times else [None]:
        if k is None:
            reader.UpdatePipeline()
        else:
            reader.UpdatePipeline(times[k])
        data = reader.GetClientSideObject().GetOutputDataObject(0)
        steps.append({"index": k, "time": None if k is None else times[k],
                      "blocks": describe_output(data)})
    summary = {"reader": reader_name, "times": times, "steps": steps}
    sys.stdout.flush()
    # One line, marked, so the parent can tell it from whatever the reader printed.
    sys.stdout.write(RESULT_MARK + json.dumps(summary) + "\n")
    sys.stdout.flush()
    return 0


# ---------------------------------------------------------------------------- parent

def run_child(pvpython, reader_name, path, timeout):
    command = [pvpython, os.path.abspath(__file__), "--child", reader_name, path]
    try:
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, ["(timed out after %d s)" % timeout], "timeout"
    text = done.stdout.decode("utf-8", errors="replace")
    summary, noise = None, []
    for line in text.splitlines():
        if line.startswith(RESULT_MARK):
            summary = json.loads(line[len(RESULT_MARK):])
        elif line.strip():
            noise.append(line)
    status = "ok" if done.returncode == 0 else "exit status %d" % done.returncode
    return summary, noise, status


def close(a, b, tolerance=1e-12):
    if a is None or b is None:
        return a is b
    if isinstance(a, float) and isinstance(b, float) and (math.isnan(a) or math.isnan(b)):
        return math.isnan(a) and math.isnan(b)
    if isinstance(a, float) and isinstance(b, float) and (math.isinf(a) or math.isinf(b)):
        return a == b  # an infinite fatigue life read as the same infinity (inf - inf is nan)
    return abs(a - b) <= tolerance * max(1.0, abs(a), abs(b))


def as_voigt(entry):
    """A 9-component array (Xdmf2's Tensor6) as its 6 Voigt components."""
    out = dict(entry)
    out["components"] = 6
    if "range" in entry:
        out["range"] = [entry["range"][c] for c in VOIGT_FROM_9]
    if "samples" in entry:
        out["samples"] = {i: [t[c] for c in VOIGT_FROM_9] for i, t in entry["samples"].items()}
    return out


def symmetric_9(entry):
    for t in entry.get("samples", {}).values():
        if not (close(t[1], t[3]) and close(t[2], t[6]) and close(t[5], t[7])):
            return False
    return True


def compare_arrays(where, reference, other, problems):
    if reference["components"] == 6 and other["components"] == 9:
        if not symmetric_9(other):
            problems.append("%s: 9-component tensor is not symmetric" % where)
        other = as_voigt(other)
    elif reference["components"] == 9 and other["components"] == 6:
        if not symmetric_9(reference):
            problems.append("%s: 9-component tensor is not symmetric" % where)
        reference = as_voigt(reference)
    for key in ("components", "tuples"):
        if reference[key] != other[key]:
            problems.append("%s: %s %s vs %s" % (where, key, reference[key], other[key]))
            return
    for c, (r, o) in enumerate(zip(reference.get("range", []), other.get("range", []))):
        if not (close(r[0], o[0]) and close(r[1], o[1])):
            problems.append("%s: range of component %d %s vs %s" % (where, c, r, o))
    for i, r in reference.get("samples", {}).items():
        o = other.get("samples", {}).get(i)
        if o is None or len(o) != len(r) or not all(close(x, y) for x, y in zip(r, o)):
            problems.append("%s: tuple %s %s vs %s" % (where, i, r, o))


def compare_summaries(reference, other, problems):
    tag = "%s vs %s" % (reference["reader"], other["reader"])
    if len(reference["times"]) != len(other["times"]) or not all(
            close(a, b) for a, b in zip(reference["times"], other["times"])):
        problems.append("%s: time steps %s vs %s" % (tag, reference["times"], other["times"]))
        return
    for rs, os_ in zip(reference["steps"], other["steps"]):
        at = "%s, t = %s" % (tag, rs["time"])
        rb, ob = rs["blocks"], os_["blocks"]
        if len(rb) != len(ob):
            problems.append("%s: %d blocks vs %d" % (at, len(rb), len(ob)))
            continue
        for i, (r, o) in enumerate(zip(rb, ob)):
            where = "%s, block %d (%s)" % (at, i, r["name"] or o["name"] or "unnamed")
            if r["name"] and o["name"] and r["name"] != o["name"]:
                problems.append("%s: name %r vs %r" % (where, r["name"], o["name"]))
            for key in ("points", "cells"):
                if r[key] != o[key]:
                    problems.append("%s: %s %d vs %d" % (where, key, r[key], o[key]))
            for label in ("point", "cell", "field"):
                ra, oa = r["arrays"].get(label, {}), o["arrays"].get(label, {})
                if set(ra) != set(oa):
                    problems.append("%s: %s arrays differ: only in %s %s, only in %s %s" % (
                        where, label, reference["reader"], sorted(set(ra) - set(oa)),
                        other["reader"], sorted(set(oa) - set(ra))))
                for name in sorted(set(ra) & set(oa)):
                    compare_arrays("%s %s array %s" % (where, label, name), ra[name], oa[name],
                                   problems)


def compare_expectation(summary, expect, problems):
    tag = summary["reader"]
    times = expect.get("times", [])
    if len(times) != len(summary["times"]) or not all(
            close(a, b) for a, b in zip(times, summary["times"])):
        problems.append("%s: time steps %s, expected %s" % (tag, summary["times"], times))
        return
    for step in summary["steps"]:
        at = "%s, t = %s" % (tag, step["time"])
        k = step["index"]
        blocks = step["blocks"]
        expected = expect["blocks"]
        if len(blocks) != len(expected):
            problems.append("%s: %d blocks, expected %d (%s)" % (
                at, len(blocks), len(expected), [b["name"] for b in expected]))
            continue
        total = sum(b["points"] for b in blocks)
        if "total_points" in expect and total != expect["total_points"]:
            problems.append("%s: %d points in all, expected %d" % (at, total, expect["total_points"]))
        for block, want in zip(blocks, expected):
            where = "%s, block %s" % (at, want["name"])
            if block["name"] and block["name"] != want["name"]:
                problems.append("%s: named %r" % (where, block["name"]))
            for key in ("points", "cells"):
                if block[key] != want[key]:
                    problems.append("%s: %s %d, expected %d" % (where, key, block[key], want[key]))
            for label in ("point", "cell", "field"):
                have = block["arrays"].get(label, {})
                want_arrays = want.get("arrays", {}).get(label, {})
                if set(have) != set(want_arrays):
                    problems.append("%s: %s arrays %s, expected %s" % (
                        where, label, sorted(have), sorted(want_arrays)))
                for name in sorted(set(have) & set(want_arrays)):
                    w = want_arrays[name]
                    h = have[name]
                    if h["components"] == 9 and w["components"] == 6:
                        h = as_voigt(h)
                    if h["components"] != w["components"] or h["tuples"] != w["tuples"]:
                        problems.append("%s: %s array %s is %d x %d, expected %d x %d" % (
                            where, label, name, h["tuples"], h["components"], w["tuples"],
                            w["components"]))
                        continue
                    # Expected values: {"samples": {tuple: values}} or, per time step,
                    # {"steps": {k: {tuple: values}}}.
                    samples = dict(w.get("samples", {}))
                    if k is not None:
                        samples.update(w.get("steps", {}).get(str(k), {}))
                    for i, values in samples.items():
                        got = h.get("samples", {}).get(i)
                        if got is None:
                            idx = int(i)
                            problems.append("%s: %s array %s tuple %d not sampled" % (
                                where, label, name, idx))
                            continue
                        if not all(close(a, b) for a, b in zip(got, values)):
                            problems.append("%s: %s array %s tuple %s = %s, expected %s" % (
                                where, label, name, i, got, values))


def block_index(reference, name):
    """Index of block NAME in the XDMF Reader's (named) output, or None."""
    for step in reference["steps"]:
        for i, block in enumerate(step["blocks"]):
            if block["name"] == name:
                return i
    return None


def array_range(block, label, name):
    entry = block["arrays"].get(label, {}).get(name)
    if entry is None or "range" not in entry:
        return None
    return entry["range"]


def largest(values):
    return max(values) if values else None


def check_requirements(summaries, blocks, times, run_summary, problems):
    """--times, --require-blocks and --summary, in every reader's output."""
    if not summaries:
        return
    reference = next((s for s in summaries if s["reader"] == "XDMFReader"), None)
    for summary in summaries:
        tag = summary["reader"]
        if times is not None and len(summary["times"]) != times:
            problems.append("%s: %d time steps, expected %d" % (tag, len(summary["times"]), times))
        count = len(summary["times"])
        wanted = probe_indices(count)
        read = [step["index"] for step in summary["steps"]]
        if count and read != wanted:
            problems.append("%s: read the time steps %s, expected the first, middle and last %s" % (
                tag, read, wanted))
    if reference is None:
        if blocks or run_summary:
            problems.append("the block checks need the XDMF Reader (it names the blocks)")
        return
    index = {}
    for name in blocks:
        i = block_index(reference, name)
        if i is None:
            problems.append("XDMFReader: no block %r (blocks: %s)" % (
                name, [b["name"] for b in reference["steps"][0]["blocks"]] if reference["steps"] else []))
        else:
            index[name] = i
    for summary in summaries:
        for step in summary["steps"]:
            at = "%s, t = %s" % (summary["reader"], step["time"])
            for name, i in index.items():
                if i >= len(step["blocks"]) or step["blocks"][i]["points"] == 0:
                    problems.append("%s: block %s missing or empty" % (at, name))
    if not run_summary:
        return
    links = [n for n in index if "." not in n and n != "mechanism"]
    assembly = [n for n in index if n.startswith("assembly.")]
    vibration = [n for n in index if n.startswith("vibration.")]
    peak = run_summary.get("max_von_mises_mpa")
    total = run_summary.get("total_deformation_mm")
    for summary in summaries:
        for step in summary["steps"]:
            at = "%s, t = %s" % (summary["reader"], step["time"])
            b = step["blocks"]
            if any(index[n] >= len(b) for n in index):
                continue  # reported above
            if peak is not None and links:
                ranges = [array_range(b[index[n]], "point", "von_mises_max") for n in links]
                if None in ranges:
                    problems.append("%s: a per-link block without von_mises_max" % at)
                elif not close(largest([r[0][1] for r in ranges]), peak * 1e6, 1e-9):
                    problems.append("%s: largest von_mises_max %.9g Pa, the run's peak %.9g Pa" % (
                        at, largest([r[0][1] for r in ranges]), peak * 1e6))
            for n in links:
                want = run_summary.get("fatigue_utilization_" + n)
                if want is None:
                    continue
                r = array_range(b[index[n]], "point", "fatigue_utilization")
                if r is None or not close(r[0][1], want, 1e-9):
                    problems.append("%s: block %s fatigue_utilization up to %s, the run's %.9g" % (
                        at, n, r[0][1] if r else None, want))
            if total is not None and assembly:
                ranges = [array_range(b[index[n]], "point", "displacement_magnitude") for n in assembly]
                if None in ranges:
                    problems.append("%s: an assembly block without displacement_magnitude" % at)
                else:
                    top = largest([r[0][1] for r in ranges])
                    if not (0.0 < top <= total * 1e-3 * (1 + 1e-9)):
                        problems.append("%s: assembly displacement up to %.9g m, the run's total "
                                        "deformation %.9g m" % (at, top, total * 1e-3))
            for n in vibration:
                r = array_range(b[index[n]], "point", "mode_1_magnitude")
                if r is None or not r[0][1] > 0.0:
                    problems.append("%s: block %s: mode_1_magnitude %s, expected a mode shape" % (
                        at, n, r[0] if r else None))


def print_summary(summary, verbose):
    print("  %-13s %d time steps%s" % (summary["reader"], len(summary["times"]),
                                      (" (%g .. %g s)" % (summary["times"][0], summary["times"][-1]))
                                      if summary["times"] else ""))
    for step in summary["steps"]:
        blocks = step["blocks"]
        points = sum(b["points"] for b in blocks)
        cells = sum(b["cells"] for b in blocks)
        label = "t = %g s" % step["time"] if step["time"] is not None else "no time"
        print("    %-14s %8d points %8d cells in %d blocks: %s" % (
            label, points, cells, len(blocks),
            ", ".join("%s %d/%d" % (b["name"] or "#%d" % i, b["points"], b["cells"])
                      for i, b in enumerate(blocks))))
        if verbose:
            for b in blocks:
                for label_, arrays in b["arrays"].items():
                    if arrays:
                        print("      %s %s: %s" % (b["name"] or "-", label_, ", ".join(
                            "%s(%d)" % (n, a["components"]) for n, a in arrays.items())))


def screenshot(path, png, field, reader_name):
    from paraview import simple
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = open_reader(reader_name, path)
    times = time_steps(reader)
    view = simple.CreateView("RenderView")
    view.ViewSize = [1200, 800]
    view.Background = [1.0, 1.0, 1.0]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.OrientationAxesVisibility = 0
    scene = simple.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    if times:
        scene.AnimationTime = times[-1]
        view.ViewTime = times[-1]
    reader.UpdatePipeline(times[-1] if times else 0.0)
    source = reader
    info = reader.GetPointDataInformation()
    if info.GetArray("displacement") is not None:
        # Scale the largest displacement to ~5 % of the model size.
        bounds = reader.GetDataInformation().GetBounds()
        size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
        largest = info.GetArray("displacement").GetRange(-1)[1]
        scale = 0.05 * size / largest if largest > 0 else 1.0
        source = simple.WarpByVector(Input=reader, Vectors=["POINTS", "displacement"],
                                     ScaleFactor=scale)
        print("  warp: displacement x %.3g (largest %.3g m, model %.3g m)" % (scale, largest, size))
    display = simple.Show(source, view)
    simple.ColorBy(display, ("POINTS", field))
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    bar = simple.GetScalarBar(simple.GetColorTransferFunction(field), view)
    bar.Title = field
    bar.ComponentTitle = ""
    bar.TitleColor = [0.0, 0.0, 0.0]
    bar.LabelColor = [0.0, 0.0, 0.0]
    view.ResetCamera()
    simple.Render(view)
    simple.SaveScreenshot(png, view, ImageResolution=[1200, 800])
    image = vtkPNGReader()
    image.SetFileName(png)
    image.Update()
    pixels = image.GetOutput().GetPointData().GetScalars()
    n = pixels.GetNumberOfTuples()
    coloured = 0
    for i in range(0, n, 7):
        r, g, b = pixels.GetTuple(i)[:3]
        if not (r > 250 and g > 250 and b > 250):
            coloured += 1
    share = coloured / max(1, len(range(0, n, 7)))
    print("  screenshot %s: %s at t = %s s, %.1f %% of the pixels not background" % (
        png, field, times[-1] if times else "-", 100 * share))
    return share


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("files", nargs="*")
    parser.add_argument("--child", nargs=2, metavar=("READER", "FILE"), help=argparse.SUPPRESS)
    parser.add_argument("--expect")
    parser.add_argument("--times", type=int)
    parser.add_argument("--require-blocks", default="")
    parser.add_argument("--summary")
    parser.add_argument("--screenshot")
    parser.add_argument("--field", default="von_mises")
    parser.add_argument("--screenshot-reader", default="Xdmf3ReaderT")
    parser.add_argument("--pvpython", default=os.environ.get("PVPYTHON") or shutil.which("pvpython"))
    parser.add_argument("--readers", default=",".join(READERS))
    parser.add_argument("--timeout", type=int, default=300)
    parser.add_argument("-v", "--verbose", action="store_true")
    args = parser.parse_args()
    if args.child:
        return child_main(args.child[0], args.child[1])
    if not args.files:
        parser.print_usage()
        return 2
    if not args.pvpython:
        print("check_xdmf_paraview: pvpython not found (give --pvpython)")
        return 2
    readers = [r for r in args.readers.split(",") if r]
    for r in readers:
        if r not in READERS:
            print("check_xdmf_paraview: unknown reader %r (%s)" % (r, ", ".join(READERS)))
            return 2
    expect = None
    if args.expect:
        with open(args.expect) as f:
            expect = json.load(f)
    run_summary = None
    if args.summary:
        import tomllib
        with open(args.summary, "rb") as f:
            run_summary = tomllib.load(f)
    blocks = [b for b in args.require_blocks.split(",") if b]
    failed = False
    for path in args.files:
        path = os.path.abspath(path)  # Xdmf3 resolves the .h5 against the path as given
        print("%s" % path)
        problems, summaries = [], []
        for reader_name in readers:
            summary, noise, status = run_child(args.pvpython, reader_name, path, args.timeout)
            if status != "ok" or summary is None:
                problems.append("%s: %s%s" % (reader_name, status,
                                               "" if summary else ", no summary"))
            if noise:
                problems.append("%s printed %d lines, e.g.:\n      %s" % (
                    reader_name, len(noise), "\n      ".join(noise[:8])))
            if summary:
                print_summary(summary, args.verbose)
                summaries.append(summary)
                if expect:
                    compare_expectation(summary, expect, problems)
        for other in summaries[1:]:
            compare_summaries(summaries[0], other, problems)
        check_requirements(summaries, blocks, args.times, run_summary, problems)
        if problems:
            failed = True
            print("  FAIL (%d):" % len(problems))
            for p in problems[:60]:
                print("    " + p)
            if len(problems) > 60:
                print("    ... and %d more" % (len(problems) - 60))
        else:
            print("  OK: %s agree, no warnings%s%s%s" % (
                ", ".join(readers), ", as expected" if expect else "",
                ", every required block (%s)" % ", ".join(blocks) if blocks else "",
                ", the run's peak von Mises, fatigue utilizations and total deformation"
                if run_summary else ""))
    if args.screenshot:
        share = screenshot(os.path.abspath(args.files[-1]), args.screenshot, args.field,
                           args.screenshot_reader)
        if share < 0.01:
            print("  FAIL: the screenshot is (almost) empty")
            failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    status = main()
    sys.stdout.flush()
    sys.stderr.flush()
    # Leave without tearing ParaView down: under Xvfb its OpenGL context can fail on
    # exit (GLXBadContext) after the screenshot is saved, which would mask the status.
    os._exit(status)
