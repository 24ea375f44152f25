#!/usr/bin/env python3
"""Calls afv_compute from Python through ctypes (standard library only) and
checks every number against `afv eval` on the same file.

    python3 doc/python_example.py [LIBAFV_SO] [AFV_PROGRAM] [POINTS]

Defaults: ./libafv.so, ./afv and data/cluster.xy (run from the repository
root after `make afv shared`, or give the installed paths).  Exit status 0
if the library and the program agree, 1 if not (doc/python.md explains it).
"""
import ctypes as C
import subprocess
import sys

lib_path = sys.argv[1] if len(sys.argv) > 1 else "./libafv.so"
afv_prog = sys.argv[2] if len(sys.argv) > 2 else "./afv"
points = sys.argv[3] if len(sys.argv) > 3 else "data/cluster.xy"

DP, IP = C.POINTER(C.c_double), C.POINTER(C.c_int)


class Params(C.Structure):        # afv_params, field by field
    _fields_ = [(name, C.c_double) for name in
                ("l", "KA", "KP", "A0", "P0", "Lambda", "cap")] + \
               [(name, DP) for name in ("KA_i", "KP_i", "A0_i", "P0_i")]


class Box(C.Structure):           # afv_box
    _fields_ = [("periodic", C.c_int), ("Lx", C.c_double), ("Ly", C.c_double)]


afv = C.CDLL(lib_path)
afv.afv_params_default.argtypes = [C.POINTER(Params)]
# afv_geom is opaque: a pointer from afv_geom_new, read through its calls
afv.afv_geom_new.restype = C.c_void_p
afv.afv_geom_delete.argtypes = [C.c_void_p]
for name, restype in (("area", DP), ("perim", DP), ("arc", DP),
                      ("contacts", IP), ("energy", C.c_double)):
    getattr(afv, "afv_geom_" + name).argtypes = [C.c_void_p]
    getattr(afv, "afv_geom_" + name).restype = restype
afv.afv_compute.argtypes = [C.c_void_p, C.c_int, DP, C.POINTER(Params),
                            C.POINTER(Box), DP]
afv.afv_compute.restype = C.c_int
afv.afv_strerror.restype = C.c_char_p

xy = []
with open(points) as fp:
    for line in fp:
        line = line.split("#")[0].replace(",", " ").split()
        if line:
            xy += [float(line[0]), float(line[1])]
n = len(xy) // 2

r = (C.c_double * (2 * n))(*xy)
f = (C.c_double * (2 * n))()
p, box, g = Params(), Box(0, 0.0, 0.0), afv.afv_geom_new()
if not g:
    sys.exit("afv_geom_new: out of memory")
afv.afv_params_default(C.byref(p))
st = afv.afv_compute(g, n, r, C.byref(p), C.byref(box), f)
if st != 0:
    sys.exit("afv_compute: " + afv.afv_strerror(st).decode())
area, perim = afv.afv_geom_area(g), afv.afv_geom_perim(g)
arc, contacts = afv.afv_geom_arc(g), afv.afv_geom_contacts(g)
energy_lib = afv.afv_geom_energy(g)

# afv eval prints every number in %.17g, which reads back to the same double
out = subprocess.run([afv_prog, "eval", points], check=True,
                     capture_output=True, text=True).stdout.splitlines()
rows = [line.split() for line in out if not line.startswith("#")]
energy = float(out[-1].split()[2])
mismatch = 0
for i, row in enumerate(rows):
    mine = [area[i], perim[i], arc[i], contacts[i], f[2*i], f[2*i+1]]
    theirs = [float(v) for v in row[3:9]]
    if mine != theirs:
        mismatch += 1
        print("cell %d: ctypes %r, afv eval %r" % (i, mine, theirs))
ok = len(rows) == n and mismatch == 0 and energy_lib == energy
print("%d cells, E = %.17g: ctypes and afv eval %s" %
      (n, energy_lib, "agree bit for bit" if ok else "DIFFER"))
afv.afv_geom_delete(g)
sys.exit(0 if ok else 1)
