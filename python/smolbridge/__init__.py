"""smolbridge: Python access to libsmolbridge (ctypes, numpy).

The reference functions keep their C names without the ``sb_`` prefix and
are vectorised over numpy arrays (broadcasting)::

    import smolbridge as sb
    sb.bb_cross_prob(2.0, 3.0, 1.0, 4.0)           # exp(-1)
    sb.bes3b_cross_prob(x, y, 1.0, v)              # arrays broadcast

A scalar call with a bad argument raises ValueError with the library's
message; an array call returns NaN where the arguments are bad.

``pbe(...)`` integrates the Smoluchowski population balance (CVODE) and
returns numpy arrays; ``collide(config)`` runs the collision engine from a
dict shaped like the INI file (through the library's run description,
<smolbridge/collide.h>, so that the checks and messages are those of
``smolbridge collide``) and returns the summary and the time series.
Theory and units: the user guide (docs/), the Python chapter
docs/python.md.
"""
import ctypes as _ct
import json as _json
import os as _os
import shutil as _shutil
import tempfile as _tempfile
import warnings as _warnings

import numpy as _np

try:  # written by `make` (installed and build-tree locations)
    from . import _paths
except ImportError:  # pragma: no cover
    _paths = None

__all__ = ["pbe", "collide", "CollideError", "CollideWarning",
           "library_version"]


def _load():
    names = []
    if _os.environ.get("SMOLBRIDGE_LIB"):
        names.append(_os.environ["SMOLBRIDGE_LIB"])
    if _paths is not None:
        names.append(_os.path.join(_paths.LIBDIR, "libsmolbridge.so"))
    names.append("libsmolbridge.so")
    err = None
    for n in names:
        try:
            return _ct.CDLL(n)
        except OSError as e:
            err = e
    raise ImportError("smolbridge: cannot load libsmolbridge.so (%s); set "
                      "SMOLBRIDGE_LIB to its path" % err)


_lib = _load()
_lib.sb_last_error.restype = _ct.c_char_p
_lib.sb_last_status.restype = _ct.c_int
_lib.sb_version.restype = _ct.c_char_p


def library_version():
    """Version of the loaded libsmolbridge."""
    return _lib.sb_version().decode()


def _message():
    return _lib.sb_last_error().decode(errors="replace")


# Plain double functions: C name without sb_ -> argument names (C order).
_FUNCS = {
    "bb_cross_prob": "x y a v", "bb_cross_logprob": "x y a v",
    "bb_nocross_prob": "x y a v", "bes3b_cross_prob": "x y a v",
    "bes3b_cross_logprob": "x y a v", "bes3b_nocross_prob": "x y a v",
    "bb_hit_pdf": "u x y a sigma2 t", "bb_hit_cdf": "u x y a sigma2 t",
    "bb_hit_sf": "u x y a sigma2 t", "bb_hit_quantile": "p x y a sigma2 t",
    "bes3b_hit_pdf": "u x y a sigma2 t", "bes3b_hit_cdf": "u x y a sigma2 t",
    "bes3b_hit_sf": "u x y a sigma2 t",
    "bes3b_hit_quantile": "p x y a sigma2 t",
    "bm_fpt_pdf": "t x a mu sigma2", "bm_fpt_cdf": "t x a mu sigma2",
    "bm_fpt_sf": "t x a mu sigma2", "bm_fpt_mass": "x a mu sigma2",
    "bm_fpt_logmass": "x a mu sigma2", "bm_fpt_quantile": "p x a mu sigma2",
    "bes3_fpt_pdf": "t x a sigma2", "bes3_fpt_cdf": "t x a sigma2",
    "bes3_fpt_sf": "t x a sigma2",
    "langevin_var_x": "tau B t", "langevin_var_u": "tau B t",
    "langevin_cov_xu": "tau B t", "langevin_var_x_cond": "tau B t",
    "langevin_var_stat": "tau B", "langevin_msd": "tau B t",
    "langevin_msd_ballistic": "tau B t", "langevin_msd_diffusive": "tau B t",
    "langevin_vacf": "tau B t",
    "stokes_tau": "rho_p d_p mu_f cc", "sphere_mass": "rho_p d_p",
    "brownian_B": "T m_p tau_p", "einstein_D": "T mu_f d_p cc",
    "knudsen": "lambda d_p", "cunningham": "kn",
    "cunningham_gen": "kn A1 A2 A3",
    "kolmogorov_time": "eps nu", "kolmogorov_length": "eps nu",
    "stokes_number": "tau_p tau_f", "particle_reynolds": "d_p w nu_f",
    "collision_speed": "u2", "wunsch_dt": "d_p u2 frac",
    "wunsch_dt_brownian": "d_p rho_p T frac",
    "kernel_brownian_co": "r_i r_j T mu",
    "kernel_brownian_fm": "r_i r_j T rho_p",
    "kernel_brownian_tr": "r_i r_j T mu rho_p lambda",
    "kernel_brownian_gh": "r_i r_j m_i m_j tau_i tau_j T",
    "kernel_brownian_gh_kn": "r_i r_j m_i m_j tau_i tau_j T",
    "kernel_gh_H": "kn", "kernel_kinetic": "d_i d_j m_i m_j T",
    "kernel_gravity": "r_i r_j rho_p rho_f mu g",
    "kernel_shear": "r_i r_j G", "kernel_saffman_turner": "r_i r_j eps nu",
    "kernel_abrahamson": "r_i r_j u2_i u2_j",
    "kernel_shear_langevin": "r_i r_j u2 tau G",
    "kernel_diffusion": "r_i r_j b2_i b2_j", "brownian_b2": "r T mu",
    "turb_pair_b2": "r eps nu",
    "kernel_brownian_turb": "r_i r_j T mu eps nu",
    "kernel_constant": "v_i v_j K", "kernel_additive": "v_i v_j K",
    "kernel_multiplicative": "v_i v_j K",
    "pbe_const_mono_n": "k tau", "pbe_const_mono_logn": "k tau",
    "pbe_add_mono_n": "k tau", "pbe_add_mono_logn": "k tau",
    "pbe_mult_mono_n": "k tau", "pbe_mult_mono_logn": "k tau",
    "pbe_const_exp_n": "x tau", "pbe_const_exp_logn": "x tau",
    "pbe_add_exp_n": "x tau", "pbe_add_exp_logn": "x tau",
    "dlvo_debye_kappa": "n0 z eps_r T",
}


