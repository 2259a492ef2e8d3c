"""The Python face of the C ABI: Surface, Metric, Mesh, Options, Quality, RunStats, AnitetError,
mesh_surface, build_layers and bl_first_height (geographic frames: _geo.py); and for 2D meshes
Pslg, Mesh2d and mesh2d().

Arrays: with NumPy importable (and ANITET_PYTHON_NUMPY not "0"), outputs are NumPy arrays shaped
(n, 3) / (n, 4) / (n,) and inputs may be any array-like; without it, outputs are lists of tuples
(lists for one value per element) and inputs are sequences. Indices are 0-based unless an
index_base of 1 is asked for.
"""
import collections.abc
import ctypes
import json
import os
from ctypes import byref, c_double, c_int32, c_int64, c_void_p

from . import _capi
from ._capi import lib

if os.environ.get("ANITET_PYTHON_NUMPY", "1") != "0":
    try:
        import numpy as _np
    except ImportError:  # numpy is optional
        _np = None
else:
    _np = None

HAVE_NUMPY = _np is not None


class AnitetError(Exception):
    """A failed call: code (an ERR_* value), name ("open_boundary") and the library's message."""

    def __init__(self, code, message):
        self.code = code
        self.name = lib.anitet_error_name(code).decode()
        self.message = message
        super().__init__("%s (%s, %d)" % (message, self.name, code))


def _check(rc):
    if rc != _capi.OK:
        raise AnitetError(rc, lib.anitet_last_error_message().decode("utf-8", "replace"))


def version():
    """The library's version, "major.minor.patch"."""
    return lib.anitet_version().decode()


def version_number():
    return lib.anitet_version_number()


def error_name(code):
    return lib.anitet_error_name(code).decode()


# ---- arrays ------------------------------------------------------------------------------------

def _flat_input(data, width, ctype, what):
    """(keep-alive object, pointer, number of rows) of rows of `width` values of ctype."""
    if _np is not None:
        dtype = _np.float64 if ctype is c_double else _np.int32
        given = _np.asarray(data)
        if ctype is c_int32:
            if given.size and given.dtype.kind not in "iu":
                raise TypeError("%s: integer values expected, got %s" % (what, given.dtype))
            if given.size and (given.min() < -2**31 or given.max() >= 2**31):
                raise ValueError("%s: values out of the int32 range" % what)
        arr = _np.ascontiguousarray(given, dtype=dtype)
        if arr.size % width != 0 or (arr.ndim == 2 and arr.shape[1] != width) or arr.ndim > 2:
            raise ValueError("%s: shape %s is not (n, %d)" % (what, arr.shape, width))
        return arr, arr.ctypes.data_as(ctypes.POINTER(ctype)), arr.size // width
    flat = []
    for row in data:
        if width == 1 and not isinstance(row, (list, tuple)):
            flat.append(row)
            continue
        if len(row) != width:
            raise ValueError("%s: a row has %d values, %d expected" % (what, len(row), width))
        flat.extend(row)
    if ctype is c_int32:
        for v in flat:
            if not isinstance(v, int):
                raise TypeError("%s: integer values expected, got %r" % (what, v))
            if v < -2**31 or v >= 2**31:
                raise ValueError("%s: value %d out of the int32 range" % (what, v))
    buf = (ctype * len(flat))(*flat)
    return buf, ctypes.cast(buf, ctypes.POINTER(ctype)), len(flat) // width


def _flat_doubles(values):
    """(keep-alive object, pointer, count) of all the values, rows flattened."""
    if _np is not None:
        arr = _np.ascontiguousarray(values, dtype=_np.float64).ravel()
        return arr, arr.ctypes.data_as(ctypes.POINTER(c_double)), arr.size
    flat = []
    for row in values:
        if hasattr(row, "__len__"):
            flat.extend(row)
        else:
            flat.append(row)
    buf = (c_double * len(flat))(*flat)
    return buf, ctypes.cast(buf, ctypes.POINTER(c_double)), len(flat)


def _output(rows, width, ctype, fill):
    """Calls fill(pointer, length) on a new buffer of rows x width values and returns it."""
    n = rows * width
    if _np is not None:
        arr = _np.empty((rows, width) if width > 1 else (rows,),
                        dtype=_np.float64 if ctype is c_double else _np.int32)
        _check(fill(arr.ctypes.data_as(ctypes.POINTER(ctype)), n))
        return arr
    buf = (ctype * max(n, 1))()
    _check(fill(ctypes.cast(buf, ctypes.POINTER(ctype)), n))
    if width == 1:
        return list(buf[:n])
    return [tuple(buf[i:i + width]) for i in range(0, n, width)]


def _text(query):
    """A JSON text through the size-query-then-fill convention."""
    needed = c_int64(0)
    _check(query(None, 0, byref(needed)))
    buf = ctypes.create_string_buffer(needed.value)
    _check(query(buf, needed.value, None))
    return buf.value.decode("utf-8")


def _path(p):
    return os.fsencode(p)


def _base(index_base):
    if index_base not in (0, 1):
        raise ValueError("index_base must be 0 or 1")
    return index_base


def _require(value, cls, what):
    """TypeError unless value is a cls (a handle of the wrong kind would reach C)."""
    if not isinstance(value, cls):
        raise TypeError("%s must be an anitet.%s, not %s" % (what, cls.__name__, type(value).__name__))


# ---- handles -----------------------------------------------------------------------------------

