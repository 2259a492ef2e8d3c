"""Per-vertex fields and their transfer between meshes (include/anitet.h, "Per-vertex fields").

    flow = anitet.Fields.read("flow.solb")                 # or Fields.from_arrays(kinds, values)
    moved = old_mesh.transfer_fields(flow, new_mesh)        # at new_mesh's points
    moved.write("flow_new.solb")
    print(moved.transfer_report())                          # points outside the old mesh, ...
    pressure = moved.field(0)                               # NumPy view, no copy

Values are one record per vertex (every field's components in field order): `values` is a
read-only (num_vertices, record_size) NumPy view over the library's memory (no copy), `field(i)`
the (num_vertices, components) columns of field i. A view keeps that memory alive after the Fields
object is closed. Without NumPy they are lists of tuples (copies).
"""
import collections
import ctypes
from ctypes import byref, c_double, c_int32, c_int64, c_void_p

from . import _capi
from ._api import Mesh, _check, _flat_input, _np, _path, _require
from ._capi import lib
from ._partition import _ORDER, _Memory, _View

_COMPONENTS = {_capi.FIELD_KIND_SCALAR: 1, _capi.FIELD_KIND_VECTOR: 3, _capi.FIELD_KIND_SYM_TENSOR: 6}
_KIND_BY_NAME = {"scalar": _capi.FIELD_KIND_SCALAR, "vector": _capi.FIELD_KIND_VECTOR,
                 "tensor": _capi.FIELD_KIND_SYM_TENSOR, "sym_tensor": _capi.FIELD_KIND_SYM_TENSOR}
_TENSORS_BY_NAME = {"auto": _capi.TENSORS_AUTO, "log_euclidean": _capi.TENSORS_LOG_EUCLIDEAN,
                    "linear": _capi.TENSORS_LINEAR}

TransferReport = collections.namedtuple("TransferReport", "outside max_outside_distance log_euclidean")
TransferReport.__doc__ = """What a transfer found: the points outside the old mesh (they took the
value at its closest boundary point), their largest distance to it, and per field whether it was
interpolated in log space."""


def _kind(kind):
    if isinstance(kind, str):
        try:
            return _KIND_BY_NAME[kind.lower()]
        except KeyError:
            raise ValueError("unknown field kind %r (scalar, vector or tensor)" % kind) from None
    return int(kind)