def _wrap(name, args):
    cf = getattr(_lib, "sb_" + name)
    cf.restype = _ct.c_double
    cf.argtypes = [_ct.c_double] * len(args)

    def f(*a):
        if len(a) != len(args):
            raise TypeError("%s(%s) takes %d arguments, %d given"
                            % (name, ", ".join(args), len(args), len(a)))
        if all(_np.ndim(x) == 0 for x in a):
            _lib.sb_clear_error()
            r = cf(*[float(x) for x in a])
            if _np.isnan(r) and _lib.sb_last_status() != 0:
                raise ValueError("%s(%s): %s" % (
                    name, ", ".join("%s=%r" % p for p in zip(args, a)),
                    _message()))
            return r
        b = _np.broadcast_arrays(*[_np.asarray(x, dtype=float) for x in a])
        out = _np.empty(b[0].shape)
        flat = [x.ravel() for x in b]
        o = out.ravel()
        for i in range(o.size):
            o[i] = cf(*[x[i] for x in flat])
        return out

    f.__name__ = name
    f.__doc__ = ("sb_%s(%s), vectorised over numpy arrays; see the user "
                 "guide for its definition, domain and accuracy."
                 % (name, ", ".join(args)))
    return f


for _n, _a in _FUNCS.items():
    globals()[_n] = _wrap(_n, _a.split())
    __all__.append(_n)

# ------------------------------------------------------------------ pbe


# sb_kernel_spec is only filled and read by the library (init, set,
# check, fn): an opaque, generously sized and aligned buffer keeps this
# module independent of its layout.
def _KernelSpec():
    return (_ct.c_double * 64)()


_OUTFN = _ct.CFUNCTYPE(_ct.c_int, _ct.c_double, _ct.POINTER(_ct.c_double),
                       _ct.POINTER(_ct.c_double), _ct.c_size_t,
                       _ct.POINTER(_ct.c_double), _ct.c_void_p)


class _PbeConfig(_ct.Structure):
    _fields_ = [("method", _ct.c_int), ("nsizes", _ct.c_size_t),
                ("v1", _ct.c_double), ("ratio", _ct.c_double),
                ("kernel", _ct.c_void_p), ("kparams", _ct.c_void_p),
                ("rtol", _ct.c_double), ("atol", _ct.c_double),
                ("linsol", _ct.c_int), ("max_steps", _ct.c_long),
                ("source", _ct.c_void_p), ("sparams", _ct.c_void_p),
                ("removal", _ct.c_void_p), ("rparams", _ct.c_void_p),
                ("tail", _ct.c_int), ("gain", _ct.c_int)]