class _Handle:
    """Owns one C handle; close() (or the end of a with block, or garbage collection) frees it."""

    _destroy = None

    def __init__(self, ptr):
        self._ptr = ptr

    @property
    def _as_parameter_(self):
        # A closed handle is NULL to the library: its calls fail with ERR_INVALID_ARGUMENT.
        return self._ptr

    def close(self):
        if getattr(self, "_ptr", None):
            type(self)._destroy(self._ptr)
            self._ptr = None

    def __del__(self):
        try:
            self.close()
        except Exception:  # interpreter shutdown: the library may be gone already
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _create(cls, call, *args):
    out = c_void_p()
    _check(call(*args, byref(out)))
    return cls(out.value)


# ---- options -----------------------------------------------------------------------------------

class Options:
    """The mesher's and the validation's options (anitet_options version 5; the fields, their
    meaning and their defaults are the C struct's, with booleans for the 0/1 ones).

    progress(stage, fraction): called on entering each stage; return False to cancel (the call
    then raises AnitetError with code ERR_CANCELLED); None or True continues. An exception raised
    in progress or log cancels the run and is raised again from the call.
    log(level, message): the validation's repairs and problems, one line per stage.

    Version 3, keywords only: hmin, hmax, hgrad (size bounds and gradation, 0: none), max_tets (0:
    no cap), recovery (RECOVERY_ALL, RECOVERY_SPLIT, RECOVERY_FUZZY), retry_layer_counts,
    attempts_seconds, anisotropic_cycles, and the boundary layer: bl_patches, the wall patch labels
    (a sequence of ints or one int; an int32 NumPy array is passed without a copy), with
    bl_first_height (needed with walls; bl_first_height() gives it for a y+), bl_growth, bl_layers,
    bl_sizing and bl_mitre (`anitet mesh --bl-mitre`, needs bl_patches: at the walls' edges and
    corners each column lengthened by 1/cos of its angle to the farthest wall normal, at most 2,
    so that the layers keep their thickness across every wall; Mesh.write_bl_columns() shows the
    columns); push_tasks_min_vertices (stage 1 pushes a layer of at least this many front
    vertices on two tasks, 0: one by one; the same mesh either way).

    Version 4: bl_slide_patches, the patch labels the walls meet that the layers' columns may
    slide along (a pipe's inlet and outlet, a symmetry plane; `anitet mesh --bl-slide-patches`),
    as bl_patches. Those patches are triangulated again where the layers slide on them.
    bl_cells: "tets" (BL_CELLS_TETS, the default) or "prisms" (BL_CELLS_PRISMS; `anitet mesh
    --bl-cells prisms`, needs bl_patches): Mesh.write() writes each boundary-layer prism as one
    prism cell instead of its 3 tets, to .vtu and OpenFOAM polyMesh only (another format raises
    ERR_UNSUPPORTED_FORMAT); the mesh keeps its tets (Mesh.prisms(), Mesh.tet_prisms()).

    Version 5: bl_sizing_growth (`anitet mesh --bl-sizing-growth`, needs bl_sizing): above the
    layers' top the normal size grows at this rate instead of bl_growth, so the interior reaches
    its own sizes in fewer tets (1.3 is a good start); 0, the default: bl_growth. Otherwise at
    least bl_growth (ERR_INVALID_ARGUMENT if not).
    """

    def __init__(self, num_threads=0, merge_duplicate_vertices=True, orient_shells=True,
                 check_self_intersections=True, layers=1, layer_scheme=_capi.LAYERS_PUSH,
                 recovery_max_seconds=0.0, refine=True, optimize=True, size_scale=1.0,
                 progress=None, log=None, *, attempts_seconds=240.0, retry_layer_counts=True,
                 recovery=_capi.RECOVERY_ALL, hmin=0.0, hmax=0.0, hgrad=0.0, max_tets=0.0,
                 anisotropic_cycles=2, bl_patches=(), bl_first_height=0.0, bl_growth=1.2,
                 bl_layers=10, bl_sizing=False, push_tasks_min_vertices=2000, bl_slide_patches=(),
                 bl_cells=_capi.BL_CELLS_TETS, bl_mitre=False, bl_sizing_growth=0.0):
        self.num_threads = num_threads
        self.merge_duplicate_vertices = merge_duplicate_vertices
        self.orient_shells = orient_shells
        self.check_self_intersections = check_self_intersections
        self.layers = layers
        self.layer_scheme = layer_scheme
        self.recovery_max_seconds = recovery_max_seconds
        self.refine = refine
        self.optimize = optimize
        self.size_scale = size_scale
        self.progress = progress
        self.log = log
        self.attempts_seconds = attempts_seconds
        self.retry_layer_counts = retry_layer_counts
        self.recovery = recovery
        self.hmin = hmin
        self.hmax = hmax
        self.hgrad = hgrad
        self.max_tets = max_tets
        self.anisotropic_cycles = anisotropic_cycles
        self.bl_patches = bl_patches
        self.bl_first_height = bl_first_height
        self.bl_growth = bl_growth
        self.bl_layers = bl_layers
        self.bl_sizing = bl_sizing
        self.push_tasks_min_vertices = push_tasks_min_vertices
        self.bl_slide_patches = bl_slide_patches
        self.bl_cells = bl_cells
        self.bl_mitre = bl_mitre
        self.bl_sizing_growth = bl_sizing_growth


