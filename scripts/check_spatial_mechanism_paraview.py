#!/usr/bin/env pvpython
"""Check that ParaView shows a spatial mechanism's skeleton where the run put it.

    pvpython scripts/check_spatial_mechanism_paraview.py [options] RESULT.xdmf

The results file of a spatial mechanism (pipeline/spatial_histories.hpp) has a
moving body "skeleton.<b>" per rigid body: its nodes' world coordinates at each
output time are the geometry of that time. For every reader -- "XDMFReader"
(Xdmf2, the GUI's "XDMF Reader"), "Xdmf3ReaderS" and "Xdmf3ReaderT" -- a child
pvpython process opens the file, updates the pipeline at each requested time
(UpdatePipeline(t), t an output time), and reports for the skeleton block of
BODY the node farthest along the body's own x axis (largest body_position x:
the arm's tip M of the SPEC 5 manipulator, whose arm spans x in [0, L]), its
body-frame and world coordinates, and the mechanism block's field data rows of
that time. The check fails unless, at every requested time and in every reader,
  - the data's time is the requested one;
  - the tip's world position equals origin + R x_body from the run's histories
    body.<b>.origin and body.<b>.rotation at that time (the frame's pose), to
    --tolerance (relative to the body's length);
  - with --expect-history NAME (a (T, 3) history in m, e.g. the closed form's
    planned gripper point "M.position"), the tip equals that history's row too;
  - the readers agree, and none prints anything (a warning, an error);
  - and with two or more times, the tip moved between the first and the last.
With --screenshot PREFIX (needs a display: run under `xvfb-run -a`), it also
saves PREFIX_t<time>.png at each requested time: every skeleton block coloured
by velocity_magnitude, the same camera for all times, and fails if a picture
is (almost) all background.

Options:
  --times T1,T2,...     output times to check (s; the nearest output time is
                        used and printed); default: the first, middle and last
  --body NAME           the rigid body (default arm): block "skeleton.NAME"
  --expect-history NAME a 3-component history in m that the tip must follow
  --tolerance X         relative tolerance (default 1e-12)
  --screenshot PREFIX   save the pictures (see above)
  --pvpython PATH       pvpython for the child processes (default: from PATH)

Exit status 0 when everything agrees, 1 on a difference, 2 on bad usage.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys

READERS = ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT")
RESULT_MARK = "@@KINETOFEM_SPATIAL_CHECK@@"
SKELETON_PREFIX = "skeleton."  # post::layout::kSkeletonBodyPrefix
BODY_POSITION = "body_position"  # post::layout::kBodyPosition
SPEED = "velocity_magnitude"  # magnitude_name(post::layout::kVelocity)


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


def leaves(data, name=""):
    """(name, dataset) of every leaf in order; names from the block metadata (Xdmf2 only)."""
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


def field_rows(block, index):
    """Row `index` of every field array of a block (the mechanism histories)."""
    out = {}
    fd = block.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetArray(i)
        if a is None or not a.GetName() or index >= a.GetNumberOfTuples():
            continue
        out[a.GetName()] = list(a.GetTuple(index))
    return out


def child_main(reader_name, path, times_wanted, block_index):
    reader = open_reader(reader_name, path)
    times = time_steps(reader)
    probes = []
    for t in times_wanted:
        k = min(range(len(times)), key=lambda i: abs(times[i] - t))
        reader.UpdatePipeline(times[k])
        data = reader.GetClientSideObject().GetOutputDataObject(0)
        blocks = list(leaves(data))
        entry = {"index": k, "time": times[k], "names": [n for n, _ in blocks]}
        info = data.GetInformation()
        from vtkmodules.vtkCommonDataModel import vtkDataObject
        entry["data_time"] = info.Get(vtkDataObject.DATA_TIME_STEP()) if info.Has(vtkDataObject.DATA_TIME_STEP()) else None
        if block_index is not None and block_index < len(blocks):
            _, skeleton = blocks[block_index]
            local = skeleton.GetPointData().GetArray(BODY_POSITION)
            if local is not None:
                tip = max(range(local.GetNumberOfTuples()), key=lambda n: local.GetTuple(n)[0])
                entry["tip_node"] = tip
                entry["tip_body"] = list(local.GetTuple(tip))
                entry["tip_world"] = list(skeleton.GetPoint(tip))
                entry["points"] = skeleton.GetNumberOfPoints()
        # The mechanism block: the one with field data (its histories, one row per time).
        for _, block in blocks:
            rows = field_rows(block, k)
            if rows:
                entry["fields"] = rows
                break
        probes.append(entry)
    sys.stdout.flush()
    sys.stdout.write(RESULT_MARK + json.dumps({"reader": reader_name, "times": times, "probes": probes}) + "\n")
    sys.stdout.flush()
    return 0


def run_child(pvpython, reader_name, path, times, block_index, timeout=300):
    command = [pvpython, os.path.abspath(__file__), "--child", reader_name, path,
               "--times", ",".join(repr(t) for t in times),
               "--block-index", str(-1 if block_index is None else block_index)]
    try:
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, ["(timed out after %d s)" % timeout]
    summary, noise = None, []
    for line in done.stdout.decode("utf-8", errors="replace").splitlines():
        if line.startswith(RESULT_MARK):
            summary = json.loads(line[len(RESULT_MARK):])
        elif line.strip():
            noise.append(line)
    if done.returncode != 0:
        noise.append("(exit status %d)" % done.returncode)
    return summary, noise


def distance(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def frame_point(fields, body, local):
    """origin + R x_body from the histories body.<b>.origin and body.<b>.rotation (row by row)."""
    o = fields.get("body.%s.origin" % body)
    r = fields.get("body.%s.rotation" % body)
    if o is None or r is None or len(r) != 9:
        return None
    return [o[i] + sum(r[3 * i + j] * local[j] for j in range(3)) for i in range(3)]


def screenshots(path, prefix, times):
    from paraview import simple
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = open_reader("Xdmf3ReaderT", path)
    steps = time_steps(reader)
    view = simple.CreateView("RenderView")
    view.ViewSize = [1200, 800]
    view.Background = [1.0, 1.0, 1.0]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    display = simple.Show(reader, view)
    simple.ColorBy(display, ("POINTS", SPEED))
    lut = simple.GetColorTransferFunction(SPEED)
    display.SetScalarBarVisibility(view, True)
    bar = simple.GetScalarBar(lut, view)
    bar.Title = "speed [m/s]"
    bar.ComponentTitle = ""
    bar.TitleColor = [0.0, 0.0, 0.0]
    bar.LabelColor = [0.0, 0.0, 0.0]
    # One camera for all times, framing the union of the poses: the motion shows as a change.
    bounds = [math.inf, -math.inf] * 3
    top = 0.0
    for t in steps:
        reader.UpdatePipeline(t)
        b = reader.GetDataInformation().GetBounds()
        for i in range(3):
            bounds[2 * i] = min(bounds[2 * i], b[2 * i])
            bounds[2 * i + 1] = max(bounds[2 * i + 1], b[2 * i + 1])
        r = reader.GetPointDataInformation().GetArray(SPEED)
        if r is not None:
            top = max(top, r.GetRange(0)[1])
    lut.RescaleTransferFunction(0.0, top if top > 0 else 1.0)
    simple.Render(view)  # the first render resets the camera: set ours after it
    centre = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
    size = max(bounds[2 * i + 1] - bounds[2 * i] for i in range(3))
    view.CameraFocalPoint = centre
    # From above, in front of the +x, -y quadrant: about 1.9 sizes away fills a 30 deg view.
    look = [1.0, -1.2, 0.8]
    norm = math.sqrt(sum(c * c for c in look))
    view.CameraPosition = [centre[i] + 1.9 * size * look[i] / norm for i in range(3)]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraParallelProjection = 0
    shares = []
    for t in times:
        k = min(range(len(steps)), key=lambda i: abs(steps[i] - t))
        view.ViewTime = steps[k]
        reader.UpdatePipeline(steps[k])
        simple.Render(view)
        png = "%s_t%.4f.png" % (prefix, steps[k])
        simple.SaveScreenshot(png, view, ImageResolution=[1200, 800])
        image = vtkPNGReader()
        image.SetFileName(png)
        image.Update()
        pixels = image.GetOutput().GetPointData().GetScalars()
        n = pixels.GetNumberOfTuples()
        coloured = sum(1 for i in range(0, n, 7) if not all(c > 250 for c in pixels.GetTuple(i)[:3]))
        share = coloured / max(1, len(range(0, n, 7)))
        print("  screenshot %s: skeletons at t = %.6g s coloured by %s (0 .. %.4g m/s), %.1f %% not background" % (
            png, steps[k], SPEED, top, 100 * share))
        shares.append(share)
    return shares


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("files", nargs="*")
    parser.add_argument("--child", nargs=2, metavar=("READER", "FILE"), help=argparse.SUPPRESS)
    parser.add_argument("--block-index", type=int, default=-1, help=argparse.SUPPRESS)
    parser.add_argument("--times", default="")
    parser.add_argument("--body", default="arm")
    parser.add_argument("--expect-history", default="")
    parser.add_argument("--tolerance", type=float, default=1e-12)
    parser.add_argument("--screenshot")
    parser.add_argument("--pvpython", default=os.environ.get("PVPYTHON") or shutil.which("pvpython"))
    args = parser.parse_args()
    wanted = [float(t) for t in args.times.split(",") if t]
    if args.child:
        return child_main(args.child[0], args.child[1], wanted, None if args.block_index < 0 else args.block_index)
    if len(args.files) != 1:
        parser.print_usage()
        return 2
    if not args.pvpython:
        print("check_spatial_mechanism_paraview: pvpython not found (give --pvpython)")
        return 2
    path = os.path.abspath(args.files[0])  # Xdmf3 resolves the .h5 against the path as given
    block = SKELETON_PREFIX + args.body
    print(path)
    problems = []
    # The XDMF Reader names the blocks; the Xdmf3 readers do not, so its order finds the block.
    probe, noise = run_child(args.pvpython, "XDMFReader", path, wanted or [0.0], None)
    if probe is None:
        print("  FAIL: the XDMF Reader read nothing:\n    " + "\n    ".join(noise[:8]))
        return 1
    names = probe["probes"][0]["names"]
    if block not in names:
        print("  FAIL: no block %r (blocks: %s)" % (block, names))
        return 1
    index = names.index(block)
    times = probe["times"]
    if not wanted:
        wanted = sorted({times[0], times[(len(times) - 1) // 2], times[-1]})
    summaries = []
    for reader in READERS:
        summary, noise = run_child(args.pvpython, reader, path, wanted, index)
        if noise:
            problems.append("%s printed %d lines, e.g.:\n      %s" % (reader, len(noise), "\n      ".join(noise[:8])))
        if summary is None:
            problems.append("%s: no result" % reader)
            continue
        summaries.append(summary)
        for p in summary["probes"]:
            at = "%s, t = %.6g s" % (reader, p["time"])
            if "tip_world" not in p:
                problems.append("%s: block %d (%s) has no %s" % (at, index, block, BODY_POSITION))
                continue
            length = max(1e-300, math.sqrt(sum(x * x for x in p["tip_body"])))
            if p["data_time"] is not None and abs(p["data_time"] - p["time"]) > 1e-12 * max(1.0, abs(p["time"])):
                problems.append("%s: the data is of t = %r" % (at, p["data_time"]))
            fields = p.get("fields", {})
            expected = frame_point(fields, args.body, p["tip_body"])
            if expected is None:
                problems.append("%s: no histories body.%s.origin / rotation in the field data" % (at, args.body))
            else:
                d = distance(p["tip_world"], expected)
                p["frame_error"] = d / length
                if d > args.tolerance * length:
                    problems.append("%s: tip %s, the frame's %s (|d| = %.3g m)" % (at, p["tip_world"], expected, d))
            if args.expect_history:
                h = fields.get(args.expect_history)
                if h is None or len(h) != 3:
                    problems.append("%s: no 3-component history %r in the field data" % (at, args.expect_history))
                else:
                    d = distance(p["tip_world"], h)
                    p["history_error"] = d / length
                    if d > args.tolerance * length:
                        problems.append("%s: tip %s, %s = %s (|d| = %.3g m)" % (at, p["tip_world"], args.expect_history, h, d))
            print("  %-13s t = %-9.6g tip node %d (x_body %.6g m) at (%.9f, %.9f, %.9f) m; vs frame %.2e, vs %s %s" % (
                reader, p["time"], p["tip_node"], p["tip_body"][0], *p["tip_world"], p.get("frame_error", math.nan),
                args.expect_history or "-", "%.2e" % p["history_error"] if "history_error" in p else "-"))
    for other in summaries[1:]:
        for a, b in zip(summaries[0]["probes"], other["probes"]):
            if "tip_world" in a and "tip_world" in b and distance(a["tip_world"], b["tip_world"]) > 1e-12 * max(
                    1.0, max(abs(x) for x in a["tip_world"])):
                problems.append("%s vs %s at t = %.6g: tip %s vs %s" % (
                    summaries[0]["reader"], other["reader"], a["time"], a["tip_world"], b["tip_world"]))
    if summaries and len(wanted) > 1:
        first, last = summaries[0]["probes"][0], summaries[0]["probes"][-1]
        if "tip_world" in first and "tip_world" in last:
            moved = distance(first["tip_world"], last["tip_world"])
            print("  the tip moved %.6g m from t = %.6g to %.6g s" % (moved, first["time"], last["time"]))
            if moved <= 0.0:
                problems.append("the tip did not move from t = %g to %g s" % (first["time"], last["time"]))
    if args.screenshot:
        for share in screenshots(path, args.screenshot, wanted):
            if share < 0.005:
                problems.append("a screenshot is (almost) empty")
    if problems:
        print("  FAIL (%d):" % len(problems))
        for p in problems[:40]:
            print("    " + p)
        return 1
    print("  OK: %s show %s's tip at the frame's pose%s at %d times, no warnings" % (
        ", ".join(READERS), block, " and at " + args.expect_history if args.expect_history else "", len(wanted)))
    return 0


if __name__ == "__main__":
    status = main()
    sys.stdout.flush()
    sys.stderr.flush()
    # Leave without tearing ParaView down: under Xvfb its OpenGL context can fail on exit.
    os._exit(status)
