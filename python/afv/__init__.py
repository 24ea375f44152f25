"""afv -- the Active Finite Voronoi model from Python.

A thin layer over the C library libafv.so through the standard library's
ctypes: every number is computed by the C library, so results are its
results bit for bit.  With numpy installed, arrays go in and come out as
numpy arrays; without it, as lists.  Positions are N x 2 (rows x, y):
given as an (N, 2) array, a list of pairs, or a flat list x0, y0, x1, ...

    import afv
    r = afv.init_lattice(37)                   # 37 cells, a compact cluster
    g = afv.compute(r, afv.Params(P0=5.2))     # shapes, energy and forces
    print(g.energy, g.area[0], g.forces[0])
    sim = afv.Simulation(r, v0=0.5, seed=1)
    sim.relax()
    sim.step(1000)
    print(afv.order_parameters(sim.positions)["giant_fraction"])
    sim.draw("final.svg")

The library is found, in order: the file named by the environment variable
AFV_LIBRARY; libafv.so in this package's directory (installed by pip, which
builds it: python/setup.py); the build tree's libafv.so (python/afv/ after
`make shared`); PREFIX/lib/libafv.so (make install puts this package in
PREFIX/lib/python3/dist-packages/afv/); then the loader's search path.
doc/python.md documents the module.
"""
import ctypes as C
import math
import numbers
import os

try:
    import numpy as _np
except ImportError:
    _np = None

__all__ = ["AfvError", "Params", "Geometry", "Simulation", "compute",
           "order_parameters", "draw", "init_lattice", "init_cluster",
           "init_random", "init_angles", "meanfield_p0", "library_path",
           "protocol_start", "box_side", "Trajectory", "read_trajectory",
           "trajectory", "msd", "analyze", "Analysis", "MSD"]

_DP, _IP = C.POINTER(C.c_double), C.POINTER(C.c_int)


# ---- the library -------------------------------------------------------------
def _library_candidates():
    here = os.path.dirname(os.path.abspath(__file__))
    if os.environ.get("AFV_LIBRARY"):
        return [os.environ["AFV_LIBRARY"]]
    def up(k):                     # libafv.so k directories above here
        return os.path.join(here, *([os.pardir] * k + ["libafv.so"]))
    return [os.path.join(here, "libafv.so"), up(2), up(3), "libafv.so"]


def _load():
    tried = []
    for path in _library_candidates():
        if os.sep in path and not os.path.exists(path):
            tried.append(path)
            continue
        try:
            return C.CDLL(path), os.path.normpath(path)
        except OSError as e:
            tried.append("%s (%s)" % (path, e))
    raise ImportError("afv: libafv.so not found (tried %s); build it with "
                      "`make shared` or set AFV_LIBRARY" % ", ".join(tried))


_lib, library_path = _load()


def _declare(name, restype, *argtypes):
    fn = getattr(_lib, name)
    fn.restype, fn.argtypes = restype, list(argtypes)
    return fn


class _CParams(C.Structure):       # afv_params, field by field (afv.h)
    _fields_ = [(name, C.c_double) for name in
                ("l", "KA", "KP", "A0", "P0", "Lambda", "cap")] + \
               [(name, _DP) for name in ("KA_i", "KP_i", "A0_i", "P0_i")]


class _CBox(C.Structure):          # afv_box
    _fields_ = [("periodic", C.c_int), ("Lx", C.c_double), ("Ly", C.c_double)]


_VP, _PP, _BP = C.c_void_p, C.POINTER(_CParams), C.POINTER(_CBox)
_declare("afv_version", C.c_char_p)
_declare("afv_struct_size", C.c_size_t, C.c_char_p)
_declare("afv_strerror", C.c_char_p, C.c_int)
_declare("afv_params_default", None, _PP)
_declare("afv_params_check", C.c_int, _PP, C.c_int)
_declare("afv_geom_new", _VP)
_declare("afv_geom_delete", None, _VP)
for _name, _type in (("area", _DP), ("perim", _DP), ("arc", _DP),
                     ("contacts", _IP)):
    _declare("afv_geom_" + _name, _type, _VP)
_declare("afv_geom_energy", C.c_double, _VP)
_declare("afv_geom_bad_pair", None, _VP, _IP, _IP)
_ECOINCIDENT = 5                   # AFV_ECOINCIDENT
_declare("afv_compute", C.c_int, _VP, C.c_int, _DP, _PP, _BP, _DP)
_declare("afv_order_parameters", C.c_int, _VP, _DP, C.c_double, _BP, _DP, _IP)
_declare("afv_svg_save", C.c_int, C.c_char_p, _VP, C.c_int, _DP, _DP, _PP,
         _BP, C.c_int)
