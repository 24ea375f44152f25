#!/usr/bin/env python3
"""Tests of the Python package afv (python/afv/); ends "N passed, M failed".

    python3 python/test_afv.py --driver python/check_driver --afv ./afv
        [--module-dir DIR] [--no-numpy]

--driver: python/check_driver (make python-test builds it), the same
scenario through the C library, printed in %.17g: every number of the
module must be its number bit for bit, and every picture its bytes.
--afv: the program, whose `afv eval` must agree with afv.compute and whose
--version with afv.__version__.  --module-dir: import afv from there (an
installed module) instead of this file's directory; --installed: import
the afv that Python finds outside the build tree (pip install ./python),
which must load the libafv.so it carries.  --no-numpy: hide
numpy, so the module runs on lists alone (as without numpy installed).
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

args = argparse.ArgumentParser()
args.add_argument("--driver", required=True)
args.add_argument("--afv", required=True)
args.add_argument("--module-dir")
args.add_argument("--installed", action="store_true")
args.add_argument("--no-numpy", action="store_true")
args = args.parse_args()

if args.no_numpy:
    sys.modules["numpy"] = None      # import numpy now raises ImportError
here = os.path.dirname(os.path.abspath(__file__))
if args.installed:                   # not the build tree's python/afv/
    sys.path = [p for p in sys.path if os.path.abspath(p or ".") != here]
    module_dir = None
else:
    module_dir = os.path.abspath(args.module_dir or here)
    sys.path.insert(0, module_dir)
import afv  # noqa: E402

try:
    import numpy as np
except ImportError:
    np = None

TESTS = []


def test(fn):
    TESTS.append(fn)
    return fn


def fail(msg):
    raise AssertionError(msg)


def flat(values):
    """Nested lists or an array as a flat list of Python numbers."""
    if np is not None and isinstance(values, np.ndarray):
        return values.reshape(-1).tolist()
    out = []
    for v in values:
        nested = isinstance(v, (list, tuple)) or \
            (np is not None and isinstance(v, np.ndarray))
        out.extend(flat(v) if nested else [v])
    return out


def same_bits(name, mine, theirs):
    """Every value equal as a double (NaN equal to NaN)."""
    mine = flat(mine) if isinstance(mine, (list, tuple)) or \
        (np is not None and isinstance(mine, np.ndarray)) else [mine]
    if len(mine) != len(theirs):
        fail("%s: %d values, the C library %d" % (name, len(mine),
                                                  len(theirs)))
    for k, (a, b) in enumerate(zip(mine, theirs)):
        if not (a == b or (math.isnan(a) and math.isnan(b))):
            fail("%s[%d]: module %r, C library %r" % (name, k, a, b))


# ---- the C side --------------------------------------------------------------
tmp = tempfile.mkdtemp(prefix="afv_pytest_")
out = subprocess.run([args.driver, tmp], check=True, capture_output=True,
                     text=True).stdout
C = {}
for line in out.splitlines():
    name, _, value = line.split()
    C.setdefault(name, []).append(float(value))


def read(path):
    with open(path, "rb") as fp:
        return fp.read()


# ---- the same scenarios through the module (check_driver.c's header) ------
def open_scenario():
    r = afv.init_lattice(37, 1.1)
    p = afv.Params(Lambda=0.3, P0=[5.5 if i % 2 else 4.5 for i in range(37)])
    return r, p


def sim_scenario():
    box = (12, 12)
    r = afv.init_cluster(40, 7, box, 3.6)
    sim = afv.Simulation(r, afv.init_angles(40, 7), box=box, seed=11)
    rep = sim.relax(1e-4, 3000)
    sim.set(v0=0.5)
    sim.step(30)
    sim.set(v0=[0.2 + 0.05 * i for i in range(40)])
    sim.step(20)
    sim.set_params(P0=5.5)
    sim.step(20)
    sim.set(dt=0.005)
    sim.step(20)
    return sim, rep


def same_order(prefix, o):
    """o (order_parameters) against the driver's PREFIX.order, .label."""
    same_bits(prefix + ".order", [o["giant_fraction"], o["omega"],
                                  o["clusters"], o["pairs"], o["junctions"]],
              C[prefix + ".order"])
    same_bits(prefix + ".labels", o["labels"], C[prefix + ".label"])