_lib.sb_pbe_alloc.restype = _ct.c_void_p
_lib.sb_pbe_alloc.argtypes = [_ct.POINTER(_PbeConfig)]
_lib.sb_pbe_free.argtypes = [_ct.c_void_p]
_lib.sb_pbe_init_mono.argtypes = [_ct.c_void_p, _ct.c_double]
_lib.sb_pbe_init_exp.argtypes = [_ct.c_void_p, _ct.c_double, _ct.c_double]
_lib.sb_pbe_solve.argtypes = [_ct.c_void_p, _ct.POINTER(_ct.c_double),
                              _ct.c_size_t, _OUTFN, _ct.c_void_p,
                              _ct.c_void_p]
_lib.sb_pbe_tail.argtypes = [_ct.c_void_p, _ct.POINTER(_ct.c_double),
                             _ct.POINTER(_ct.c_double)]
_lib.sb_pbe_state_moments.argtypes = [_ct.c_void_p, _ct.POINTER(_ct.c_double)]
_lib.sb_kernel_type_from_name.argtypes = [_ct.c_char_p,
                                          _ct.POINTER(_ct.c_int)]
_lib.sb_kernel_spec_init.argtypes = [_ct.c_void_p, _ct.c_int]
_lib.sb_kernel_spec_set.argtypes = [_ct.c_void_p, _ct.c_char_p,
                                    _ct.c_double]
_lib.sb_kernel_spec_check.argtypes = [_ct.c_void_p]


def pbe(kernel, n0, times, sizes=100, method="discrete", init="mono", v1=1.0,
        v0=None, ratio=None, rtol=1e-8, atol=0.0, **params):
    """Integrate the Smoluchowski population balance (CVODE).

    kernel: a name of ``smolbridge pbe --help`` ("constant", "additive",
    "multiplicative", "brownian-co", ...) with its parameters as keywords
    (SI units; ``lambda`` as ``lambda_``).  Returns a dict of numpy arrays:
    ``t`` (nt), ``v`` (nbins), ``n`` (nt x nbins), ``moments`` (nt x 3:
    M0, M1, M2 with the lumped tail), ``tail_n`` and ``tail_M1`` (nt: the
    number and mass of the sizes above the largest, discrete method).
    """
    if method not in ("discrete", "sectional"):
        raise ValueError("pbe: method = %r: valid: 'discrete', 'sectional'"
                         % (method,))
    if init not in ("mono", "exp"):
        raise ValueError("pbe: init = %r: valid: 'mono', 'exp'" % (init,))
    if (isinstance(sizes, bool) or not float(sizes).is_integer()
            or not 2 <= sizes <= 1e6):
        raise ValueError("pbe: sizes = %r: valid: a whole number from 2 to "
                         "1e6" % (sizes,))
    sizes = int(sizes)
    if ratio is not None and not float(ratio) > 1:
        raise ValueError("pbe: ratio = %r: valid: > 1 (sectional)"
                         % (ratio,))
    times = _np.atleast_1d(_np.asarray(times, dtype=float))
    if times.ndim != 1 or len(times) == 0:
        raise ValueError("pbe: times: give one or more output times")
    spec = _KernelSpec()
    kt = _ct.c_int()
    if _lib.sb_kernel_type_from_name(kernel.encode(), _ct.byref(kt)):
        raise ValueError("pbe: %s" % _message())
    _lib.sb_kernel_spec_init(spec, kt)
    for k, x in params.items():
        key = "lambda" if k == "lambda_" else k
        if _lib.sb_kernel_spec_set(spec, key.encode(), float(x)):
            raise ValueError("pbe: %s" % _message())
    if _lib.sb_kernel_spec_check(spec):
        raise ValueError("pbe: %s" % _message())
    cfg = _PbeConfig()
    _lib.sb_pbe_config_init(_ct.byref(cfg))
    cfg.method = {"discrete": 0, "sectional": 1}[method]
    cfg.nsizes = int(sizes)
    cfg.v1 = float(v1)
    if method == "sectional":
        cfg.ratio = (float(ratio) if ratio is not None
                     else 10.0 ** (12.0 / (sizes - 1)))
    cfg.kernel = _ct.cast(_lib.sb_kernel_spec_fn, _ct.c_void_p)
    cfg.kparams = _ct.cast(spec, _ct.c_void_p)
    cfg.rtol = float(rtol)
    cfg.atol = float(atol)
    p = _lib.sb_pbe_alloc(_ct.byref(cfg))
    if not p:
        raise ValueError("pbe: %s" % _message())
    try:
        if init == "mono":
            st = _lib.sb_pbe_init_mono(p, float(n0))
        else:
            if v0 is None:
                v0 = (1e4 if method == "sectional" else 10.0) * v1
            st = _lib.sb_pbe_init_exp(p, float(n0), float(v0))
        if st:
            raise ValueError("pbe: %s" % _message())
        # multiplicative kernel: M2 = M2(0)/(1 - K M2(0) t) for any start,
        # an infinite cluster at t = 1/(K M2(0)); no mass-conserving
        # solution beyond it (as smolbridge pbe)
        if kernel == "multiplicative":
            m0 = (_ct.c_double * 3)()
            _lib.sb_pbe_state_moments(p, m0)
            tgel = 1.0 / (float(params.get("K", 1.0)) * m0[2])
            if times.max() >= tgel:
                raise ValueError(
                    "pbe: gelation at t = 1/(K M2(0)) = %g: the population "
                    "balance has no mass-conserving solution beyond it "
                    "(post-gel models are not implemented); give times "
                    "before it" % tgel)
        rows = []
        broke = []

        def out(t, v, n, nb, m, data):
            tn, tm = _ct.c_double(), _ct.c_double()
            _lib.sb_pbe_tail(p, _ct.byref(tn), _ct.byref(tm))
            nk = _np.ctypeslib.as_array(n, (nb,)).copy()
            # a negative concentration: the model broke down (gelation)
            nmin = min(nk.min(), tn.value)
            if nmin < -1e-9 * m[0] or not m[0] > 0:
                broke.append("at t = %g the solution has a negative number "
                             "concentration (min %g, M0 = %g): the "
                             "population balance broke down (gelation)"
                             % (t, nmin, m[0]))
                return 1
            rows.append((t, _np.ctypeslib.as_array(v, (nb,)).copy(), nk,
                         [m[0], m[1], m[2]], tn.value, tm.value))
            return 0

        cb = _OUTFN(out)
        arr = (_ct.c_double * len(times))(*times)
        st = _lib.sb_pbe_solve(p, arr, len(times), cb, None, None)
        if broke:
            raise RuntimeError("pbe: %s" % broke[0])
        if st:
            raise RuntimeError("pbe: %s" % _message())
    finally:
        _lib.sb_pbe_free(p)
    return {"t": _np.array([r[0] for r in rows]), "v": rows[0][1],
            "n": _np.array([r[2] for r in rows]),
            "moments": _np.array([r[3] for r in rows]),
            "tail_n": _np.array([r[4] for r in rows]),
            "tail_M1": _np.array([r[5] for r in rows])}


