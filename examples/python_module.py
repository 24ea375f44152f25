#!/usr/bin/env python3
"""examples/python_module.py -- a tour of the Python module afv: shapes,
energy and forces of a configuration, per-cell parameters, the order
parameters, a picture.  Under a second.

    python3 examples/python_module.py OUTDIR
"""
import os
import sys

import afv

out = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(out, exist_ok=True)
print("afv", afv.__version__, "from", afv.library_path)

# three cells in open space (the README's C example)
g = afv.compute([[0, 0], [1.6, 0], [0.8, 1.3]], afv.Params(P0=5.2))
for i in range(g.n):
    print("cell %d: A %.4f P %.4f free arc %.4f contacts %d F (%.4f, %.4f)"
          % (i, g.area[i], g.perimeter[i], g.arc[i], g.contacts[i],
             g.forces[i][0], g.forces[i][1]))
print("E %.6f" % g.energy)

# a patch of 61 cells, the inner ones stiffer (P0 per cell)
r = afv.init_lattice(61, a=1.7)
inner = [x * x + y * y < 9 for x, y in (tuple(p) for p in r)]
params = afv.Params(P0=[4.0 if i else 6.0 for i in inner])
o = afv.order_parameters(r, params)
print("61 cells: N_GC/N %.2f, Omega %.3f, %d contacting pairs, %d triple "
      "junctions" % (o["giant_fraction"], o["omega"], o["pairs"],
                     o["junctions"]))
afv.draw(os.path.join(out, "patch.svg"), r, params=params,
         color_by_cluster=True)
print("picture:", os.path.join(out, "patch.svg"))
print("mean-field P0* (Lambda 0.2): %.4f" % afv.meanfield_p0())