class _Callbacks:
    """The C callbacks of a call's Python progress and log functions: an exception raised in
    either cancels the call and is raised again by call(). The ctypes callback objects must
    outlive the call: they are attributes of self."""

    def __init__(self):
        self.error = None

    def c_progress(self, user_progress):
        """A PROGRESS_FN calling user_progress(stage, fraction); False cancels."""
        def progress(fraction, stage, _):
            if self.error is not None:
                return 1
            try:
                return 1 if user_progress(stage.decode(), fraction) is False else 0
            except BaseException as e:  # noqa: B902 - re-raised after the C call returns
                self.error = e
                return 1

        self._progress = _capi.PROGRESS_FN(progress)
        return self._progress

    def c_log(self, user_log):
        """A LOG_FN calling user_log(level, message)."""
        def log(level, message, _):
            if self.error is not None:
                return
            try:
                user_log(level, message.decode("utf-8", "replace"))
            except BaseException as e:  # noqa: B902
                self.error = e

        self._log = _capi.LOG_FN(log)
        return self._log

    def call(self, fn, *args):
        rc = fn(*args)
        if self.error is not None:
            raise self.error
        _check(rc)


class _CallbackScope(_Callbacks):
    """The C struct of an Options with its callbacks and wall labels, for the duration of one
    call."""

    def __init__(self, options):
        super().__init__()
        self.struct = _capi.COptions()
        _check(lib.anitet_options_init(byref(self.struct), _capi.OPTIONS_VERSION))
        if options is None:
            return
        s = self.struct
        s.num_threads = options.num_threads
        s.merge_duplicate_vertices = int(bool(options.merge_duplicate_vertices))
        s.orient_shells = int(bool(options.orient_shells))
        s.check_self_intersections = int(bool(options.check_self_intersections))
        s.layers = options.layers
        s.layer_scheme = options.layer_scheme
        s.recovery_max_seconds = options.recovery_max_seconds
        s.refine = int(bool(options.refine))
        s.optimize = int(bool(options.optimize))
        s.size_scale = options.size_scale
        s.attempts_seconds = options.attempts_seconds
        s.retry_layer_counts = int(bool(options.retry_layer_counts))
        s.recovery = options.recovery
        s.hmin, s.hmax, s.hgrad = options.hmin, options.hmax, options.hgrad
        s.max_tets = options.max_tets
        s.anisotropic_cycles = options.anisotropic_cycles
        s.bl_first_height = options.bl_first_height
        s.bl_growth = options.bl_growth
        s.bl_layers = options.bl_layers
        s.bl_sizing = int(bool(options.bl_sizing))
        s.push_tasks_min_vertices = options.push_tasks_min_vertices
        s.bl_cells = _bl_cells(options.bl_cells)
        s.bl_mitre = int(bool(options.bl_mitre))
        s.bl_sizing_growth = options.bl_sizing_growth
        # self._walls and self._slides own the memory behind the label pointers until the call
        # returns.
        self._walls, pointer, count = _labels(options.bl_patches, "bl_patches")
        if count > 0:
            s.bl_patches, s.bl_num_patches = pointer, count
        self._slides, pointer, count = _labels(options.bl_slide_patches, "bl_slide_patches")
        if count > 0:
            s.bl_slide_patches, s.bl_num_slide_patches = pointer, count
        if options.progress is not None:
            s.progress = self.c_progress(options.progress)
        if options.log is not None:
            s.log = self.c_log(options.log)


BL_CELLS = ("tets", "prisms")  # names of the BL_CELLS_* values, in order


def _bl_cells(value):
    """An Options.bl_cells as its BL_CELLS_* value (a name of BL_CELLS, or the value itself)."""
    if isinstance(value, str):
        try:
            return BL_CELLS.index(value.lower())
        except ValueError:
            raise ValueError("unknown bl_cells %r (one of %s)" % (value, ", ".join(BL_CELLS))) from None
    return value


def _labels(labels, what):
    """(keep-alive object, pointer, count) of patch labels: a sequence of ints, one int or None."""
    if labels is None:
        return None, None, 0
    return _flat_input([labels] if isinstance(labels, int) else labels, 1, c_int32, what)


def _options_arg(options, kwargs):
    if kwargs:
        if options is not None:
            raise TypeError("give either an Options or keyword options, not both")
        options = Options(**kwargs)
    return _CallbackScope(options)


# ---- surfaces ----------------------------------------------------------------------------------