class Fields:
    """Fields at the vertices of a mesh: kinds (FIELD_KIND_SCALAR, _VECTOR, _SYM_TENSOR) and one
    record of values per vertex."""

    def __init__(self, ptr):
        self._memory = _Memory(ptr, lib.anitet_fields_destroy)

    @property
    def _as_parameter_(self):
        return self._memory.ptr if self._memory is not None else None  # closed: NULL

    def close(self):
        """Drops this object's hold on the values (views keep theirs)."""
        self._memory = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @classmethod
    def _made(cls, call, *args):
        out = c_void_p()
        _check(call(*args, byref(out)))
        return cls(out.value)

    @classmethod
    def from_arrays(cls, kinds, values):
        """kinds: one per field, FIELD_KIND_* or "scalar", "vector" (x y z), "tensor" (xx xy yy
        xz yz zz); values: one record per vertex, shaped (n, record_size) or flat (copied)."""
        kind_list = [_kind(k) for k in ([kinds] if isinstance(kinds, (int, str)) else kinds)]
        k_keep, k_ptr, nf = _flat_input(kind_list, 1, c_int32, "kinds")
        record = sum(_COMPONENTS.get(k, 1) for k in kind_list)
        v_keep, v_ptr, rows = _flat_input(values, record, c_double, "values")
        # k_keep and v_keep own the memory behind the pointers until the call returns.
        return cls._made(lib.anitet_fields_create, k_ptr, nf, v_ptr, rows * record)

    @classmethod
    def read(cls, path):
        """Fields from a Medit .sol or a GMF .solb (by extension)."""
        return cls._made(lib.anitet_fields_read, _path(path))

    def write(self, path):
        """Writes a Medit .sol (same bits when read back) or a GMF .solb, by extension."""
        _check(lib.anitet_fields_write(self, _path(path)))

    def counts(self):
        """(number of fields, components per vertex, number of vertices)."""
        nf, record, nv = c_int32(), c_int32(), c_int64()
        _check(lib.anitet_fields_get_counts(self, byref(nf), byref(record), byref(nv)))
        return nf.value, record.value, nv.value

    num_fields = property(lambda self: self.counts()[0])
    record_size = property(lambda self: self.counts()[1])
    num_vertices = property(lambda self: self.counts()[2])

    @property
    def kinds(self):
        """The FIELD_KIND_* of each field, a list."""
        nf = self.num_fields
        buf = (c_int32 * nf)()
        _check(lib.anitet_fields_get_kinds(self, buf, nf))
        return list(buf)

    @property
    def values(self):
        """(num_vertices, record_size) values, a read-only view (a list of tuples without NumPy)."""
        _, record, nv = self.counts()
        data, count = ctypes.POINTER(c_double)(), c_int64()
        _check(lib.anitet_fields_get_data(self, byref(data), byref(count)))
        address = ctypes.cast(data, c_void_p).value
        if _np is not None:
            if count.value == 0:
                return _np.zeros((nv, record))
            view = _np.asarray(_View(address, (nv, record), _ORDER + "f8", self._memory))
            view.flags.writeable = False
            return view
        flat = (c_double * count.value).from_address(address)[:]  # a copy
        return [tuple(flat[i:i + record]) for i in range(0, count.value, record)]

    def field(self, index):
        """Field `index`'s columns: (num_vertices, components) (a view with NumPy), or (n,) for a
        scalar."""
        kinds = self.kinds
        start = sum(_COMPONENTS[k] for k in kinds[:index])
        width = _COMPONENTS[kinds[index]]
        values = self.values
        if _np is not None:
            return values[:, start] if width == 1 else values[:, start:start + width]
        if width == 1:
            return [row[start] for row in values]
        return [row[start:start + width] for row in values]

    def transfer_report(self):
        """TransferReport of the transfer that made these fields (AnitetError ERR_INVALID_ARGUMENT
        for fields that a transfer did not make)."""
        nf = self.num_fields
        outside, distance, flags = c_int64(), c_double(), (c_int32 * max(nf, 1))()
        _check(lib.anitet_fields_get_transfer_report(self, byref(outside), byref(distance), flags, nf))
        return TransferReport(outside.value, distance.value, [bool(f) for f in flags[:nf]])

    def __repr__(self):
        nf, record, nv = self.counts()
        return "Fields(%d fields %r, %d values per vertex, %d vertices)" % (nf, self.kinds, record, nv)


def _tensors(tensors):
    """A TENSORS_* value from itself or its name."""
    if isinstance(tensors, str):
        try:
            return _TENSORS_BY_NAME[tensors.lower()]
        except KeyError:
            raise ValueError("unknown tensors %r (auto, log_euclidean or linear)" % tensors) from None
    return tensors


def transfer_fields(from_mesh, fields, to_mesh, tensors=_capi.TENSORS_AUTO, num_threads=0):
    """`fields`, given at the points of from_mesh, carried to the points of to_mesh: new Fields.
    Scalars and vectors interpolated linearly, tensors as `tensors` says: TENSORS_AUTO ("auto",
    log space when every tensor of the field is SPD), TENSORS_LOG_EUCLIDEAN ("log_euclidean") or
    TENSORS_LINEAR ("linear"). num_threads: the task arena's threads (0: all cores; the same
    values on any number)."""
    _require(from_mesh, Mesh, "from_mesh")
    _require(fields, Fields, "fields")
    _require(to_mesh, Mesh, "to_mesh")
    return Fields._made(lib.anitet_mesh_transfer_fields_ext, from_mesh, fields, to_mesh, _tensors(tensors),
                        num_threads)


def _mesh_transfer_fields(self, fields, to, tensors=_capi.TENSORS_AUTO, num_threads=0):
    """`fields` (at this mesh's points) carried to the points of the Mesh `to`: see
    anitet.transfer_fields."""
    return transfer_fields(self, fields, to, tensors, num_threads)


Mesh.transfer_fields = _mesh_transfer_fields