_declare("afv_init_lattice", C.c_int, C.c_int, C.c_double, _BP, _DP)
_declare("afv_init_cluster", None, C.c_int, C.c_ulonglong, _BP, C.c_double, _DP)
_declare("afv_init_random", None, C.c_int, C.c_ulonglong, _BP, C.c_double, _DP)
_declare("afv_init_angles", None, C.c_int, C.c_ulonglong, _DP)
_declare("afv_meanfield_p0", C.c_double, C.c_double, C.c_double, C.c_double)
_declare("afv_dyn_new", _VP)
_declare("afv_dyn_delete", None, _VP)
_declare("afv_dyn_set", C.c_int, _VP, C.c_char_p, C.c_double)
_declare("afv_dyn_get", C.c_int, _VP, C.c_char_p, _DP)
_declare("afv_dyn_set_cells", C.c_int, _VP, C.c_char_p, _DP)
_declare("afv_sim_new", _VP)
_declare("afv_sim_delete", None, _VP)
_declare("afv_sim_init", C.c_int, _VP, C.c_int, _DP, _DP, _PP, _BP, _VP)
_declare("afv_sim_step", C.c_int, _VP)
_declare("afv_sim_refresh", C.c_int, _VP)
_declare("afv_sim_n", C.c_int, _VP)
_declare("afv_sim_steps", C.c_longlong, _VP)
_declare("afv_sim_set_steps", None, _VP, C.c_longlong)
_declare("afv_sim_time", C.c_double, _VP)
_declare("afv_sim_positions", _DP, _VP)
_declare("afv_sim_angles", _DP, _VP)
_declare("afv_sim_forces", _DP, _VP)
_declare("afv_sim_geom", _VP, _VP)
_declare("afv_sim_params", _PP, _VP)
_declare("afv_sim_box", _BP, _VP)
_declare("afv_sim_dyn", _VP, _VP)
_declare("afv_sim_bad_cell", C.c_int, _VP)
_declare("afv_relax_report_new", _VP)
_declare("afv_relax_report_delete", None, _VP)
_declare("afv_relax_report_get", C.c_int, _VP, C.c_char_p, _DP)
_declare("afv_relax", C.c_int, _VP, C.c_double, C.c_long, _VP, _VP, _VP)

_LP = C.POINTER(C.c_longlong)
_declare("afv_sim_jumps", C.c_longlong, _VP)
_declare("afv_sim_largest_move", C.c_double, _VP)
_declare("afv_traj_new", _VP)
_declare("afv_traj_delete", None, _VP)
_declare("afv_traj_read", C.c_int, C.c_char_p, _VP, C.c_char_p, C.c_size_t)
_declare("afv_traj_set", C.c_int, _VP, C.c_int, C.c_int, _BP, _LP, _DP, _DP,
         _DP)
_declare("afv_traj_unwrap", None, _VP)
_declare("afv_traj_n", C.c_int, _VP)
_declare("afv_traj_nframes", C.c_int, _VP)
_declare("afv_traj_box", _BP, _VP)
_declare("afv_traj_steps", _LP, _VP)
for _name in ("times", "positions", "angles"):
    _declare("afv_traj_" + _name, _DP, _VP)
_declare("afv_msd_new", _VP)
_declare("afv_msd_delete", None, _VP)
_declare("afv_msd_compute", C.c_int, _VP, _VP, C.c_int, C.c_double)
_declare("afv_msd_series", _DP, _VP, C.c_char_p, _IP)
_declare("afv_analysis_new", _VP)
_declare("afv_analysis_delete", None, _VP)
_declare("afv_analyze", C.c_int, _VP, _VP, C.c_double, C.c_double,
         C.c_double, C.c_double, C.c_double)
_declare("afv_analysis_get", C.c_int, _VP, C.c_char_p, _DP)
_declare("afv_analysis_series", _DP, _VP, C.c_char_p, _IP)
_declare("afv_protocol_new", _VP)
_declare("afv_protocol_delete", None, _VP)
_declare("afv_protocol_set", C.c_int, _VP, C.c_char_p, C.c_double)
_declare("afv_protocol_set_cells", C.c_int, _VP, C.c_char_p, _DP)
_declare("afv_protocol_start", C.c_int, _VP, C.c_int, _PP, _BP, _VP, _VP,
         _VP, _VP, _VP)

for _struct, _mirror in (("afv_params", _CParams), ("afv_box", _CBox)):
    if _lib.afv_struct_size(_struct.encode()) != C.sizeof(_mirror):
        raise ImportError("afv: %s in %s is not the struct this module "
                          "mirrors (a module of another version?)"
                          % (_struct, library_path))

__version__ = _lib.afv_version().decode()

_ORDER_NAMES = ("giant_fraction", "omega", "clusters", "pairs", "junctions")
_ORDER_INTS = ("clusters", "pairs", "junctions")
_RELAX_NAMES = ("iterations", "time", "max_force", "energy0", "energy",
                "drift", "drop", "jumps", "converged", "at_kink", "refused")
_RELAX_INTS = ("iterations", "jumps")
_RELAX_FLAGS = ("converged", "at_kink", "refused")
_DYN_NAMES = ("mu", "v0", "Dr", "dt", "seed")
_REMOVED_DYN = ("max_move", "integrator")   # the sub-steps, gone in 0.3.0


class AfvError(Exception):
    """A status other than AFV_OK from the library (status: its code)."""

    def __init__(self, status, what):
        self.status = status
        Exception.__init__(self, "%s: %s" % (
            what, _lib.afv_strerror(status).decode()))


def _check(status, what):
    if status != 0:
        raise AfvError(status, what)