class Surface(_Handle):
    """A closed triangulated surface: the input of the mesher."""

    _destroy = lib.anitet_surface_destroy

    @classmethod
    def from_arrays(cls, points, triangles, patches=None, index_base=0):
        """points (n, 3), triangles (m, 3) counter-clockwise seen from outside, patches (m,)."""
        p_keep, p_ptr, n = _flat_input(points, 3, c_double, "points")
        t_keep, t_ptr, m = _flat_input(triangles, 3, c_int32, "triangles")
        l_keep, l_ptr = None, None
        if patches is not None:
            l_keep, l_ptr, k = _flat_input(patches, 1, c_int32, "patches")
            if k != m:
                raise ValueError("patches: %d labels for %d triangles" % (k, m))
        # p_keep, t_keep and l_keep own the memory behind the pointers until the call returns.
        return _create(cls, lib.anitet_surface_create, p_ptr, n, t_ptr, m, l_ptr,
                       _base(index_base))

    @classmethod
    def read(cls, path):
        """A surface from a file (.off .obj .stl .ply .mesh .meshb .msh)."""
        return _create(cls, lib.anitet_surface_read, _path(path))

    def counts(self):
        np_, nt = c_int64(), c_int64()
        _check(lib.anitet_surface_get_counts(self, byref(np_), byref(nt)))
        return np_.value, nt.value

    @property
    def num_points(self):
        return self.counts()[0]

    @property
    def num_triangles(self):
        return self.counts()[1]

    def points(self):
        return _output(self.num_points, 3, c_double,
                       lambda p, n: lib.anitet_surface_get_points(self, p, n))

    def triangles(self, index_base=0):
        b = _base(index_base)
        return _output(self.num_triangles, 3, c_int32,
                       lambda p, n: lib.anitet_surface_get_triangles(self, p, n, b))

    def patches(self):
        return _output(self.num_triangles, 1, c_int32,
                       lambda p, n: lib.anitet_surface_get_patches(self, p, n))

    def validate(self, options=None, **kwargs):
        """Validates and safely repairs the surface in place; AnitetError names the first problem
        (the report stays available: problem_count, validation_report)."""
        scope = _options_arg(options, kwargs)
        scope.call(lib.anitet_surface_validate, self, byref(scope.struct))

    def problem_count(self, code):
        count = c_int64()
        _check(lib.anitet_surface_problem_count(self, code, byref(count)))
        return count.value

    def validation_json(self):
        return _text(lambda buf, n, needed: lib.anitet_surface_validation_json(self, buf, n, needed))

    def validation_report(self):
        return json.loads(self.validation_json())

    def mesh(self, metric=None, options=None, **kwargs):
        """Meshes the inside of the surface: see mesh_surface."""
        return mesh_surface(self, metric, options, **kwargs)

    def build_layers(self, options=None, **kwargs):
        """Stage 1 alone: see build_layers."""
        return build_layers(self, options, **kwargs)


# ---- metrics -----------------------------------------------------------------------------------

class Metric(_Handle):
    """A metric (sizing) field."""

    _destroy = lib.anitet_metric_destroy

    @classmethod
    def uniform(cls, size):
        return _create(cls, lib.anitet_metric_create_uniform, float(size))

    @classmethod
    def analytic(cls, function):
        """function(x, y, z) -> the 6 values xx xy yy xz yz zz (or, for 2D meshes, which evaluate
        it at z = 0, the 3 values xx xy yy); an exception marks the point as not evaluable
        (evaluate raises it again)."""
        holder = {"error": None}

        def callback(x, y, z, m, _):
            try:
                values = function(x, y, z)
                if len(values) == 3:  # a 2D tensor: zz (unused in 2D) their mean
                    values = (values[0], values[1], values[2], 0.0, 0.0, 0.5 * (values[0] + values[2]))
                if len(values) != 6:
                    raise ValueError("the metric function returned %d values, 6 (or 3) expected" % len(values))
                for i in range(6):
                    m[i] = float(values[i])
                return 0
            except BaseException as e:  # noqa: B902 - reported by evaluate
                holder["error"] = e
                return 1

        c_callback = _capi.METRIC_FN(callback)
        metric = _create(cls, lib.anitet_metric_create_analytic, c_callback, None)
        metric._callback = c_callback  # must live as long as the C metric
        metric._holder = holder
        return metric

    @classmethod
    def read(cls, path, background_mesh_path=None):
        """A metric from a file, by extension: an OpenVDB .vdb (grid "size", or the six
        "log_metric_*" or "metric_*" grids; no background), or a Medit .sol or .solb (a size or a
        tensor per vertex) on the tetrahedral mesh at background_mesh_path (.mesh .meshb .msh .vtu
        .node)."""
        bg = _path(background_mesh_path) if background_mesh_path is not None else None
        return _create(cls, lib.anitet_metric_read, _path(path), bg)

    @classmethod
    def from_points(cls, background, values, components=None):
        """A metric from values at the points of `background` (a Mesh), in its point order:
        (n,) sizes or (n, 6) tensors xx xy yy xz yz zz. components (1 or 6) defaults to the
        values' row length. The values and the mesh are copied."""
        _require(background, Mesh, "background")
        if components is None:
            first = values[0] if len(values) else 0.0
            components = len(first) if hasattr(first, "__len__") else 1
        keep, ptr, count = _flat_doubles(values)  # keep owns the memory behind ptr
        return _create(cls, lib.anitet_metric_create_from_points, background, ptr, count,
                       components)

    @classmethod
    def surface_sizing(cls, surface, options=None, **kwargs):
        """The sizing field mesh_surface follows when given no metric (`anitet mesh
        --write-sizing`): a grid over the surface's box from its triangles' sizes, bounded and
        graded by the options' hmin, hmax and hgrad (an Options or keywords). The surface is
        validated on a copy with the options' repairs, as mesh_surface does."""
        _require(surface, Surface, "surface")
        scope = _options_arg(options, kwargs)
        out = c_void_p()
        scope.call(lib.anitet_metric_create_surface_sizing, surface, byref(scope.struct), byref(out))
        return cls(out.value)

    @classmethod
    def read_on_mesh(cls, path, background):
        """A Medit .sol or .solb metric on `background`, a Mesh in memory (copied): one moved to
        a local frame by Mesh.to_local, say, or the mesh of the last adaptation pass."""
        _require(background, Mesh, "background")
        return _create(cls, lib.anitet_metric_read_on_mesh, _path(path), background)

    def write(self, path, box_of=None):
        """Writes the metric as OpenVDB grids (.vdb), which Metric.read reads back: a grid metric
        (read from a .vdb, or Metric.surface_sizing) as it is, any other sampled on a lattice over
        the box of the Surface box_of (required then)."""
        if box_of is not None:
            _require(box_of, Surface, "box_of")
        _check(lib.anitet_metric_write(self, box_of, _path(path)))

    def evaluate(self, x, y, z):
        """The tensor at (x, y, z): a tuple xx xy yy xz yz zz."""
        m = (c_double * 6)()
        holder = getattr(self, "_holder", None)
        if holder is not None:
            holder["error"] = None
        rc = lib.anitet_metric_evaluate(self, x, y, z, m)
        if rc != _capi.OK and holder is not None and holder["error"] is not None:
            error, holder["error"] = holder["error"], None
            raise AnitetError(rc, lib.anitet_last_error_message().decode()) from error
        _check(rc)
        return tuple(m)


