"""Adaptation (include/anitet.h, "Adaptation"; `anitet adapt`): a Mesh and a metric in, a new Mesh
whose edges have unit length in the metric out, fields carried along.

    metric = [linear_metric(p) for p in mesh.points()]     # (n, 6) tensors or (n,) sizes
    result = anitet.adapt(mesh, metric, fields=solution)    # or mesh.adapt(metric, ...)
    mesh, solution = result.mesh, result.fields
    print(result.stats.edges_in_range, result.stats.mean_ratio_min)

The metric: values at the mesh's points, (n, 6) symmetric tensors xx xy yy xz yz zz or (n,)
sizes (a C-contiguous float64 NumPy array is passed without a copy), or a Metric (an analytic
function, a file) evaluated at every new point.
"""
import collections
from ctypes import byref, c_void_p

from . import _capi
from ._api import Mesh, Metric, _Callbacks, _check, _Figures, _flat_doubles, _require
from ._capi import lib
from ._fields import Fields, _tensors



class AdaptStats(_Figures):
    """The numbers of anitet_adapt_stats (version 1): what the adaptation did (cycles, splits,
    collapses, swaps, moves, those on the surface) and the UGAWG measures of the new mesh in the
    metric (edges_in_range: the share of edges of metric length in [1/sqrt2, sqrt2];
    mean_ratio_min and _mean), with the seconds."""

    FIELDS = tuple(name for name, _ in _capi.CAdaptStats._fields_ if name != "version")



AdaptResult = collections.namedtuple("AdaptResult", "mesh fields stats")
AdaptResult.__doc__ = """The new Mesh (with the metric at its points, Mesh.metric()), the fields
carried to its points (None without fields) and the AdaptStats."""


def adapt(mesh, metric, fields=None, *, keep_surface=False, ridge_angle_deg=45.0, max_cycles=30,
          optimize_cycles=3, tensors=_capi.TENSORS_AUTO, num_threads=0, progress=None, log=None):
    """Adapts `mesh` to `metric` (values at its points, or a Metric): an AdaptResult.

    fields: Fields at mesh's points, carried to the new mesh's (tensors: how their symmetric
    tensors go, "auto", "log_euclidean" or "linear"). keep_surface: keep the boundary triangles
    exactly (`--keep-surface`); ridge_angle_deg, max_cycles, optimize_cycles: as `anitet adapt`.
    num_threads: the call's task arena (0: all cores; the same mesh on any number).
    progress(stage, fraction): False cancels (AnitetError ERR_CANCELLED); log(level, line): one
    line per sweep. An exception raised in either cancels the call and is raised again."""
    _require(mesh, Mesh, "mesh")
    if fields is not None:
        _require(fields, Fields, "fields")
    scope = _Callbacks()
    options = _capi.CAdaptOptions()
    _check(lib.anitet_adapt_options_init(byref(options), _capi.ADAPT_OPTIONS_VERSION))
    options.num_threads = num_threads
    options.keep_surface = int(bool(keep_surface))
    options.max_cycles = max_cycles
    options.ridge_angle_deg = ridge_angle_deg
    options.optimize_cycles = optimize_cycles
    options.tensors = _tensors(tensors)
    if progress is not None:
        options.progress = scope.c_progress(progress)
    if log is not None:
        options.log = scope.c_log(log)
    stats = _capi.CAdaptStats()
    stats.version = _capi.ADAPT_STATS_VERSION
    out, out_fields = c_void_p(), c_void_p()
    fields_out = byref(out_fields) if fields is not None else None
    if isinstance(metric, Metric):
        scope.call(lib.anitet_adapt_to_metric, mesh, metric, fields, byref(options), byref(out), fields_out,
                   byref(stats))
    else:
        first = metric[0] if len(metric) else 0.0
        components = len(first) if hasattr(first, "__len__") else 1
        keep, pointer, count = _flat_doubles(metric)  # keep owns the memory behind pointer
        scope.call(lib.anitet_adapt, mesh, pointer, count, components, fields, byref(options), byref(out),
                   fields_out, byref(stats))
    new_fields = Fields(out_fields.value) if fields is not None else None
    new_mesh = Mesh(out.value)
    new_mesh._patch_names = dict(mesh._patch_names)  # the library copied them
    return AdaptResult(new_mesh, new_fields, AdaptStats(stats))


def _mesh_adapt(self, metric, fields=None, **kwargs):
    """This mesh adapted to `metric`: see anitet.adapt."""
    return adapt(self, metric, fields, **kwargs)


Mesh.adapt = _mesh_adapt
