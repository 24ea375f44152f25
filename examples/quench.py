#!/usr/bin/env python3
"""examples/quench.py -- a quench with the Python module: a tissue of 100
cells relaxed, run at low activity (v0 = 0.2, clustered), then quenched to
v0 = 2.5 (the first half of the paper's reversibility experiment); the
largest cluster's share N_GC/N and the confluency Omega before and after,
and a picture of each state.  A few seconds.

    python3 examples/quench.py OUTDIR

The module is found as doc/python.md says (PYTHONPATH=PREFIX/lib/python3/
dist-packages after make install, or python/ in the build tree).
"""
import math
import os
import sys

import afv

out = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(out, exist_ok=True)

L = math.sqrt(100 * math.pi / 0.5)    # 100 cells at the paper's phi = 0.5
box = (L, L)
r = afv.init_cluster(100, 1, box)      # the authors' start: a random square
sim = afv.Simulation(r, afv.init_angles(100, 1), box=box,
                     params=afv.Params(P0=4.8), v0=0.2, seed=1)
relax = sim.relax(tol=1e-4, max_iter=20000)
print("relaxed in %d steps, E %.4f -> %.4f" % (
    relax["iterations"], relax["energy0"], relax["energy"]))


def report(label):
    o = sim.order_parameters()
    print("%-26s t = %6.1f  N_GC/N = %.2f  Omega = %.2f  clusters = %d" % (
        label, sim.time, o["giant_fraction"], o["omega"], o["clusters"]))
    return o


sim.step(1500)
before = report("v0 = 0.2:")
sim.draw(os.path.join(out, "before_quench.svg"), color_by_cluster=True)
sim.set(v0=2.5)                       # the quench: the next step uses it
sim.step(1500)
after = report("after the quench, v0 = 2.5:")
sim.draw(os.path.join(out, "after_quench.svg"), color_by_cluster=True)
print("pictures: %s, %s" % (os.path.join(out, "before_quench.svg"),
                            os.path.join(out, "after_quench.svg")))
# the quench breaks the tissue up: more clusters after it than before
sys.exit(0 if after["clusters"] > before["clusters"] else 1)