# ---- volume meshes -----------------------------------------------------------------------------

# The names of the PATCH_TYPE_* values, indexed by them.
PATCH_TYPES = ("wall", "inlet", "outlet", "farfield", "symmetry", "patch")


class _Figures:
    """The figures of a C struct as attributes: FIELDS, those in FLAGS as booleans."""

    FIELDS = ()
    FLAGS = ()

    def __init__(self, c_struct):
        for name in self.FIELDS:
            value = getattr(c_struct, name)
            setattr(self, name, bool(value) if name in self.FLAGS else value)

    def as_dict(self):
        return {name: getattr(self, name) for name in self.FIELDS}

    def __repr__(self):
        return "%s(%s)" % (type(self).__name__, ", ".join("%s=%r" % kv for kv in self.as_dict().items()))


class Quality(_Figures):
    """The numbers of anitet_quality (version 1)."""

    FIELDS = ("valid", "boundary_constrained", "vertices", "tets", "nonpositive_tets",
              "radius_ratio_mean", "radius_ratio_min", "mean_ratio_mean", "mean_ratio_min",
              "min_dihedral_deg", "max_dihedral_deg", "good_fraction", "bad_fraction")
    FLAGS = ("valid", "boundary_constrained")


class RunStats(_Figures):
    """The numbers of anitet_run_stats (version 3): what the run that made a mesh did.
    recovery_strategy is RECOVERY_SPLIT or RECOVERY_FUZZY (the strategy that worked); the bl_*
    figures are 0 without a boundary layer, the slide_* ones without slide patches, bl_prisms and
    bl_prism_tets_left (prism cells made, boundary-layer tets left as tets) without
    bl_cells="prisms".
    Mesh.run_report() has everything else."""

    FIELDS = tuple(name for name, _ in _capi.CRunStats._fields_ if name not in ("version", "reserved0"))
    FLAGS = ("refine_stopped_at_pass_cap",)


class PatchNames(collections.abc.MutableMapping):
    """The patch names of a Mesh, label -> name, as given through it: setting or deleting an item
    names or unnames the label (Mesh.set_patch_name)."""

    def __init__(self, mesh):
        self._mesh = mesh

    def __getitem__(self, label):
        return self._mesh._patch_names[label]

    def __setitem__(self, label, name):
        if name is None:
            raise TypeError("a patch name is a str; del removes it")
        self._mesh.set_patch_name(label, name)

    def __delitem__(self, label):
        if label not in self._mesh._patch_names:
            raise KeyError(label)
        self._mesh.set_patch_name(label, None)

    def __iter__(self):
        return iter(sorted(self._mesh._patch_names))

    def __len__(self):
        return len(self._mesh._patch_names)

    def __repr__(self):
        return "PatchNames(%r)" % dict(self)


