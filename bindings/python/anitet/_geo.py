"""Geographic coordinates (include/anitet.h, "Geographic coordinates"; `anitet mesh --geodetic`).

A surface given as longitude, latitude (degrees) and ellipsoidal height (metres) on WGS84, in
that order as x, y, z, is meshed in a local Cartesian frame in metres:

    frame = anitet.GeoFrame.centred(geodetic)          # ENU at the centre of its box
    local = anitet.Surface.from_arrays(lonlat_h, tris)  # a copy to move
    local.to_local(frame)
    mesh = local.mesh(anitet.Metric.uniform(300.0))     # sizes in metres
    mesh.to_geodetic(frame, geodetic)                   # the surface's points come back exactly
"""
from ctypes import byref, c_double, c_int32

from . import _capi
from ._api import Mesh, Surface, _check, _create, _Handle, _require
from ._capi import lib


class GeoFrame(_Handle):
    """A local Cartesian frame on WGS84: GEO_ENU (east-north-up tangent frame at the origin, an
    exact round trip up to rounding) or GEO_UTM (the UTM zone of the origin, the height as z)."""

    _destroy = lib.anitet_geo_frame_destroy

    @classmethod
    def create(cls, lat, lon, height=0.0, kind=_capi.GEO_ENU):
        """A frame of `kind` at the origin (lat, lon in degrees, height in metres)."""
        return _create(cls, lib.anitet_geo_frame_create, kind, lat, lon, height)

    @classmethod
    def centred(cls, surface, kind=_capi.GEO_ENU):
        """A frame at the centre of the bounding box of the surface's (lon, lat, h) points
        (longitudes unwrapped around the first point's), as `anitet mesh --geodetic` without
        --origin."""
        _require(surface, Surface, "surface")
        return _create(cls, lib.anitet_geo_frame_create_centred, kind, surface)

    def _get(self):
        lat, lon, height, zone, north = c_double(), c_double(), c_double(), c_int32(), c_int32()
        _check(lib.anitet_geo_frame_get(self, byref(lat), byref(lon), byref(height), byref(zone),
                                        byref(north)))
        return lat.value, lon.value, height.value, zone.value, north.value

    @property
    def origin(self):
        """(lat, lon, height) of the origin."""
        return self._get()[:3]

    @property
    def utm_zone(self):
        """(zone 1-60, north: bool) of a GEO_UTM frame; None for a GEO_ENU one."""
        zone, north = self._get()[3:]
        return (zone, bool(north)) if zone else None

    def __repr__(self):
        if not self._ptr:
            return "GeoFrame(closed)"
        return "GeoFrame(origin=%r, utm_zone=%r)" % (self.origin, self.utm_zone)


def _surface_to_local(self, frame):
    """Moves the points from (lon, lat, h) to the GeoFrame's x, y, z in metres, in place; a point
    out of range raises AnitetError naming it, and then no point is moved."""
    _require(frame, GeoFrame, "frame")
    _check(lib.anitet_surface_to_local(self, frame))


def _mesh_to_local(self, frame):
    """Moves the points from (lon, lat, h) to the GeoFrame, in place: a background mesh of a .sol
    metric, say (Metric.read_on_mesh; its metric values are not converted)."""
    _require(frame, GeoFrame, "frame")
    _check(lib.anitet_mesh_to_local(self, frame))


def _mesh_to_geodetic(self, frame, geodetic_surface=None):
    """Moves the points from the GeoFrame back to (lon, lat, h), longitudes in [-180, 180]
    (`anitet mesh --geodetic-output`). geodetic_surface: the Surface, before to_local, that this
    mesh was meshed from; its points then come back exactly (AnitetError for a mesh no run made,
    or whose run merged points)."""
    _require(frame, GeoFrame, "frame")
    if geodetic_surface is not None:
        _require(geodetic_surface, Surface, "geodetic_surface")
    _check(lib.anitet_mesh_to_geodetic(self, frame, geodetic_surface))


Surface.to_local = _surface_to_local
Mesh.to_local = _mesh_to_local
Mesh.to_geodetic = _mesh_to_geodetic