# -------------------------------------------------------------- collide

class CollideError(RuntimeError):
    """A failed engine run: .status is 2 for an input error (the
    configuration, the output directory) and 1 for a failed run or outputs
    that could not be written (the exit status of `smolbridge collide`);
    str() is the library's message."""

    def __init__(self, status, message):
        RuntimeError.__init__(self, message)
        self.status = status


class CollideWarning(UserWarning):
    """A key without effect, or collision events a run dropped."""


class _Progress(_ct.Structure):  # sb_collide_progress
    _fields_ = [("event", _ct.c_int), ("t", _ct.c_double),
                ("t_begin", _ct.c_double), ("t_measure", _ct.c_double),
                ("t_end", _ct.c_double), ("dt", _ct.c_double),
                ("fraction", _ct.c_double), ("particles", _ct.c_size_t),
                ("collisions", _ct.c_ulonglong),
                ("first_contacts", _ct.c_longlong)]


_PROGRESSFN = _ct.CFUNCTYPE(_ct.c_int, _ct.POINTER(_Progress), _ct.c_void_p)
_lib.sb_collide_alloc.restype = _ct.c_void_p
_lib.sb_collide_alloc.argtypes = []
_lib.sb_collide_free.argtypes = [_ct.c_void_p]
_lib.sb_collide_read_string.argtypes = [_ct.c_void_p, _ct.c_char_p,
                                        _ct.c_char_p]