class Mesh(_Handle):
    """A tetrahedral mesh: the mesher's result, read from a file or built from arrays."""

    _destroy = lib.anitet_mesh_destroy

    def __init__(self, ptr):
        super().__init__(ptr)
        self._patch_names = {}  # what set_patch_name gave the library (it has no getter)

    @classmethod
    def from_arrays(cls, points, tets, regions=None, boundary_triangles=None,
                    boundary_patches=None, index_base=0):
        p_keep, p_ptr, n = _flat_input(points, 3, c_double, "points")
        t_keep, t_ptr, nt = _flat_input(tets, 4, c_int32, "tets")
        r_keep, r_ptr, b_keep, b_ptr, l_keep, l_ptr, nb = None, None, None, None, None, None, 0
        if regions is not None:
            r_keep, r_ptr, k = _flat_input(regions, 1, c_int32, "regions")
            if k != nt:
                raise ValueError("regions: %d labels for %d tets" % (k, nt))
        if boundary_triangles is not None:
            b_keep, b_ptr, nb = _flat_input(boundary_triangles, 3, c_int32, "boundary_triangles")
        if boundary_patches is not None:
            l_keep, l_ptr, k = _flat_input(boundary_patches, 1, c_int32, "boundary_patches")
            if k != nb:
                raise ValueError("boundary_patches: %d labels for %d triangles" % (k, nb))
        # The *_keep names own the memory behind the pointers until the call returns.
        return _create(cls, lib.anitet_mesh_create, p_ptr, n, t_ptr, nt, r_ptr, b_ptr, nb, l_ptr,
                       _base(index_base))

    @classmethod
    def read(cls, path):
        """A mesh from a file (.mesh .meshb .msh .node/.ele .vtu)."""
        return _create(cls, lib.anitet_mesh_read, _path(path))

    def write(self, path):
        """Writes by extension: .mesh .meshb .msh .vtu, or for solvers .su2 .cgns .exo/.e and a
        path ending in polyMesh (OpenFOAM), the patches named as patch_names says (others
        patch<label>) and typed as set_patch_type says."""
        _check(lib.anitet_mesh_write(self, _path(path)))

    def set_patch_name(self, label, name):
        """Names the boundary patch `label` in the files write() writes (SU2 markers, OpenFOAM
        patches, CGNS and Exodus names, Gmsh physical names): 1-32 letters, digits or '_',
        starting with a letter. None removes the name."""
        encoded = None if name is None else name.encode("utf-8")
        _check(lib.anitet_mesh_set_patch_name(self, label, encoded))
        if name is None:
            self._patch_names.pop(label, None)
        else:
            self._patch_names[label] = name

    def set_patch_type(self, label, type):  # noqa: A002 - the C argument's name
        """Sets the type of the boundary patch `label` in the files write() writes (OpenFOAM, CGNS,
        Exodus II): "wall", "inlet", "outlet", "farfield", "symmetry", "patch" or a PATCH_TYPE_*
        value; None (PATCH_TYPE_FROM_NAME) removes it, the name then implies the type."""
        if type is None:
            type = _capi.PATCH_TYPE_FROM_NAME
        elif isinstance(type, str):
            try:
                type = PATCH_TYPES.index(type.lower())
            except ValueError:
                raise ValueError("unknown patch type %r (one of %s)" % (type, ", ".join(PATCH_TYPES))) from None
        _check(lib.anitet_mesh_set_patch_type(self, label, type))

    def patch_type(self, label):
        """The type write() gives the patch `label`, a name of PATCH_TYPES: the one set, else the
        one its name implies ("inlet" or "inflow" in it: inlet, ...; any other name: wall)."""
        t = c_int32()
        _check(lib.anitet_mesh_get_patch_type(self, label, byref(t)))
        return PATCH_TYPES[t.value]

    @property
    def patch_names(self):
        """The names given, a mutable mapping label -> name (mesh.patch_names[4] = "farfield",
        del mesh.patch_names[4], update(...)); assigning a dict replaces them all."""
        return PatchNames(self)

    @patch_names.setter
    def patch_names(self, names):
        current = PatchNames(self)
        current.clear()
        current.update(names)

    @property
    def run_stats(self):
        """What the run that made this mesh did (RunStats). AnitetError (ERR_INVALID_ARGUMENT)
        for a mesh read from a file or made from arrays."""
        stats = _capi.CRunStats()
        stats.version = _capi.RUN_STATS_VERSION
        _check(lib.anitet_mesh_get_run_stats(self, byref(stats)))
        return RunStats(stats)

    def run_json(self):
        """The run's whole report as JSON text: stages (name, seconds, tets), layers, recovery,
        coupling, refine, optimize, metric_quality, boundary_layer, notices, seconds."""
        return _text(lambda buf, n, needed: lib.anitet_mesh_run_json(self, buf, n, needed))

    def run_report(self):
        """run_json() parsed: a dict."""
        return json.loads(self.run_json())

    def write_metric(self, path):
        """Writes the per-vertex metric as a Medit .sol (binary .solb by its extension)."""
        _check(lib.anitet_mesh_write_metric(self, _path(path)))

    def write_bl_columns(self, path):
        """Writes the boundary layer's columns as CSV (`anitet mesh --bl-columns`): a header line,
        then per wall vertex its point, the layers its column reaches, its first and total height,
        its normal share and its patch labels. For a mesh of mesher_run or layers_run with
        bl_patches; another raises ERR_INVALID_ARGUMENT."""
        _check(lib.anitet_mesh_write_bl_columns(self, _path(path)))

    def counts(self):
        """(points, tets, boundary triangles)."""
        a, b, c = c_int64(), c_int64(), c_int64()
        _check(lib.anitet_mesh_get_counts(self, byref(a), byref(b), byref(c)))
        return a.value, b.value, c.value

    @property
    def num_points(self):
        return self.counts()[0]

    @property
    def num_tets(self):
        return self.counts()[1]

    @property
    def num_boundary_triangles(self):
        return self.counts()[2]

    def points(self):
        return _output(self.num_points, 3, c_double,
                       lambda p, n: lib.anitet_mesh_get_points(self, p, n))

    def tets(self, index_base=0):
        b = _base(index_base)
        return _output(self.num_tets, 4, c_int32,
                       lambda p, n: lib.anitet_mesh_get_tets(self, p, n, b))

    def regions(self):
        return _output(self.num_tets, 1, c_int32,
                       lambda p, n: lib.anitet_mesh_get_regions(self, p, n))

    @property
    def num_prisms(self):
        """Prism cells (Options.bl_cells "prisms"): how many; 0 for a mesh without."""
        n = c_int64()
        _check(lib.anitet_mesh_get_prism_count(self, byref(n)))
        return n.value

    def prisms(self, index_base=0):
        """The prism cells write() writes in place of their tets, num_prisms x 6: the wall-side
        triangle a b c, then a' b' c' where its columns reach (edges a-a', b-b', c-c')."""
        b = _base(index_base)
        return _output(self.num_prisms, 6, c_int32, lambda p, n: lib.anitet_mesh_get_prisms(self, p, n, b))

    def tet_prisms(self, index_base=0):
        """Per tet of tets(), the prism it is one of the 3 tets of (counted from index_base), or -1
        for a tet written as a tet."""
        b = _base(index_base)
        return _output(self.num_tets, 1, c_int32, lambda p, n: lib.anitet_mesh_get_tet_prisms(self, p, n, b))

    def boundary_triangles(self, index_base=0):
        b = _base(index_base)
        return _output(self.num_boundary_triangles, 3, c_int32,
                       lambda p, n: lib.anitet_mesh_get_boundary_triangles(self, p, n, b))

    def boundary_patches(self):
        return _output(self.num_boundary_triangles, 1, c_int32,
                       lambda p, n: lib.anitet_mesh_get_boundary_patches(self, p, n))

    @property
    def metric_components(self):
        """0 (no per-vertex metric), 1 (size) or 6 (xx xy yy xz yz zz)."""
        c = c_int32()
        _check(lib.anitet_mesh_get_metric_components(self, byref(c)))
        return c.value

    def metric(self):
        """The per-vertex metric, (n, components) values; None when the mesh has none."""
        comps = self.metric_components
        if comps == 0:
            return None
        return _output(self.num_points, comps, c_double,
                       lambda p, n: lib.anitet_mesh_get_metric(self, p, n))

    def set_metric(self, values, components=None):
        """Sets the per-vertex metric: values (n, 6) tensors or (n,) sizes; None removes it."""
        if values is None:
            _check(lib.anitet_mesh_set_metric(self, None, 0, 0))
            return
        if components is None:
            first = values[0] if len(values) else 0.0
            components = len(first) if hasattr(first, "__len__") else 1
        keep, ptr, count = _flat_doubles(values)  # keep owns the memory behind ptr
        _check(lib.anitet_mesh_set_metric(self, ptr, count, components))

    def sample_metric(self, metric):
        """Sets the per-vertex metric to `metric`'s values at the points (`anitet mesh
        --write-metric`): sizes (1 component) when every tensor is isotropic, else tensors; then
        write_metric writes it. A failing analytic metric raises AnitetError and leaves the mesh's
        metric as it was."""
        _require(metric, Metric, "metric")
        _check(lib.anitet_mesh_sample_metric(self, metric))

    def quality(self, input=None):  # noqa: A002 - the C argument's name
        """The quality numbers, against the input surface when given (boundary_constrained)."""
        q = _capi.CQuality()
        q.version = _capi.QUALITY_VERSION
        _check(lib.anitet_mesh_quality(self, input, byref(q)))
        return Quality(q)

    def quality_json(self, input=None):  # noqa: A002
        """The full quality report as JSON text."""
        return _text(lambda buf, n, needed: lib.anitet_mesh_quality_json(self, input, buf, n, needed))

    def quality_report(self, input=None):  # noqa: A002
        return json.loads(self.quality_json(input))