@test
def open_space_is_the_c_librarys():
    r, p = open_scenario()
    g = afv.compute(r, p)
    for name in ("area", "perimeter", "arc", "contacts", "forces", "energy"):
        same_bits(name, getattr(g, name), C["open." + name])
    same_order("open", afv.order_parameters(r, p))


@test
def simulation_is_the_c_librarys():
    sim, rep = sim_scenario()
    same_bits("relax", [rep["iterations"], rep["energy"]], C["sim.relax"])
    for name in ("positions", "angles", "forces", "energy", "time", "steps"):
        same_bits(name, getattr(sim, name), C["sim." + name])
    same_order("sim", sim.order_parameters())


@test
def pictures_are_the_c_librarys():
    r, p = open_scenario()
    path = os.path.join(tmp, "open_py.svg")
    afv.draw(path, r, params=p)
    if read(path) != read(os.path.join(tmp, "open.svg")):
        fail("afv.draw differs from afv_svg_write (open.svg)")
    sim, _ = sim_scenario()
    sim.draw(os.path.join(tmp, "sim_py.svg"))
    if read(os.path.join(tmp, "sim_py.svg")) != \
            read(os.path.join(tmp, "sim.svg")):
        fail("Simulation.draw differs from afv_svg_write (sim.svg)")
    if os.path.exists(path + ".tmp"):
        fail("draw left " + path + ".tmp")


@test
def compute_agrees_with_afv_eval():
    # afv eval prints every number in %.17g, which reads back exactly
    r = afv.init_cluster(60, 3, None, 7.0)
    points = os.path.join(tmp, "points.xy")
    with open(points, "w") as fp:
        for x, y in (flat(r)[2 * i:2 * i + 2] for i in range(60)):
            fp.write("%.17g %.17g\n" % (x, y))
    g = afv.compute(r)
    lines = subprocess.run([args.afv, "eval", points], check=True,
                           capture_output=True, text=True).stdout.splitlines()
    rows = [line.split() for line in lines if not line.startswith("#")]
    theirs = [float(v) for row in rows for v in row[3:9]]
    mine = []
    forces = flat(g.forces)
    for i in range(60):
        mine += [g.area[i], g.perimeter[i], g.arc[i], g.contacts[i],
                 forces[2 * i], forces[2 * i + 1]]
    same_bits("afv eval", mine, theirs)
    same_bits("afv eval energy", g.energy, [float(lines[-1].split()[2])])


@test
def version_is_the_programs():
    # "afv 0.3.0", and " (commit ...)" after it in a build from git
    out = subprocess.run([args.afv, "--version"], check=True,
                         capture_output=True, text=True).stdout.split()
    if out[:2] != ["afv", afv.__version__]:
        fail("afv --version says %r, afv.__version__ %r" % (out,
                                                           afv.__version__))


@test
def module_is_the_one_asked_for():
    # the package afv/ in module_dir; or, --installed (pip), a package
    # outside the build tree that loads the library it carries
    package = os.path.dirname(os.path.abspath(afv.__file__))
    if args.installed:
        if package.startswith(os.path.dirname(here) + os.sep):
            fail("imported the build tree's %s" % afv.__file__)
        if os.path.dirname(os.path.abspath(afv.library_path)) != package:
            fail("loaded %s, not the package's own libafv.so"
                 % afv.library_path)
    elif os.path.dirname(package) != module_dir:
        fail("imported %s, not from %s" % (afv.__file__, module_dir))