_lib.sb_collide_set.argtypes = [_ct.c_void_p, _ct.c_char_p]
_lib.sb_collide_check.argtypes = [_ct.c_void_p]
_lib.sb_collide_run.argtypes = [_ct.c_void_p, _PROGRESSFN, _ct.c_void_p]
_lib.sb_collide_failed.argtypes = [_ct.c_void_p]
_lib.sb_collide_error.restype = _ct.c_char_p
_lib.sb_collide_error.argtypes = [_ct.c_void_p]
_lib.sb_collide_nwarnings.restype = _ct.c_size_t
_lib.sb_collide_nwarnings.argtypes = [_ct.c_void_p]
_lib.sb_collide_warning.restype = _ct.c_char_p
_lib.sb_collide_warning.argtypes = [_ct.c_void_p, _ct.c_size_t]
_COLLIDE_EWRITE = 3  # sb_collide_failure: exits with 1, as a run error
_EVENTS = {0: "begin", 1: "step"}


def _ini(config):
    lines = []
    for sec, keys in config.items():
        lines.append("[%s]" % sec)
        for k, v in keys.items():
            # repeatable keys: a list of lists gives one line each
            rep = k in ("particle", "region") and \
                isinstance(v, (list, tuple)) and len(v) > 0 and \
                isinstance(v[0], (list, tuple, _np.ndarray))
            vals = v if rep else [v]
            for x in vals:
                if isinstance(x, (list, tuple, _np.ndarray)):
                    x = " ".join(repr(float(y)) for y in x)
                elif isinstance(x, bool):
                    x = "yes" if x else "no"
                elif isinstance(x, float):
                    x = repr(x)
                lines.append("%s = %s" % (k, x))
        lines.append("")
    return "\n".join(lines)


def collide(config, output=None, sets=(), progress=None):
    """Run the collision engine from a dict shaped like the INI file:
    ``{"run": {"L": 1e-5, ...}, "species colloid": {"radius": 1e-7, ...}}``
    (values: numbers, strings, lists for vectors; ``particle`` and
    ``[observe] region`` may be lists of lists: one line each).  ``sets``: extra "SECTION.KEY=VALUE" overrides.
    The outputs go to ``output`` (default: a temporary directory, removed
    afterwards).  ``progress`` (optional) is called with a dict (``event``
    "begin" or "step", ``t``, ``t_begin``, ``t_measure``, ``t_end``,
    ``dt`` in s, ``fraction`` of the current stretch, ``particles``,
    ``collisions``, ``first_contacts``: the first contacts counted after
    the warm-up with ``[observe] first_hit``, -1 without it) about every
    tenth of the run; a true return value or
    an exception stops the run.  Keys without effect give CollideWarning.
    Returns ``(summary, series)``: the summary.json dict and the series.csv
    columns as a dict of numpy arrays (pandas.DataFrame(series) makes a
    table).  Raises CollideError with the library's message ("config:LINE:
    ..." for the INI text built from the dict, one line per key in the
    dict's order)."""
    tmp = _tempfile.mkdtemp(prefix="smolbridge-")
    c = None
    raised = []

    def relay(p, user):
        if progress is None:
            return 0
        q = p.contents
        info = {n: getattr(q, n) for n, _ in _Progress._fields_}
        info["event"] = _EVENTS.get(q.event, q.event)
        try:
            return 1 if progress(info) else 0
        except BaseException as e:  # re-raised after the run
            raised.append(e)
            return 1

    try:
        cfg = {s: dict(k) for s, k in config.items()}
        out = output or _os.path.join(tmp, "out")
        cfg.setdefault("run", {})["output"] = out
        c = _lib.sb_collide_alloc()
        if not c:
            raise MemoryError("collide: %s" % _message())
        st = _lib.sb_collide_read_string(c, _ini(cfg).encode(), b"config")
        for s in sets:
            if not st:
                st = _lib.sb_collide_set(c, s.encode())
        if not st:
            st = _lib.sb_collide_run(c, _PROGRESSFN(relay), None)
        for i in range(_lib.sb_collide_nwarnings(c)):
            _warnings.warn(_lib.sb_collide_warning(c, i).decode(
                errors="replace"), CollideWarning, stacklevel=2)
        if raised:
            raise raised[0]
        if st:
            kind = _lib.sb_collide_failed(c)
            raise CollideError(1 if kind == _COLLIDE_EWRITE else kind,
                               _lib.sb_collide_error(c).decode(
                                   errors="replace"))
        with open(_os.path.join(out, "summary.json")) as f:
            summary = _json.load(f)
        data = _np.genfromtxt(_os.path.join(out, "series.csv"),
                              delimiter=",", names=True, ndmin=1)
        series = {n: _np.asarray(data[n]) for n in data.dtype.names}
        return summary, series
    finally:
        if c:
            _lib.sb_collide_free(c)
        _shutil.rmtree(tmp, ignore_errors=True)