# ---- arrays in and out ----------------------------------------------------
def _flat(values):
    """values (any nesting of numbers, or an array) as a flat list."""
    out = []
    for v in values:
        if not isinstance(v, str) and hasattr(v, "__len__"):
            out.extend(_flat(v))
        else:
            out.append(float(v))
    return out


class _Doubles(object):
    """A C double array holding values (kept alive as long as this is)."""

    def __init__(self, values, count=None, what="values"):
        if _np is not None:
            self.array = _np.ascontiguousarray(values, dtype=_np.float64)
            self.array = self.array.reshape(-1)
            self.ptr = self.array.ctypes.data_as(_DP)
            n = self.array.size
        else:
            flat = _flat(values)
            n = len(flat)
            self.array = (C.c_double * max(n, 1))(*flat)
            self.ptr = C.cast(self.array, _DP)
        if count is not None and n != count:
            raise ValueError("%s: %d numbers, expected %d" % (what, n, count))
        self.size = n


def _positions(r):
    """(n, pointer holder) for positions given as pairs or flat."""
    d = _Doubles(r, what="positions")
    if d.size % 2:
        raise ValueError("positions: an odd count of numbers (%d)" % d.size)
    return d.size // 2, d


def _out(ptr, count, pairs=False, ints=False):
    """count values from a C pointer: an array (copy) or a list."""
    if _np is not None:
        a = _np.ctypeslib.as_array(ptr, (count,)).copy() if count else \
            _np.zeros(0, dtype=_np.int32 if ints else _np.float64)
        return a.reshape(-1, 2) if pairs else a
    values = ptr[:count]
    if pairs:
        return [[values[2 * i], values[2 * i + 1]] for i in range(count // 2)]
    return values


def _empty(count):
    if _np is not None:
        a = _np.zeros(count, dtype=_np.float64)
        return a, a.ctypes.data_as(_DP)
    a = (C.c_double * max(count, 1))()
    return a, C.cast(a, _DP)


# ---- parameters and box ---------------------------------------------------
class Params(object):
    """The model's parameters (afv_params): l, KA, KP, A0, P0, Lambda, cap,
    with the paper's defaults (afv_params_default: l 1, KA KP 1, A0 pi,
    P0 4.8, Lambda 0.2, cap 0).  KA, KP, A0 and P0 may each be one number or
    one per cell (a sequence of N values: a mixture of cell types)."""

    _SCALARS = ("l", "KA", "KP", "A0", "P0", "Lambda", "cap")
    _PER_CELL = ("KA", "KP", "A0", "P0")

    def __init__(self, **values):
        c = _CParams()
        _lib.afv_params_default(C.byref(c))
        for name in self._SCALARS:
            setattr(self, name, getattr(c, name))
        for name, value in values.items():
            if name not in self._SCALARS:
                raise TypeError("Params: unknown parameter %r (known: %s)"
                                % (name, ", ".join(self._SCALARS)))
            setattr(self, name, value)

    def __repr__(self):
        return "Params(%s)" % ", ".join(
            "%s=%r" % (k, getattr(self, k)) for k in self._SCALARS)

    def _c(self, n):
        """The C struct for n cells and the arrays it points to."""
        c, keep = _CParams(), []
        for name in self._SCALARS:
            value = getattr(self, name)
            if name in self._PER_CELL and not isinstance(value, numbers.Real):
                d = _Doubles(value, n, "Params." + name)
                keep.append(d)
                setattr(c, name + "_i", d.ptr)
                value = 0.0
            setattr(c, name, float(value))
        st = _lib.afv_params_check(C.byref(c), n)
        if st != 0:
            raise AfvError(st, "Params: " + self._first_bad(c, n))
        return c, keep

    def _first_bad(self, c, n):
        """The name of the first value afv_params_check refuses in c."""
        for name in self._SCALARS:
            one = _CParams()
            _lib.afv_params_default(C.byref(one))
            setattr(one, name, getattr(c, name))
            if name in self._PER_CELL:
                setattr(one, name + "_i", getattr(c, name + "_i"))
            if _lib.afv_params_check(C.byref(one), n) != 0:
                return "%s = %r" % (name, getattr(self, name))
        return "the combination of values"


def _params(p, n):
    return (p if p is not None else Params())._c(n)


def _box(box):
    """None: open space; (Lx, Ly): a periodic box."""
    if box is None:
        return _CBox(0, 0.0, 0.0)
    Lx, Ly = box
    return _CBox(1, float(Lx), float(Ly))


# ---- one configuration -----------------------------------------------------
class Geometry(object):
    """Shapes, energy and forces of one configuration (afv_compute):
    n, area, perimeter, arc (free boundary length), contacts (edges longer
    than AFV_CONTACT_TOL l), energy, forces (N x 2, -dE/dr)."""

    def __repr__(self):
        return "Geometry(n=%d, energy=%r)" % (self.n, self.energy)


def _read_geom(g, n):
    out = Geometry()
    out.n = n
    out.area = _out(_lib.afv_geom_area(g), n)
    out.perimeter = _out(_lib.afv_geom_perim(g), n)
    out.arc = _out(_lib.afv_geom_arc(g), n)
    out.contacts = _out(_lib.afv_geom_contacts(g), n, ints=True)
    out.energy = _lib.afv_geom_energy(g)
    return out


class _Geom(object):
    """An afv_geom computed for positions (deleted with this object)."""

    def __init__(self, r, params, box):
        self.n, self.r = _positions(r)
        self.params, self.keep = _params(params, self.n)
        self.box = _box(box)
        self.g = _lib.afv_geom_new()
        if not self.g:
            raise MemoryError("afv_geom_new")
        self.f, fptr = _empty(2 * self.n)
        st = _lib.afv_compute(self.g, self.n, self.r.ptr, C.byref(self.params),
                              C.byref(self.box), fptr)
        if st == _ECOINCIDENT:
            i, j = C.c_int(), C.c_int()
            _lib.afv_geom_bad_pair(self.g, C.byref(i), C.byref(j))
            raise AfvError(st, "afv_compute: cells %d and %d" % (i.value,
                                                                j.value))
        _check(st, "afv_compute")
        self.fptr = fptr

    def __del__(self):
        if getattr(self, "g", None):
            _lib.afv_geom_delete(self.g)
            self.g = None


def compute(r, params=None, box=None):
    """Geometry, energy and forces of the cells at r (N x 2) with params
    (Params; None: the defaults) in box (None: open space; (Lx, Ly):
    periodic).  Returns a Geometry."""
    gg = _Geom(r, params, box)
    out = _read_geom(gg.g, gg.n)
    out.forces = _out(gg.fptr, 2 * gg.n, pairs=True)
    return out


def _order(g, n, rptr, l, box):
    values, vptr = _empty(5)
    labels = (C.c_int * max(n, 1))()
    _check(_lib.afv_order_parameters(g, rptr, l, C.byref(box), vptr,
                                     C.cast(labels, _IP)),
           "afv_order_parameters")
    out = dict(zip(_ORDER_NAMES, [float(v) for v in values[:5]]))
    for name in _ORDER_INTS:
        out[name] = int(out[name])
    out["labels"] = _out(C.cast(labels, _IP), n, ints=True)
    return out


def order_parameters(r, params=None, box=None):
    """The paper's order parameters of the cells at r: giant_fraction
    (N_GC / N), omega (confluency Omega), clusters (their number), pairs
    (contacting pairs), junctions (triple junctions), and labels (each
    cell's cluster)."""
    gg = _Geom(r, params, box)
    return _order(gg.g, gg.n, gg.r.ptr, gg.params.l, gg.box)


def _save_svg(path, g, n, rptr, theta_ptr, params, box, color_by_cluster):
    _check(_lib.afv_svg_save(os.fsencode(path), g, n, rptr, theta_ptr,
                             C.byref(params), C.byref(box),
                             1 if color_by_cluster else 0),
           "draw %s" % path)


def draw(path, r, theta=None, params=None, box=None, color_by_cluster=False):
    """Writes afv's SVG picture of the cells at r (with polarity arrows if
    theta, N angles, is given) into path, atomically; cells filled by
    cluster if color_by_cluster."""
    gg = _Geom(r, params, box)
    th = _Doubles(theta, gg.n, "theta") if theta is not None else None
    _save_svg(path, gg.g, gg.n, gg.r.ptr, th.ptr if th else None, gg.params,
              gg.box, color_by_cluster)


# ---- initial configurations -----------------------------------------------
def init_lattice(n, a=1.0, box=None):
    """n centres on a triangular lattice of spacing a (in l), nearest the
    centre of the box (the origin in open space)."""
    b = _box(box)
    out, ptr = _empty(2 * n)
    _check(_lib.afv_init_lattice(n, a, C.byref(b), ptr), "afv_init_lattice")
    return _out(ptr, 2 * n, pairs=True)


def init_cluster(n, seed, box=None, side=None):
    """The authors' start: n centres uniform in a square of side `side`
    (default 0.3 Lx in a periodic box) from the streams of seed."""
    b = _box(box)
    if side is None:
        if not b.periodic:
            raise ValueError("init_cluster: give side in open space")
        side = 0.3 * b.Lx
    out, ptr = _empty(2 * n)
    _lib.afv_init_cluster(n, seed, C.byref(b), side, ptr)
    return _out(ptr, 2 * n, pairs=True)


def init_random(n, seed, box=None, side=None):
    """n centres uniform in the periodic box (open space: a square of side
    `side` about the origin) from the streams of seed."""
    b = _box(box)
    if side is None and not b.periodic:
        raise ValueError("init_random: give side in open space")
    out, ptr = _empty(2 * n)
    _lib.afv_init_random(n, seed, C.byref(b), side or 0.0, ptr)
    return _out(ptr, 2 * n, pairs=True)


def init_angles(n, seed):
    """n polarity angles uniform in [0, 2 pi) from the streams of seed."""
    out, ptr = _empty(n)
    _lib.afv_init_angles(n, seed, ptr)
    return _out(ptr, n)


def meanfield_p0(Lambda=0.2, A0=math.pi, KP=1.0):
    """The P0 below which the hexagonal packing closes its gaps."""
    return _lib.afv_meanfield_p0(Lambda, A0, KP)


# ---- simulations -----------------------------------------------------------
def _relax_report(rep):
    """An afv_relax_report as a dict (integers and flags as such)."""
    out, v = {}, C.c_double()
    for name in _RELAX_NAMES:
        _check(_lib.afv_relax_report_get(rep, name.encode(), C.byref(v)),
               name)
        out[name] = v.value
    for name in _RELAX_INTS:
        out[name] = int(out[name])
    for name in _RELAX_FLAGS:
        out[name] = bool(out[name])
    return out


class Simulation(object):
    """A running simulation (afv_sim): the cells at r (N x 2), angles theta
    (N; default all 0), params, box as for compute(), and the dynamics'
    values mu, v0, Dr, dt, seed with afv_dyn_default's defaults (mu 1,
    v0 0, Dr 0.1, dt 0.01, seed 1); v0 and Dr may be one per cell.  The
    step is the paper's Euler step.

    step(k) takes k steps; relax() relaxes at zero activity.  Between steps
    set(v0=...) changes the dynamics (a quench), set_params(P0=...) the
    model; the run then goes on exactly as one started from that state."""

    def __init__(self, r, theta=None, params=None, box=None, **dyn):
        n, rd = _positions(r)
        cp, keep = self._open(n, params, dyn)
        cb = _box(box)
        th = _Doubles(theta, n, "theta") if theta is not None else None
        _check(_lib.afv_sim_init(self._sim, n, rd.ptr, th.ptr if th else None,
                                 C.byref(cp), C.byref(cb), self._dyn),
               "afv_sim_init")
        self._cells = {}    # afv_sim_init copied the per-cell arrays

    def _open(self, n, params, dyn):
        """A new afv_sim and afv_dyn for n cells (dyn: the dynamics'
        values); returns the C params and the arrays they point to."""
        self.n = n
        self._params = params if params is not None else Params()
        cp, keep = self._params._c(n)
        self._dyn = _lib.afv_dyn_new()
        self._sim = _lib.afv_sim_new()
        if not self._dyn or not self._sim:
            raise MemoryError("afv_sim_new")
        self._cells = {}
        self._set_dyn(self._dyn, dyn)
        return cp, keep

    def __del__(self):
        if getattr(self, "_sim", None):
            _lib.afv_sim_delete(self._sim)
            self._sim = None
        if getattr(self, "_dyn", None):
            _lib.afv_dyn_delete(self._dyn)
            self._dyn = None

    def _set_dyn(self, d, values):
        for name, value in values.items():
            if name in _REMOVED_DYN:
                raise TypeError("Simulation: %s: integrator substeps and "
                                "max_move were removed in afv 0.3.0 (the "
                                "step is the paper's Euler step)" % name)
            if name not in _DYN_NAMES:
                raise TypeError("Simulation: unknown key %r (known: %s)"
                                % (name, ", ".join(_DYN_NAMES)))
            if name in ("v0", "Dr") and not isinstance(value, numbers.Real):
                arr = _Doubles(value, self.n, name)
                self._cells[name] = arr    # the library reads it every step
                _check(_lib.afv_dyn_set_cells(d, name.encode(), arr.ptr),
                       "dynamics " + name)
                continue
            if name in ("v0", "Dr"):
                _lib.afv_dyn_set_cells(d, name.encode(), None)
                self._cells.pop(name, None)
            try:
                number = float(value)
            except (TypeError, ValueError):
                raise ValueError("Simulation: %s = %r is not a number"
                                 % (name, value))
            _check(_lib.afv_dyn_set(d, name.encode(), number),
                   "dynamics %s = %r" % (name, value))

    def set(self, **dyn):
        """Changes the dynamics' values (as in Simulation()) before the
        next step."""
        self._set_dyn(_lib.afv_sim_dyn(self._sim), dyn)

    def get(self, name):
        """The dynamics' value name (as in Simulation())."""
        v = C.c_double()
        _check(_lib.afv_dyn_get(_lib.afv_sim_dyn(self._sim), name.encode(),
                                C.byref(v)), "dynamics " + name)
        return v.value

    def set_params(self, **values):
        """Changes model parameters (scalars) and recomputes the forces."""
        p = _lib.afv_sim_params(self._sim).contents
        for name, value in values.items():
            if name not in Params._SCALARS:
                raise TypeError("set_params: unknown parameter %r" % name)
            setattr(p, name, float(value))
        _check(_lib.afv_sim_refresh(self._sim), "afv_sim_refresh")

    def step(self, k=1):
        """Takes k steps (afv_sim_step); AfvError if one cannot be taken
        (the state is that before it)."""
        for _ in range(k):
            st = _lib.afv_sim_step(self._sim)
            if st != 0:
                raise AfvError(st, "step %d (cell %d)" % (
                    self.steps, _lib.afv_sim_bad_cell(self._sim)))

    def relax(self, tol=1e-6, max_iter=100000):
        """Relaxation at zero activity (afv_relax) to max |F| <= tol, a
        kink, a refused step or max_iter steps; returns its report."""
        rep = _lib.afv_relax_report_new()
        if not rep:
            raise MemoryError("afv_relax_report_new")
        try:
            _check(_lib.afv_relax(self._sim, tol, max_iter, rep, None, None),
                   "afv_relax")
            return _relax_report(rep)
        finally:
            _lib.afv_relax_report_delete(rep)

    @property
    def steps(self):
        """Steps taken; settable (the noise of a step is drawn for (seed,
        cell, step), so a continued run sets it to where it stopped)."""
        return _lib.afv_sim_steps(self._sim)

    @steps.setter
    def steps(self, k):
        _lib.afv_sim_set_steps(self._sim, int(k))

    @property
    def time(self):
        return _lib.afv_sim_time(self._sim)

    @property
    def box(self):
        """None in open space, else the periodic box (Lx, Ly)."""
        b = _lib.afv_sim_box(self._sim).contents
        return (b.Lx, b.Ly) if b.periodic else None

    @property
    def jumps(self):
        """Steps so far (relaxation too) that moved some cell more than
        half a cell radius (afv_sim_jumps: Euler no longer follows the
        continuous dynamics there; a smaller dt, or the cap, helps)."""
        return _lib.afv_sim_jumps(self._sim)

    @property
    def largest_move(self):
        """The largest move of a cell in one step so far, in l."""
        return _lib.afv_sim_largest_move(self._sim)

    @property
    def positions(self):
        """The N x 2 centres, unwrapped (a copy)."""
        return _out(_lib.afv_sim_positions(self._sim), 2 * self.n, pairs=True)

    @property
    def angles(self):
        return _out(_lib.afv_sim_angles(self._sim), self.n)

    @property
    def forces(self):
        return _out(_lib.afv_sim_forces(self._sim), 2 * self.n, pairs=True)

    @property
    def energy(self):
        return _lib.afv_geom_energy(_lib.afv_sim_geom(self._sim))

    def geometry(self):
        """The shapes and forces at the current positions (a Geometry)."""
        out = _read_geom(_lib.afv_sim_geom(self._sim), self.n)
        out.forces = self.forces
        return out

    def order_parameters(self):
        """order_parameters() of the current configuration."""
        return _order(_lib.afv_sim_geom(self._sim), self.n,
                      _lib.afv_sim_positions(self._sim),
                      _lib.afv_sim_params(self._sim).contents.l,
                      _lib.afv_sim_box(self._sim).contents)

    def draw(self, path, color_by_cluster=False):
        """afv's SVG picture of the current state into path."""
        _save_svg(path, _lib.afv_sim_geom(self._sim), self.n,
                  _lib.afv_sim_positions(self._sim),
                  _lib.afv_sim_angles(self._sim),
                  _lib.afv_sim_params(self._sim).contents,
                  _lib.afv_sim_box(self._sim).contents, color_by_cluster)


# ---- the paper's protocol ---------------------------------------------------
_STARTS = {"cluster": 0, "lattice": 1, "random": 2, "given": 3}  # AFV_START_*
_RELAXES = {"flow": 0, "fire": 1}                                 # AFV_RELAX_*
_AUTHORS_SQUARE = 0.3              # AFV_AUTHORS_SQUARE


def box_side(n, phi=0.5, l=1.0):
    """afv run's box side L = sqrt(N pi l^2 / phi) (packing fraction phi),
    computed in the program's order of operations (the same bits)."""
    return math.sqrt(float(n) * math.pi * l * l / phi)


def protocol_start(n, params=None, phi=0.5, box="periodic", init="cluster",
                   spacing=1.8, positions=None, theta=None, relax="flow",
                   relax_tol=1e-6, relax_max_steps=100000, **dyn):
    """The paper's protocol up to the active run, as `afv run` does it with
    the same keys (afv run --help): n cells at packing fraction phi in a
    periodic box of side box_side(n, phi, l) (box="open": open space);
    the start init ("cluster": the authors' square of side 0.3 L, uniform
    from the seed; "lattice": the triangular lattice of spacing `spacing`
    l; "random": uniform over the box; "given": `positions`), angles from
    the seed unless `theta` is given; relaxed at v0 = 0 (relax "flow": the
    paper's Euler steps; "fire": FIRE 2.0) to max |F| <= relax_tol or
    relax_max_steps steps; then v0 on, at step 0.  dyn: mu, v0, Dr, dt,
    seed as for Simulation (afv run's defaults: v0 0.5, the others
    Simulation's).  Returns the Simulation, its relaxation's report in
    .start_report: stepping it gives afv run's trajectory bit for bit."""
    if init not in _STARTS:
        raise ValueError("protocol_start: init %r (known: %s)"
                         % (init, ", ".join(_STARTS)))
    if relax not in _RELAXES:
        raise ValueError("protocol_start: relax %r (known: flow, fire)"
                         % (relax,))
    if box not in ("periodic", "open"):
        raise ValueError("protocol_start: box %r (periodic or open)" % (box,))
    dyn.setdefault("v0", 0.5)          # afv run's default v0
    sim = Simulation.__new__(Simulation)
    cp, keep = sim._open(n, params, dyn)
    L = box_side(n, phi, cp.l)
    cb = _CBox(1 if box == "periodic" else 0, L, L)
    pr = _lib.afv_protocol_new()
    rep = _lib.afv_relax_report_new()
    try:
        if not pr or not rep:
            raise MemoryError("afv_protocol_new")
        values = {"start": _STARTS[init], "relax": _RELAXES[relax],
                  "relax_tol": relax_tol, "relax_max_steps": relax_max_steps,
                  "side": (_AUTHORS_SQUARE * L if init == "cluster" else L),
                  "spacing": spacing * cp.l}
        for name, value in values.items():
            _check(_lib.afv_protocol_set(pr, name.encode(), float(value)),
                   "protocol_start: %s = %r" % (name, value))
        arrays = {"r": _Doubles(positions, 2 * n, "positions")
                  if init == "given" else None,
                  "theta": _Doubles(theta, n, "theta")
                  if theta is not None else None}
        if init == "given" and positions is None:
            raise ValueError("protocol_start: init 'given' needs positions")
        for name, d in arrays.items():
            _lib.afv_protocol_set_cells(pr, name.encode(), d.ptr if d else None)
        _check(_lib.afv_protocol_start(sim._sim, n, C.byref(cp), C.byref(cb),
                                       sim._dyn, pr, rep, None, None),
               "protocol_start")
        sim._cells = {}             # afv_sim_init copied the per-cell arrays
        sim.start_report = _relax_report(rep)
    finally:
        _lib.afv_protocol_delete(pr)
        _lib.afv_relax_report_delete(rep)
    return sim


# ---- trajectories -----------------------------------------------------------
class Trajectory(object):
    """The frames of a run: n (cells), box (None or (Lx, Ly)), steps and
    times (one per frame), positions (frames x N x 2, unwrapped centres)
    and angles (frames x N).  Arrays with numpy, else nested lists."""

    def __init__(self, handle):
        self._tr = handle
        self.n = _lib.afv_traj_n(handle)
        self.nframes = _lib.afv_traj_nframes(handle)
        b = _lib.afv_traj_box(handle).contents
        self.box = (b.Lx, b.Ly) if b.periodic else None
        steps = _lib.afv_traj_steps(handle)
        self.steps = [int(steps[k]) for k in range(self.nframes)]
        self.times = _out(_lib.afv_traj_times(handle), self.nframes)
        self.positions = _per_frame(_lib.afv_traj_positions(handle),
                                    self.nframes, self.n, 2)
        self.angles = _per_frame(_lib.afv_traj_angles(handle), self.nframes,
                                 self.n, 1)

    def __len__(self):
        return self.nframes

    def __repr__(self):
        return "Trajectory(n=%d, frames=%d, box=%r)" % (self.n, self.nframes,
                                                        self.box)

    def __del__(self):
        if getattr(self, "_tr", None):
            _lib.afv_traj_delete(self._tr)
            self._tr = None


def _per_frame(ptr, nframes, n, width):
    """nframes frames of n rows of width values from a C pointer: an
    (nframes, n, width) array (width 1: (nframes, n)), or nested lists."""
    count = nframes * n * width
    if _np is not None:
        a = _np.ctypeslib.as_array(ptr, (count,)).copy() if count else \
            _np.zeros(0, dtype=_np.float64)
        return a.reshape((nframes, n, width) if width > 1 else (nframes, n))
    values = ptr[:count] if count else []
    if width == 1:
        return [values[k * n:(k + 1) * n] for k in range(nframes)]
    return [[values[(k * n + i) * width:(k * n + i + 1) * width]
             for i in range(n)] for k in range(nframes)]


def read_trajectory(path):
    """Every complete frame of a trajectory file: afv run's trajectory.dat
    (format 2) or the text format of earlier versions (format 1); a
    Trajectory.  AfvError (with the file's line or frame) if it cannot be
    read."""
    tr = _lib.afv_traj_new()
    if not tr:
        raise MemoryError("afv_traj_new")
    err = C.create_string_buffer(512)
    st = _lib.afv_traj_read(os.fsencode(path), tr, err, len(err))
    if st != 0:
        _lib.afv_traj_delete(tr)
        raise AfvError(st, err.value.decode(errors="replace") or str(path))
    return Trajectory(tr)


def trajectory(positions, times, box=None, steps=None, angles=None):
    """A Trajectory from arrays: positions (frames x N x 2), times (one per
    frame), box (None or (Lx, Ly)), steps (default 0, 1, ...) and angles
    (frames x N, default zeros); for analyze() and msd()."""
    nframes = len(times)
    r = _Doubles(positions, what="positions")
    if nframes == 0 or r.size % (2 * nframes):
        raise ValueError("trajectory: %d numbers of positions do not make %d "
                         "frames of N x 2" % (r.size, nframes))
    n = r.size // (2 * nframes)
    t = _Doubles(times, nframes, "times")
    th = _Doubles(angles, n * nframes, "angles") if angles is not None \
        else None
    st = (C.c_longlong * max(nframes, 1))(*[int(k) for k in steps]) \
        if steps is not None else None
    if steps is not None and len(steps) != nframes:
        raise ValueError("trajectory: %d steps for %d frames" % (len(steps),
                                                                 nframes))
    b = _box(box)
    tr = _lib.afv_traj_new()
    if not tr:
        raise MemoryError("afv_traj_new")
    status = _lib.afv_traj_set(tr, n, nframes, C.byref(b),
                               C.cast(st, _LP) if st is not None else None,
                               t.ptr, r.ptr, th.ptr if th else None)
    if status != 0:
        _lib.afv_traj_delete(tr)
        raise AfvError(status, "trajectory")
    return Trajectory(tr)


def _as_trajectory(frames, times, box, unwrap):
    """frames: a Trajectory, or positions with times and box; unwrapped
    (minimum image between frames) if unwrap: for wrapped positions."""
    if not isinstance(frames, Trajectory):
        if times is None:
            raise ValueError("positions need times (one per frame)")
        frames = trajectory(frames, times, box)
    elif unwrap:                    # never change the caller's Trajectory
        frames = trajectory(frames.positions, frames.times, frames.box,
                            frames.steps)
    if unwrap:
        _lib.afv_traj_unwrap(frames._tr)
    return frames


# ---- run analysis ------------------------------------------------------------
class MSD(object):
    """Mean-squared displacements on log-spaced lags: lag (in time), msd
    (plain), msd_rel (relative to the contacting neighbours at the time
    origin)."""

    def __repr__(self):
        return "MSD(%d lags)" % len(self.lag)


def _series(get, handle, name):
    """The series `name` of a C afv_msd or afv_analysis (empty if none)."""
    count = C.c_int()
    ptr = get(handle, name.encode(), C.byref(count))
    if ptr and count.value:
        return _out(ptr, count.value)
    return _np.zeros(0) if _np is not None else []


def msd(frames, times=None, box=None, first=0, l=1.0, unwrap=False):
    """The MSD of a Trajectory, or of positions (frames x N x 2) at times,
    over the time origins first .. frames-2 (afv_msd_compute; frames
    equally spaced in time, unwrapped: unwrap=True unwraps positions
    wrapped into a periodic box).  Returns an MSD."""
    tr = _as_trajectory(frames, times, box, unwrap)
    m = _lib.afv_msd_new()
    if not m:
        raise MemoryError("afv_msd_new")
    try:
        _check(_lib.afv_msd_compute(m, tr._tr, int(first), float(l)), "msd")
        out = MSD()
        for name in ("lag", "msd", "msd_rel"):
            setattr(out, name, _series(_lib.afv_msd_series, m, name))
        return out
    finally:
        _lib.afv_msd_delete(m)


class Analysis(object):
    """What `afv analyze` reports, under the names of its files: the
    numbers of summary.txt (cells, frames, first: the first steady frame,
    ngc_frac_mean, ngc_frac_sd, n_clusters_mean, n_clusters_sd,
    omega_mean, omega_sd, t1_final, D_s, D_s_lag, D_s_origins, D_s_plain,
    D_0, D_eff, tau_NGC, tau_NGC_reliable, t1_rate, msd_beta), the series of
    series.csv (time, ngc_frac, n_clusters, omega, t1: one per frame), of
    msd.csv (lag, msd, msd_rel) and of csd.csv (csd: p(s), s = 1..N)."""

    def __repr__(self):
        return "Analysis(frames=%d, ngc_frac_mean=%r, D_eff=%r)" % (
            self.frames, self.ngc_frac_mean, self.D_eff)


_ANALYSIS_NUMBERS = ("cells", "frames", "first", "ngc_frac_mean",
                     "ngc_frac_sd", "n_clusters_mean", "n_clusters_sd",
                     "omega_mean", "omega_sd", "t1_final", "D_s", "D_s_lag",
                     "D_s_origins", "D_s_plain", "D_0", "D_eff", "tau_NGC",
                     "tau_NGC_reliable", "t1_rate", "msd_beta")
_ANALYSIS_INTS = ("cells", "frames", "first", "D_s_origins",
                  "tau_NGC_reliable")
_ANALYSIS_SERIES = ("time", "ngc_frac", "n_clusters", "omega", "t1", "lag",
                    "msd", "msd_rel", "csd")


def analyze(frames, times=None, box=None, l=1.0, v0=0.5, Dr=0.1,
            steady_from=0.0, lag=5000.0, unwrap=False):
    """`afv analyze` on a Trajectory (read_trajectory, trajectory()) or on
    positions (frames x N x 2) at times in box: the order parameters
    N_GC/N, the number of clusters and Omega at every frame and their
    means over the steady frames (time >= steady_from), T1, the MSD of
    the steady frames, D_s at the computed lag nearest to `lag`, D_eff =
    D_s / D_0 with D_0 = v0^2 / (2 Dr), tau_NGC, msd_beta.  l, v0 and Dr
    are the run's (afv analyze reads them from params.txt).  The numbers
    are afv_analyze's, the same bits as afv analyze's.  Returns an
    Analysis."""
    tr = _as_trajectory(frames, times, box, unwrap)
    a = _lib.afv_analysis_new()
    if not a:
        raise MemoryError("afv_analysis_new")
    try:
        _check(_lib.afv_analyze(a, tr._tr, float(l), float(v0), float(Dr),
                                float(steady_from), float(lag)), "analyze")
        out, v = Analysis(), C.c_double()
        for name in _ANALYSIS_NUMBERS:
            _check(_lib.afv_analysis_get(a, name.encode(), C.byref(v)), name)
            setattr(out, name, int(v.value) if name in _ANALYSIS_INTS
                    else v.value)
        for name in _ANALYSIS_SERIES:
            setattr(out, name, _series(_lib.afv_analysis_series, a, name))
        return out
    finally:
        _lib.afv_analysis_delete(a)