@test
def arrays_with_numpy_lists_without():
    g = afv.compute([[0, 0], [1.6, 0], [0.8, 1.3]])
    if np is None:
        if not (isinstance(g.area, list) and isinstance(g.forces, list)
                and isinstance(g.forces[0], list)):
            fail("without numpy: %r, %r" % (type(g.area), type(g.forces)))
    else:
        if not (isinstance(g.area, np.ndarray) and g.forces.shape == (3, 2)
                and g.area.dtype == np.float64):
            fail("with numpy: %r %r" % (type(g.area), g.forces))
        # an (N, 2) array, a flat list and pairs give the same numbers
        a = afv.compute(np.array([[0, 0], [1.6, 0], [0.8, 1.3]]))
        b = afv.compute([0, 0, 1.6, 0, 0.8, 1.3])
        same_bits("array input", a.forces, flat(b.forces))
        same_bits("array input", a.forces, flat(g.forces))


@test
def bad_input_is_refused():
    # (what, call, what the message must name)
    refusals = [
        ("odd count", lambda: afv.compute([0, 0, 1]), "odd"),
        ("unknown parameter", lambda: afv.Params(P1=3), "'P1'"),
        ("per-cell length", lambda: afv.compute(
            [[0, 0], [1, 1]], afv.Params(P0=[4, 5, 6])), "Params.P0"),
        ("l = 0", lambda: afv.compute([[0, 0]], afv.Params(l=0)), "l = 0"),
        ("KA < 0", lambda: afv.compute([[0, 0]], afv.Params(KA=-1)),
         "KA = -1"),
        ("coincident", lambda: afv.compute([[0, 0], [3, 0], [3, 0]]),
         "cells 1 and 2"),
        ("unknown dynamics key", lambda: afv.Simulation([[0, 0]], v1=2),
         "'v1'"),
        ("seed 0.5", lambda: afv.Simulation([[0, 0]], seed=0.5), "seed"),
        ("integrator substeps", lambda: afv.Simulation(
            [[0, 0]], integrator="substeps"), "removed in afv 0.3.0"),
        ("max_move", lambda: afv.Simulation([[0, 0]], max_move=0.05),
         "max_move"),
    ]
    for what, call, named in refusals:
        try:
            call()
        except (afv.AfvError, ValueError, TypeError) as e:
            if named not in str(e):
                fail("%s: the message %r does not name %r" % (what, str(e),
                                                             named))
            continue
        fail(what + ": accepted")


@test
def quench_continues_as_a_fresh_start():
    # a simulation changed between steps goes on as one started from that
    # state with the new values (afv.h, afv_sim)
    sim, _ = sim_scenario()
    fresh = afv.Simulation(sim.positions, sim.angles, box=(12, 12), seed=11,
                           v0=[0.2 + 0.05 * i for i in range(40)],
                           params=afv.Params(P0=5.5), dt=0.005)
    if fresh.get("dt") != 0.005:
        fail("dt=0.005 gave %r" % fresh.get("dt"))
    fresh_steps = sim.steps
    sim.step(5)
    fresh.steps = fresh_steps       # the noise is drawn for (seed, cell, step)
    fresh.step(5)
    same_bits("quench", sim.positions, flat(fresh.positions))


# ---- the paper's protocol, trajectories and the run analysis -------------
PROTOCOL = dict(seed=5, relax_max_steps=2000)   # check_driver.c's protocol


def protocol_frames():
    """protocol_start as the driver's, 200 steps: the 11 frames (every 20
    steps) of positions, angles and times, and the simulation."""
    sim = afv.protocol_start(40, **PROTOCOL)
    positions, angles, times = [sim.positions], [sim.angles], [sim.time]
    for _ in range(10):
        sim.step(20)
        positions.append(sim.positions)
        angles.append(sim.angles)
        times.append(sim.time)
    return sim, positions, angles, times


@test
def protocol_start_is_the_c_librarys():
    sim, _, _, _ = protocol_frames()
    rep = sim.start_report
    same_bits("relax", [rep["iterations"], rep["energy"]], C["protocol.relax"])
    same_bits("positions", sim.positions, C["protocol.positions"])
    same_bits("angles", sim.angles, C["protocol.angles"])