def mesh_surface(surface, metric=None, options=None, **kwargs):
    """Meshes the inside of `surface` (validated on a copy) into a new Mesh.

    metric: a Metric for the sizes (the mesh then carries it at its vertices, Mesh.metric()), or
    None for sizes from the surface's triangles. options: an Options, or its fields as keywords
    (layers=1, size_scale=2, hgrad=1.3, bl_patches=[1], bl_first_height=0.01, progress=...).
    What the run did: the mesh's run_stats and run_report().
    """
    if metric is not None and not isinstance(metric, Metric):
        raise TypeError("metric must be an anitet.Metric or None, not %s" % type(metric).__name__)
    scope = _options_arg(options, kwargs)
    out = c_void_p()
    scope.call(lib.anitet_mesher_run, surface, metric, byref(scope.struct), byref(out))
    return Mesh(out.value)


def build_layers(surface, options=None, **kwargs):
    """Stage 1 alone (`anitet mesh --stop-after layers`, the C ABI's anitet_layers_run), to look
    at the layers: validates a copy of `surface`, builds the advancing-front layers (the options'
    layers, layer_scheme, push_tasks_min_vertices and bl_* fields; the others are not used) at the
    surface's own sizes and returns T1 as a Mesh: the surface's triangles under their labels, the
    new front's under the largest label + 1, the boundary layer's tets in region 1. Its run_stats
    hold layers_used and the boundary layer measured on T1."""
    scope = _options_arg(options, kwargs)
    out = c_void_p()
    scope.call(lib.anitet_layers_run, surface, byref(scope.struct), byref(out))
    return Mesh(out.value)


def bl_first_height(yplus, reynolds, ref_length):
    """The first boundary-layer height h0 for a target y+ (`anitet mesh --bl-yplus`), from the
    flat-plate estimate Cf = 0.026 Re^(-1/7), h0 = y+ L / (Re sqrt(Cf / 2)), with the Reynolds
    number Re and the reference length L (in the coordinates' unit)."""
    h0 = c_double()
    _check(lib.anitet_bl_first_height(yplus, reynolds, ref_length, byref(h0)))
    return h0.value


# ---- 2D meshes ---------------------------------------------------------------------------------

