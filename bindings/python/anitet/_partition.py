"""Partitions: a Mesh in parts for the ranks of a solver (include/anitet.h, "Partitions").

    partition = mesh.partition(4, ghost_layers=1)     # or anitet.partition_mesh(mesh, 4)
    print(partition.info())                            # edge cut, imbalance, ...
    part = partition[2]                                 # what rank 2 holds
    xyz, tets = part.points, part.tets                  # NumPy views, no copy
    for q, send in part.halo(anitet.HALO_VERTEX_SEND).items(): ...

A part's arrays are NumPy views over the library's memory (read-only, 0-based ids): no copy. Each
view keeps that memory alive, so a view stays valid after its Part or Partition is closed or
garbage collected; the memory goes with the last of them. Without NumPy the arrays are lists
(copies). The orders (own items first, ascending global ids, halo lists that two neighbours
agree on) are those of the header.
"""
import ctypes
import sys
from ctypes import byref, c_double, c_int32, c_int64, c_void_p

from . import _capi
from ._api import Mesh, _check, _Figures, _np
from ._capi import lib

_ORDER = "<" if sys.byteorder == "little" else ">"  # the library's memory: native order
_CTYPE = {_capi.TYPE_INT32: c_int32, _capi.TYPE_INT64: c_int64, _capi.TYPE_DOUBLE: c_double}
_WIDTH = {_capi.PART_POINTS: 3, _capi.PART_TETS: 4, _capi.PART_BOUNDARY_TRIANGLES: 3}
# The lent arrays of each halo list: (offsets, items).
_HALO_ARRAYS = {
    _capi.HALO_VERTEX_SEND: (_capi.PART_VERTEX_SEND_OFFSETS, _capi.PART_VERTEX_SEND),
    _capi.HALO_VERTEX_RECV: (_capi.PART_VERTEX_RECV_OFFSETS, _capi.PART_VERTEX_RECV),
    _capi.HALO_TET_SEND: (_capi.PART_TET_SEND_OFFSETS, _capi.PART_TET_SEND),
    _capi.HALO_TET_RECV: (_capi.PART_TET_RECV_OFFSETS, _capi.PART_TET_RECV),
}


class _Memory:
    """Owns one C handle and frees it when the last Python object that uses it goes: the Partition
    or Part, the parts lent by a partition, and every NumPy view of their arrays."""

    def __init__(self, ptr, destroy):
        self.ptr = ptr
        self._destroy = destroy

    def __del__(self):
        try:
            if self.ptr:
                self._destroy(self.ptr)
                self.ptr = None
        except Exception:  # interpreter shutdown: the library may be gone already
            pass


class _View:
    """The NumPy array interface of memory the library owns; holds the memory's owner."""

    def __init__(self, address, shape, typestr, memory):
        self.__array_interface__ = {"data": (address, True), "shape": shape, "typestr": typestr,
                                    "version": 3}
        self._memory = memory


class PartitionInfo(_Figures):
    """The numbers of anitet_partition_info (version 1)."""

    FIELDS = ("num_parts", "ghost_layers", "empty_parts", "num_tets", "edge_cut",
              "interface_vertices", "imbalance", "total_weight", "max_part_weight")