@test
def protocol_start_is_afv_runs():
    # afv run with the same keys: its trajectory.dat holds the frames
    out = os.path.join(tmp, "run")
    subprocess.run([args.afv, "run", "--N", "40", "--seed", "5",
                    "--relax_max_steps", "2000", "--steps", "200",
                    "--frame_every", "20", "--svg_every", "0", "--quiet",
                    "--out", out], check=True)
    tr = afv.read_trajectory(os.path.join(out, "trajectory.dat"))
    _, positions, _, _ = protocol_frames()
    same_bits("afv run frames", tr.positions, flat(positions))
    if tr.steps != list(range(0, 201, 20)):
        fail("afv run's steps: %r" % tr.steps)


@test
def trajectories_of_both_formats_are_read():
    for name, fmt in (("traj.dat", "traj2"), ("traj1.txt", "traj1")):
        tr = afv.read_trajectory(os.path.join(tmp, name))
        if (tr.n, tr.nframes, len(tr)) != (40, 11, 11) or tr.box is None:
            fail("%s: %r" % (name, tr))
        same_bits(fmt + ".steps", tr.steps, C[fmt + ".steps"])
        for field in ("times", "positions", "angles"):
            same_bits(fmt + "." + field, getattr(tr, field),
                      C[fmt + "." + field])
    _, positions, angles, _ = protocol_frames()
    same_bits("format 1 positions", positions, C["traj1.positions"])
    same_bits("format 1 angles", angles, C["traj1.angles"])
    try:
        afv.read_trajectory(os.path.join(tmp, "open.svg"))
    except afv.AfvError as e:
        if "open.svg" not in str(e):
            fail("the message %r does not name the file" % str(e))
    else:
        fail("an SVG read as a trajectory")


ANALYSIS = dict(l=1, v0=0.5, Dr=0.1, steady_from=0.5, lag=1)


def same_analysis(what, a):
    for name in afv._ANALYSIS_NUMBERS + afv._ANALYSIS_SERIES:
        same_bits("%s: %s" % (what, name), getattr(a, name),
                  C["analysis." + name])


@test
def analysis_is_the_c_librarys():
    tr = afv.read_trajectory(os.path.join(tmp, "traj.dat"))
    same_analysis("Trajectory", afv.analyze(tr, **ANALYSIS))
    # the same frames as arrays: the simulation's own positions
    sim, positions, _, times = protocol_frames()
    same_bits("times", times, C["traj2.times"])
    same_analysis("arrays", afv.analyze(positions, times, sim.box,
                                        **ANALYSIS))
    m = afv.msd(positions, times, sim.box, first=2)
    for name in ("lag", "msd", "msd_rel"):
        same_bits("msd." + name, getattr(m, name), C["msd." + name])


@test
def unwrap_undoes_wrapping():
    # the cluster moved to the box's corner, then wrapped: cells that
    # cross the box's edges between frames jump by L unless unwrapped
    sim, positions, _, times = protocol_frames()
    L = sim.box[0]
    wrapped = [[[(x + L / 2) % L, (y + L / 2) % L] for x, y in flat_pairs(f)]
               for f in positions]
    a = afv.msd(positions, times, sim.box)
    b = afv.msd(wrapped, times, sim.box, unwrap=True)
    c = afv.msd(wrapped, times, sim.box)
    for name in ("msd", "msd_rel"):
        mine, theirs = flat(getattr(b, name)), flat(getattr(a, name))
        if max(abs(x - y) for x, y in zip(mine, theirs)) > 1e-9:
            fail("unwrapped %s: %r, not %r" % (name, mine, theirs))
    if flat(c.msd) == flat(a.msd):
        fail("no cell crossed the box's edge: the test tests nothing")


def flat_pairs(frame):
    values = flat(frame)
    return [values[2 * i:2 * i + 2] for i in range(len(values) // 2)]


failed = 0
for t in TESTS:
    try:
        t()
        print("ok   %s" % t.__name__)
    except Exception as e:          # a failed check or an error: reported
        failed += 1
        print("FAIL %s: %s: %s" % (t.__name__, type(e).__name__, e))
print("python module (%s, %s): %d passed, %d failed" % (
    "numpy " + np.__version__ if np is not None else "no numpy",
    afv.library_path, len(TESTS) - failed, failed))
sys.exit(1 if failed else 0)