class Pslg(_Handle):
    """A planar straight-line graph: the 2D mesher's input (points, segments with labels, hole
    points). The unbounded face and the faces holding a hole point are outside."""

    _destroy = lib.anitet_pslg_destroy

    @classmethod
    def from_arrays(cls, points, segments, labels=None, holes=None, index_base=0):
        """points (n, 2), segments (m, 2) point indices, labels (m,), holes (h, 2)."""
        base = _base(index_base)
        pk, pp, n = _flat_input(points, 2, c_double, "points")
        sk, sp, m = _flat_input(segments, 2, c_int32, "segments")
        lk, lp = None, None
        if labels is not None:
            lk, lp, count = _flat_input([(v,) for v in labels], 1, c_int32, "labels")
            if count != m:
                raise ValueError("one label per segment is needed (%d for %d)" % (count, m))
        hk, hp, h = None, None, 0
        if holes is not None and len(holes):
            hk, hp, h = _flat_input(holes, 2, c_double, "holes")
        return _create(cls, lib.anitet_pslg_create, pp, n, sp, m, lp, hp, h, base)

    @classmethod
    def read(cls, path):
        """A PSLG from a .poly (Triangle), a 2D .mesh (Medit, its Edges) or a .geojson (lon/lat
        polygons: mesh them with geodetic=True)."""
        return _create(cls, lib.anitet_pslg_read, _path(path))

    def counts(self):
        """(points, segments, hole points)."""
        n, m, h = c_int64(), c_int64(), c_int64()
        _check(lib.anitet_pslg_get_counts(self, byref(n), byref(m), byref(h)))
        return n.value, m.value, h.value

    def mesh(self, metric=None, **kwargs):
        """Meshes the PSLG: see mesh2d."""
        return mesh2d(self, metric, **kwargs)


class Mesh2d(_Handle):
    """A triangle mesh of the 2D mesher: the input's points first and in order, counter-clockwise
    triangles with their region attributes, and the segments' pieces as edges with labels."""

    _destroy = lib.anitet_mesh2d_destroy

    def counts(self):
        """(points, triangles, edges)."""
        n, t, e = c_int64(), c_int64(), c_int64()
        _check(lib.anitet_mesh2d_get_counts(self, byref(n), byref(t), byref(e)))
        return n.value, t.value, e.value

    def points(self):
        return _output(self.counts()[0], 2, c_double, lambda p, n: lib.anitet_mesh2d_get_points(self, p, n))

    def triangles(self, index_base=0):
        base = _base(index_base)
        return _output(self.counts()[1], 3, c_int32,
                       lambda p, n: lib.anitet_mesh2d_get_triangles(self, p, n, base))

    def attributes(self):
        return _output(self.counts()[1], 1, c_double, lambda p, n: lib.anitet_mesh2d_get_attributes(self, p, n))

    def edges(self, index_base=0):
        base = _base(index_base)
        return _output(self.counts()[2], 2, c_int32, lambda p, n: lib.anitet_mesh2d_get_edges(self, p, n, base))

    def edge_labels(self):
        return _output(self.counts()[2], 1, c_int32, lambda p, n: lib.anitet_mesh2d_get_edge_labels(self, p, n))

    def write(self, path):
        """Writes by extension: .mesh, .msh, .vtu, or .14 / fort.14 (ADCIRC)."""
        _check(lib.anitet_mesh2d_write(self, _path(path)))

    def quality(self):
        """A dict: min_angle_deg, min_angle_off_input_deg (over the triangles with no input point),
        mean_radius_ratio (2r/R) and edges_in_range (share of metric lengths in [1/sqrt2, sqrt2])."""
        v = [c_double() for _ in range(4)]
        _check(lib.anitet_mesh2d_quality(self, *(byref(x) for x in v)))
        names = ("min_angle_deg", "min_angle_off_input_deg", "mean_radius_ratio", "edges_in_range")
        return {k: x.value for k, x in zip(names, v)}


def mesh2d(pslg, metric=None, split_segments=False, layers=1, refine=True, optimize=True,
           geodetic=False, geo_frame=_capi.GEO_ENU, hsize=0.0, size_scale=1.0, hmin=0.0, hmax=0.0,
           hgrad=0.0, progress=None):
    """Meshes a Pslg into a new Mesh2d (the fields are anitet_mesh2d_options'): every segment
    stays whole unless split_segments; sizes from hsize (0: the segments' lengths), or a Metric
    evaluated at z = 0; geodetic: the points are longitude, latitude, meshed in metres and
    returned in degrees (the input's points exactly). progress(stage, fraction): return False
    to cancel (AnitetError with ERR_CANCELLED)."""
    if not isinstance(pslg, Pslg):
        raise TypeError("pslg must be an anitet.Pslg, not %s" % type(pslg).__name__)
    if metric is not None and not isinstance(metric, Metric):
        raise TypeError("metric must be an anitet.Metric or None, not %s" % type(metric).__name__)
    o = _capi.CMesh2dOptions()
    _check(lib.anitet_mesh2d_options_init(byref(o), _capi.MESH2D_OPTIONS_VERSION))
    o.split_segments = int(bool(split_segments))
    o.layers = layers
    o.refine = int(bool(refine))
    o.optimize = int(bool(optimize))
    o.geodetic = int(bool(geodetic))
    o.geo_frame = geo_frame
    o.hsize, o.size_scale, o.hmin, o.hmax, o.hgrad = float(hsize), float(size_scale), float(hmin), float(hmax), float(hgrad)
    error = []
    if progress is not None:
        def c_progress(fraction, stage, _):
            try:
                return 1 if progress(stage.decode(), fraction) is False else 0
            except BaseException as e:  # noqa: B902 - re-raised after the call
                error.append(e)
                return 1

        keep = _capi.PROGRESS_FN(c_progress)  # alive until the call returns
        o.progress = keep
    out = c_void_p()
    rc = lib.anitet_mesh2d_run(pslg, metric, byref(o), byref(out))
    if error:
        raise error[0]
    holder = getattr(metric, "_holder", None) if metric is not None else None
    if rc != _capi.OK and holder is not None and holder["error"] is not None:
        cause, holder["error"] = holder["error"], None
        raise AnitetError(rc, lib.anitet_last_error_message().decode()) from cause
    _check(rc)
    return Mesh2d(out.value)