class Part:
    """One part: what one rank holds (lent by a Partition, or one's own from from_bytes)."""

    def __init__(self, ptr, memory):
        self._ptr = ptr
        self._memory = memory  # the partition's (lent part) or its own

    @property
    def _as_parameter_(self):
        return self._ptr if self._memory is not None else None  # closed: NULL to the library

    def close(self):
        """Drops this object's hold on the part's memory (views keep theirs)."""
        self._memory = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @classmethod
    def from_bytes(cls, data):
        """A part from the bytes of to_bytes (checked: AnitetError ERR_PARSE when they are not)."""
        data = bytes(data)
        out = c_void_p()
        _check(lib.anitet_part_deserialize(data, len(data), byref(out)))
        return cls(out.value, _Memory(out.value, lib.anitet_part_destroy))

    def to_bytes(self):
        """The part as bytes (for from_bytes on a machine of the same byte order)."""
        needed = c_int64(0)
        _check(lib.anitet_part_serialize(self, None, 0, byref(needed)))
        buf = ctypes.create_string_buffer(needed.value)
        _check(lib.anitet_part_serialize(self, buf, needed.value, None))
        return buf.raw

    def _numbers(self):
        index, parts, neighbours, layers = c_int32(), c_int32(), c_int32(), c_int32()
        _check(lib.anitet_part_get_index(self, byref(index), byref(parts), byref(neighbours),
                                         byref(layers)))
        return index.value, parts.value, neighbours.value, layers.value

    @property
    def index(self):
        """This part's number (0-based: its rank)."""
        return self._numbers()[0]

    @property
    def num_parts(self):
        return self._numbers()[1]

    @property
    def ghost_layers(self):
        return self._numbers()[3]

    def counts(self):
        """(vertices, own vertices, tets, own tets, boundary triangles, own boundary triangles);
        own items come first in each array."""
        c = [c_int64() for _ in range(6)]
        _check(lib.anitet_part_get_counts(self, *[byref(x) for x in c]))
        return tuple(x.value for x in c)

    def array(self, which):
        """The lent array `which` (a PART_* constant): a read-only NumPy view shaped (n, 3) for
        points and boundary triangles, (n, 4) for tets, else (n,); 0-based ids. A list (copy)
        without NumPy."""
        data, count, kind = c_void_p(), c_int64(), c_int32()
        _check(lib.anitet_part_get_array(self, which, byref(data), byref(count), byref(kind)))
        width = _WIDTH.get(which, 1)
        n = count.value
        ctype = _CTYPE[kind.value]
        if _np is not None:
            typestr = _ORDER + {c_int32: "i4", c_int64: "i8", c_double: "f8"}[ctype]
            shape = (n // width, width) if width > 1 else (n,)
            if n == 0:
                return _np.zeros(shape, dtype=typestr)
            view = _np.asarray(_View(data.value, shape, typestr, self._memory))
            view.flags.writeable = False
            return view
        if n == 0:
            return []
        values = (ctype * n).from_address(data.value)[:]  # a copy, the memory not needed after
        if width == 1:
            return values
        return [tuple(values[i:i + width]) for i in range(0, n, width)]

    points = property(lambda self: self.array(_capi.PART_POINTS), doc="(n, 3) coordinates")
    tets = property(lambda self: self.array(_capi.PART_TETS), doc="(n, 4) local vertex ids")
    regions = property(lambda self: self.array(_capi.PART_REGIONS))
    vertex_global_ids = property(lambda self: self.array(_capi.PART_VERTEX_GLOBAL_IDS))
    vertex_owners = property(lambda self: self.array(_capi.PART_VERTEX_OWNERS))
    tet_global_ids = property(lambda self: self.array(_capi.PART_TET_GLOBAL_IDS))
    tet_owners = property(lambda self: self.array(_capi.PART_TET_OWNERS))
    tet_layers = property(lambda self: self.array(_capi.PART_TET_LAYERS),
                          doc="0 for an own tet, k for ghost layer k")
    boundary_triangles = property(lambda self: self.array(_capi.PART_BOUNDARY_TRIANGLES))
    boundary_patches = property(lambda self: self.array(_capi.PART_BOUNDARY_PATCHES))
    boundary_global_ids = property(lambda self: self.array(_capi.PART_BOUNDARY_GLOBAL_IDS))
    neighbours = property(lambda self: self.array(_capi.PART_NEIGHBOURS), doc="ascending")

    def halo(self, which):
        """Halo list `which` (a HALO_* constant) as {neighbour part: local ids}, neighbours
        ascending, each list by ascending global id (views with NumPy)."""
        offsets_id, items_id = _HALO_ARRAYS[which]
        offsets, items = self.array(offsets_id), self.array(items_id)
        return {int(q): items[int(offsets[i]):int(offsets[i + 1])]
                for i, q in enumerate(self.neighbours)}

    def __repr__(self):
        index, parts, neighbours, layers = self._numbers()
        return "Part(%d of %d, %d neighbours, counts %r)" % (index, parts, neighbours, self.counts())


class Partition:
    """A mesh cut into parts (Mesh.partition or partition_mesh): len() parts, indexable."""

    def __init__(self, ptr):
        self._memory = _Memory(ptr, lib.anitet_partition_destroy)

    @property
    def _as_parameter_(self):
        return self._memory.ptr if self._memory is not None else None

    def close(self):
        """Drops this object's hold on the partition (its parts and views keep theirs)."""
        self._memory = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def info(self):
        info = _capi.CPartitionInfo()
        info.version = _capi.PARTITION_INFO_VERSION
        _check(lib.anitet_partition_get_info(self, byref(info)))
        return PartitionInfo(info)

    def __len__(self):
        return self.info().num_parts

    def tet_parts(self):
        """The part of each tet of the mesh (a copy)."""
        n = self.info().num_tets
        if _np is not None:
            out = _np.empty(n, dtype=_np.int32)
            _check(lib.anitet_partition_get_tet_parts(self, out.ctypes.data_as(ctypes.POINTER(c_int32)), n))
            return out
        buf = (c_int32 * max(n, 1))()
        _check(lib.anitet_partition_get_tet_parts(self, buf, n))
        return list(buf[:n])

    def part(self, index):
        """Part `index` (0 .. len - 1), lent: it keeps the partition's memory alive."""
        out = c_void_p()
        _check(lib.anitet_partition_get_part(self, index, byref(out)))
        return Part(out.value, self._memory)

    def __getitem__(self, index):
        if not 0 <= index < len(self):
            raise IndexError("part %d of %d" % (index, len(self)))
        return self.part(index)

    def __iter__(self):
        return (self.part(i) for i in range(len(self)))


def partition_mesh(mesh, num_parts, ghost_layers=1, imbalance=0.03, tet_weights=None, num_threads=0):
    """Cuts `mesh` into num_parts parts with METIS (the dual graph: tets sharing a face) and
    builds each part with `ghost_layers` layers of ghost tets. tet_weights: one weight per tet
    (>= 0) or None; imbalance: the heaviest part may weigh (1 + imbalance) times the mean."""
    if not isinstance(mesh, Mesh):
        raise TypeError("mesh must be an anitet.Mesh, not %s" % type(mesh).__name__)
    o = _capi.CPartitionOptions()
    _check(lib.anitet_partition_options_init(byref(o), _capi.PARTITION_OPTIONS_VERSION))
    o.num_threads = num_threads
    o.ghost_layers = ghost_layers
    o.imbalance = imbalance
    keep = None
    if tet_weights is not None:
        if _np is not None:
            keep = _np.ascontiguousarray(tet_weights, dtype=_np.float64).ravel()
            o.tet_weights = keep.ctypes.data_as(ctypes.POINTER(c_double))
            o.num_tet_weights = keep.size
        else:
            keep = (c_double * len(tet_weights))(*tet_weights)
            o.tet_weights = ctypes.cast(keep, ctypes.POINTER(c_double))
            o.num_tet_weights = len(tet_weights)
    out = c_void_p()
    _check(lib.anitet_mesh_partition(mesh, num_parts, byref(o), byref(out)))
    del keep  # read during the call only
    return Partition(out.value)


def _mesh_partition(self, num_parts, **options):
    """This mesh in parts: see anitet.partition_mesh."""
    return partition_mesh(self, num_parts, **options)


Mesh.partition = _mesh_partition
