"""Tests of the Python binding (bindings/python) over libanitet.

Environment: PYTHONPATH with bindings/python, ANITET_LIBRARY (the built library), ANITET_HEADER
(include/anitet.h, for the drift checks), ANITET_EXAMPLES_DIR (examples/python, for the sphere),
ANITET_TEST_DATA_DIR (tests/data), ANITET_METRIC_VDB_DIR (the .vdb files of the fixture
make_metric_vdb; optional). ANITET_PYTHON_NUMPY=0 runs the same tests without NumPy.
"""
import collections
import ctypes
import os
import re
import sys
import tempfile
import threading
import unittest

import anitet
from anitet import _capi

sys.path.insert(0, os.environ["ANITET_EXAMPLES_DIR"])
import boundary_layer  # noqa: E402 - the sphere in a box
import mesh_sphere  # noqa: E402 - the examples' sphere

HEADER = os.environ["ANITET_HEADER"]
DATA = os.environ["ANITET_TEST_DATA_DIR"]
UGAWG = os.environ["ANITET_UGAWG_DIR"]

CUBE_POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_TRIS = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (3, 7, 6), (3, 6, 2),
             (0, 4, 7), (0, 7, 3), (1, 2, 6), (1, 6, 5)]


def rows(a):
    """Rows as tuples (or values) whatever the array type."""
    if anitet.HAVE_NUMPY:
        return [tuple(r) if hasattr(r, "__len__") else r for r in a.tolist()]
    return list(a)


def sphere():
    points, tris, patches = mesh_sphere.sphere()
    return anitet.Surface.from_arrays(points, tris, patches), points, tris, patches


class HeaderDrift(unittest.TestCase):
    """The binding's declarations mirror include/anitet.h."""

    @classmethod
    def setUpClass(cls):
        with open(HEADER) as f:
            cls.header = f.read()

    def test_every_function_declared(self):
        declared = re.findall(r"ANITET_API[^;(]*[ *](anitet_[a-z0-9_]+)\(", self.header)
        self.assertGreater(len(declared), 30)
        self.assertEqual(sorted(declared), sorted(_capi._PROTOTYPES))

    def test_constants(self):
        pattern = (r"#define ANITET_((?:ERR_[A-Z_]+|OK|LOG_[A-Z]+|LAYERS_[A-Z_]+|RECOVERY_[A-Z]+|GEO_[A-Z]+|"
                   r"VERSION_MAJOR|VERSION_MINOR|VERSION_PATCH|OPTIONS_VERSION|QUALITY_VERSION|RUN_STATS_VERSION|"
                   r"PARTITION_[A-Z]+_VERSION|ADAPT_[A-Z]+_VERSION|"
                   r"HALO_[A-Z_]+|TYPE_[A-Z0-9]+|PART_[A-Z_]+|MESH2D_OPTIONS_VERSION|GEO_[A-Z]+|"
                   r"PATCH_TYPE_[A-Z_]+|FIELD_KIND_[A-Z_]+|TENSORS_[A-Z_]+|BL_CELLS_[A-Z]+)) \(?(-?\d+)\)?")
        found = re.findall(pattern, self.header)
        self.assertGreater(len(found), 25)
        for name, value in found:
            self.assertEqual(getattr(anitet, name), int(value), name)

    def struct_fields(self, name):
        """[(field, kind)] of a header struct, kind int32_t, int64_t, double or pointer."""
        body = re.search(r"typedef struct %s \{(.*?)\} %s;" % (name, name), self.header, re.S).group(1)
        body = re.sub(r"/\*.*?\*/", "", body, flags=re.S)
        fields = []
        for decl in (d.strip() for d in body.split(";")):
            if decl:
                pointer = "*" in decl or re.match(r"anitet_\w+_fn ", decl)
                name = re.search(r"(\w+)$", decl).group(1)
                fields.append((name, "pointer" if pointer else decl.split()[0]))
        return fields

    @staticmethod
    def ctypes_fields(struct):
        kinds = {ctypes.c_int32: "int32_t", ctypes.c_int64: "int64_t", ctypes.c_double: "double"}
        return [(name, kinds.get(t, "pointer")) for name, t in struct._fields_]

    def test_struct_layouts(self):
        for struct, name in ((_capi.COptions, "anitet_options"), (_capi.CQuality, "anitet_quality"),
                             (_capi.CRunStats, "anitet_run_stats"),
                             (_capi.CPartitionOptions, "anitet_partition_options"),
                             (_capi.CPartitionInfo, "anitet_partition_info"),
                             (_capi.CAdaptOptions, "anitet_adapt_options"),
                             (_capi.CAdaptStats, "anitet_adapt_stats")):
            self.assertEqual(self.ctypes_fields(struct), self.struct_fields(name), name)
        pointer = ctypes.sizeof(ctypes.c_void_p)
        self.assertEqual(ctypes.sizeof(_capi.CPartitionOptions), 24 + pointer + 8)
        self.assertEqual(ctypes.sizeof(_capi.CPartitionInfo), 64)
        self.assertEqual(self.ctypes_fields(_capi.CMesh2dOptions), self.struct_fields("anitet_mesh2d_options"))
        self.assertEqual(ctypes.sizeof(_capi.CRunStats), 264)
        # Version 1 ends after the four pointers; version 2 adds 32 bytes, version 3 seven 8-byte
        # fields, eight 4-byte ones and a pointer, version 4 two 4-byte fields and a pointer,
        # version 5 a double.
        self.assertEqual(_capi.COptions.layers.offset, 24 + 4 * pointer)
        self.assertEqual(_capi.COptions.attempts_seconds.offset, _capi.COptions.layers.offset + 32)
        self.assertEqual(_capi.COptions.bl_num_slide_patches.offset,
                         _capi.COptions.attempts_seconds.offset + 88 + pointer)
        self.assertEqual(_capi.COptions.bl_sizing_growth.offset,
                         _capi.COptions.bl_num_slide_patches.offset + 8 + pointer)
        self.assertEqual(ctypes.sizeof(_capi.COptions), _capi.COptions.bl_sizing_growth.offset + 8)

    def test_options_defaults_are_the_library_s(self):
        c = _capi.COptions()
        self.assertEqual(_capi.lib.anitet_options_init(ctypes.byref(c), _capi.OPTIONS_VERSION), 0)
        python = anitet.Options()
        skip = ("version", "reserved0", "progress", "progress_user_data", "log",
                "log_user_data", "bl_num_patches", "bl_patches", "bl_num_slide_patches", "bl_slide_patches")
        for name, _ in _capi.COptions._fields_:
            if name not in skip:
                self.assertEqual(getattr(python, name), getattr(c, name), name)
        self.assertEqual((c.bl_num_patches, bool(c.bl_patches)), (0, False))
        self.assertEqual((c.bl_num_slide_patches, bool(c.bl_slide_patches)), (0, False))
        self.assertEqual(len(python.bl_patches), 0)
        self.assertEqual(len(python.bl_slide_patches), 0)


class Library(unittest.TestCase):
    def test_version(self):
        self.assertEqual(anitet.version(), anitet.__version__)
        self.assertEqual(anitet.version_number(), 100)
        self.assertEqual(anitet.error_name(anitet.ERR_OPEN_BOUNDARY), "open_boundary")


class Surfaces(unittest.TestCase):
    def test_round_trip(self):
        s = anitet.Surface.from_arrays(CUBE_POINTS, CUBE_TRIS, list(range(12)))
        self.assertEqual(s.counts(), (8, 12))
        self.assertEqual(rows(s.points()), [tuple(float(c) for c in p) for p in CUBE_POINTS])
        self.assertEqual(rows(s.triangles()), CUBE_TRIS)
        self.assertEqual(rows(s.triangles(index_base=1)), [tuple(v + 1 for v in t) for t in CUBE_TRIS])
        self.assertEqual(rows(s.patches()), list(range(12)))
        s.validate()
        self.assertEqual(s.problem_count(anitet.ERR_OPEN_BOUNDARY), 0)
        self.assertIn("problems", s.validation_report())

    def test_one_based(self):
        s = anitet.Surface.from_arrays(CUBE_POINTS, [tuple(v + 1 for v in t) for t in CUBE_TRIS],
                                       index_base=1)
        self.assertEqual(rows(s.triangles()), CUBE_TRIS)
        self.assertEqual(rows(s.patches()), [0] * 12)

    def test_errors(self):
        bad = list(CUBE_TRIS)
        bad[2] = (4, 5, 8)
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.Surface.from_arrays(CUBE_POINTS, bad)
        self.assertEqual(e.exception.code, anitet.ERR_BAD_INDEX)
        self.assertEqual(e.exception.name, "bad_index")
        self.assertIn("triangle 2 refers to vertex 8", e.exception.message)
        with self.assertRaises(ValueError):
            anitet.Surface.from_arrays(CUBE_POINTS, [(0, 1)])
        with self.assertRaises(ValueError):
            anitet.Surface.from_arrays(CUBE_POINTS, CUBE_TRIS, index_base=2)
        with self.assertRaises(TypeError):
            anitet.Surface.from_arrays(CUBE_POINTS, [(0.5, 1, 2)])
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.Surface.from_arrays([], [])
        self.assertEqual(e.exception.code, anitet.ERR_EMPTY_INPUT)
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.Surface.read(os.path.join(DATA, "io", "no_such_file.off"))
        self.assertEqual(e.exception.code, anitet.ERR_FILE_NOT_FOUND)

    def test_open_surface(self):
        s = anitet.Surface.from_arrays(CUBE_POINTS, CUBE_TRIS[:11])
        with self.assertRaises(anitet.AnitetError) as e:
            s.validate()
        self.assertEqual(e.exception.code, anitet.ERR_OPEN_BOUNDARY)
        self.assertEqual(s.problem_count(anitet.ERR_OPEN_BOUNDARY), 3)
        with self.assertRaises(anitet.AnitetError) as e:
            s.mesh()
        self.assertEqual(e.exception.code, anitet.ERR_OPEN_BOUNDARY)

    def test_closed_handle(self):
        s = anitet.Surface.from_arrays(CUBE_POINTS, CUBE_TRIS)
        with s:
            pass
        with self.assertRaises(anitet.AnitetError) as e:  # a closed handle is NULL to the library
            s.counts()
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
        s.close()  # twice is fine


class Meshing(unittest.TestCase):
    def test_sphere(self):
        s, points, tris, patches = sphere()
        m = anitet.mesh_surface(s)
        n, nt, nb = m.counts()
        self.assertEqual(nb, len(tris))
        self.assertGreater(nt, n)
        self.assertEqual(rows(m.points())[:len(points)], points)
        self.assertEqual(rows(m.boundary_triangles()), tris)
        self.assertEqual(rows(m.boundary_patches()), patches)
        tets = rows(m.tets())
        self.assertEqual(len(tets), nt)
        self.assertEqual(rows(m.tets(index_base=1))[0], tuple(v + 1 for v in tets[0]))
        self.assertEqual(len(set(rows(m.regions()))), 1)
        self.assertIsNone(m.metric())
        q = m.quality(s)
        self.assertTrue(q.valid)
        self.assertTrue(q.boundary_constrained)
        self.assertEqual(q.nonpositive_tets, 0)
        self.assertEqual(q.tets, nt)
        self.assertEqual(m.quality_report(s)["tets"], nt)

    def test_progress_log_and_cancel(self):
        s = sphere()[0]
        stages, logs = [], []
        m = s.mesh(progress=lambda stage, f: stages.append((stage, f)),
                   log=lambda level, text: logs.append((level, text)))
        names = [st for st, _ in stages]
        self.assertEqual(names[:4], ["validate", "layers", "recovery", "coupling"])
        self.assertEqual(names[-1], "done")
        self.assertEqual(stages[-1][1], 1.0)
        self.assertTrue(any("stage layers" in text for _, text in logs))
        m.close()
        # Returning False cancels.
        seen = []

        def stop_at_recovery(stage, fraction):
            seen.append(stage)
            return stage != "recovery"

        with self.assertRaises(anitet.AnitetError) as e:
            s.mesh(progress=stop_at_recovery)
        self.assertEqual(e.exception.code, anitet.ERR_CANCELLED)
        self.assertEqual(seen, ["validate", "layers", "recovery"])

        # An exception in a callback cancels and comes back as itself.
        def broken(stage, fraction):
            raise KeyError(stage)

        with self.assertRaises(KeyError):
            s.mesh(progress=broken)

    def test_options(self):
        s = sphere()[0]
        one = s.mesh(options=anitet.Options(layers=1, refine=False, optimize=False))
        two = s.mesh(layers=2, refine=False, optimize=False)
        self.assertNotEqual(one.num_tets, two.num_tets)
        with self.assertRaises(anitet.AnitetError) as e:
            s.mesh(layers=0)
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
        self.assertIn("layers is 0", e.exception.message)
        with self.assertRaises(TypeError):
            s.mesh(options=anitet.Options(), layers=1)
        with self.assertRaises(TypeError):
            s.mesh(anitet.Options())  # the first argument is the metric

    def test_deterministic_and_threads(self):
        s = sphere()[0]
        alone = s.mesh()
        results = [None, None]

        def work(i):
            surface = sphere()[0]
            results[i] = surface.mesh()

        threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for m in results:
            self.assertEqual(m.counts(), alone.counts())
            self.assertEqual(rows(m.points()), rows(alone.points()))
            self.assertEqual(rows(m.tets()), rows(alone.tets()))


    def test_options_v3(self):
        s = sphere()[0]
        plain = s.mesh()
        self.assertGreater(s.mesh(hmax=0.2).num_tets, 2 * plain.num_tets)
        m = s.mesh(recovery=anitet.RECOVERY_SPLIT, retry_layer_counts=False)
        self.assertEqual(m.run_stats.recovery_strategy, anitet.RECOVERY_SPLIT)
        self.assertEqual(m.run_stats.layers_retries, 0)
        for fields, words in (({"recovery": 3}, "recovery is 3"),
                              ({"hmin": 2.0, "hmax": 1.0}, "hmin"),
                              ({"hgrad": 0.5}, "hgrad"),
                              ({"attempts_seconds": -1.0}, "attempts_seconds"),
                              ({"anisotropic_cycles": 11}, "anisotropic_cycles is 11"),
                              ({"bl_sizing": True}, "bl_sizing"),
                              ({"hmax": 0.2, "max_tets": 100}, "100")):
            with self.assertRaises(anitet.AnitetError) as e:
                s.mesh(options=anitet.Options(**fields))
            self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT, fields)
            self.assertIn(words, e.exception.message)
        with self.assertRaises(TypeError):
            # Version 3's fields are keywords only.
            anitet.Options(1, True, True, True, 1, 0, 0.0, True, True, 1.0, None, None, 240.0)
        with self.assertRaises(TypeError):
            s.mesh(bl_wall=[1])  # no such option
        # A plain run: its stats and report, no boundary layer.
        stats = plain.run_stats
        self.assertEqual((stats.vertices, stats.tets), plain.counts()[:2])
        self.assertEqual((stats.bl_layers, stats.bl_wall_vertices, stats.bl_tets), (0, 0, 0))
        self.assertGreater(stats.seconds, 0)
        self.assertIn(stats.recovery_strategy, (anitet.RECOVERY_SPLIT, anitet.RECOVERY_FUZZY))
        self.assertIsInstance(stats.refine_stopped_at_pass_cap, bool)
        self.assertEqual(stats.as_dict()["tets"], stats.tets)
        report = plain.run_report()
        self.assertEqual([st["stage"] for st in report["stages"]][:2], ["layers", "recovery"])
        self.assertEqual(report["notices"], [])


class BoundaryLayers(unittest.TestCase):
    """Options version 3's boundary layer on the sphere inside a box, the run's report, and the
    patch names of the written files."""

    WALLS = dict(bl_first_height=0.02, bl_growth=1.25, bl_layers=4)

    @classmethod
    def setUpClass(cls):
        cls.surface = anitet.Surface.from_arrays(*boundary_layer.sphere_in_box())
        cls.mesh = cls.surface.mesh(bl_patches=[1, 2, 3], **cls.WALLS)

    def test_report(self):
        s, n = self.mesh.run_stats, mesh_sphere.NPOINTS
        self.assertEqual((s.vertices, s.tets), self.mesh.counts()[:2])
        self.assertEqual((s.bl_layers, s.bl_wall_vertices, s.bl_full_columns), (4, n, n))
        self.assertGreaterEqual(s.bl_nominal_columns, 0.9 * n)
        self.assertGreaterEqual(s.bl_tets, 3 * 4 * mesh_sphere.NTRI)
        self.assertAlmostEqual(s.bl_first_height_mean, 0.02, delta=0.002)
        self.assertTrue(0 < s.bl_first_height_min <= s.bl_first_height_max)
        self.assertAlmostEqual(s.bl_growth_mean, 1.25, delta=0.05)
        self.assertLessEqual(s.bl_max_height_error, 0.1)
        report = self.mesh.run_report()
        self.assertEqual(report["boundary_layer"]["layers"], 4)
        self.assertEqual(report["boundary_layer"]["columns_reaching"][4], n)
        self.assertEqual(report["boundary_layer"]["tets"], s.bl_tets)
        q = self.mesh.quality(self.surface)
        self.assertTrue(q.valid and q.boundary_constrained)

    def test_columns_csv_and_mitre(self):
        # Mesh.write_bl_columns: `anitet mesh --bl-columns`' CSV, a line per wall vertex (on the
        # sphere, patches 1-3). bl_mitre reaches the struct; without walls it is refused.
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "columns.csv")
            self.mesh.write_bl_columns(path)
            with open(path) as f:
                lines = f.read().splitlines()
        self.assertEqual(lines[0], "x,y,z,layers,first_height,total_height,normal_share,patches")
        self.assertEqual(len(lines) - 1, mesh_sphere.NPOINTS)
        for line in lines[1:]:
            fields = line.split(",")
            self.assertEqual(int(fields[3]), 4)
            self.assertTrue(set(fields[7].split()) <= {"1", "2", "3"}, line)
        self.assertEqual(anitet._api._options_arg(None, {"bl_mitre": True}).struct.bl_mitre, 1)
        with self.assertRaises(anitet.AnitetError) as e:
            self.surface.mesh(bl_mitre=True)
        self.assertIn("bl_mitre needs boundary-layer walls", e.exception.message)
        with self.assertRaises(anitet.AnitetError) as e:
            self.surface.mesh(refine=False, optimize=False).write_bl_columns("unused.csv")
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)

    def test_walls_in_every_form(self):
        # One int, a tuple, an int32 NumPy array (passed without a copy): the same struct.
        scope = anitet._api._options_arg(None, {"bl_patches": 2})
        self.assertEqual((scope.struct.bl_num_patches, scope.struct.bl_patches[0]), (1, 2))
        scope = anitet._api._options_arg(anitet.Options(bl_patches=()), {})
        self.assertEqual((scope.struct.bl_num_patches, bool(scope.struct.bl_patches)), (0, False))
        if anitet.HAVE_NUMPY:
            import numpy
            walls = numpy.array([1, 2, 3], dtype=numpy.int32)
            scope = anitet._api._options_arg(None, {"bl_patches": walls})
            self.assertEqual(ctypes.addressof(scope.struct.bl_patches.contents), walls.ctypes.data)
            m = self.surface.mesh(options=anitet.Options(bl_patches=walls, **self.WALLS))
            self.assertEqual(m.run_stats.bl_tets, self.mesh.run_stats.bl_tets)
        with self.assertRaises(TypeError):
            self.surface.mesh(bl_patches=[1.5], **self.WALLS)

    def test_errors(self):
        for fields, words in (({"bl_patches": [1, 7]}, "wall patch label 7"),
                              ({"bl_patches": [1, 2, 3], "bl_first_height": 0.0}, "bl_first_height"),
                              ({"bl_patches": [1, 2, 3], "bl_layers": 0}, "bl_layers"),
                              ({"bl_patches": [1, 2, 3], "bl_growth": 0.5}, "bl_growth")):
            with self.assertRaises(anitet.AnitetError) as e:
                self.surface.mesh(**dict(self.WALLS, **fields))
            self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
            self.assertIn(words, e.exception.message)
        read = anitet.Mesh.read(os.path.join(DATA, "io", "box.mesh"))
        for call in (lambda: read.run_stats, read.run_report, read.run_json):
            with self.assertRaises(anitet.AnitetError) as e:
                call()
            self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
            self.assertIn("not made by anitet_mesher_run", e.exception.message)
        read.close()
        with self.assertRaises(anitet.AnitetError) as e:
            read.run_stats
        self.assertIn("mesh is NULL", e.exception.message)

    def test_patch_names(self):
        m = self.mesh
        self.addCleanup(m.patch_names.clear)
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "names.su2")

            def markers():
                m.write(path)
                with open(path) as f:
                    return re.findall(r"^MARKER_TAG= (\w+)$", f.read(), re.M)

            m.set_patch_name(4, "farfield")
            m.patch_names[2] = "sphere_band"
            self.assertEqual(dict(m.patch_names), {2: "sphere_band", 4: "farfield"})
            self.assertEqual(markers(), ["patch1", "sphere_band", "patch3", "farfield"])
            del m.patch_names[2]
            m.set_patch_name(4, None)
            self.assertEqual(markers(), ["patch1", "patch2", "patch3", "patch4"])
            m.patch_names = {1: "south", 3: "north"}
            self.assertEqual(markers(), ["south", "patch2", "north", "patch4"])
            for label, name, words in ((9, "wall", "patch label 9"), (4, "far field", "far field"),
                                       (4, "", ""), (4, "9lives", "9lives"), (4, "x" * 33, "x" * 33)):
                with self.assertRaises(anitet.AnitetError) as e:
                    m.patch_names[label] = name
                self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
                self.assertIn(words, e.exception.message)
            self.assertEqual(dict(m.patch_names), {1: "south", 3: "north"})  # unchanged by the errors
            with self.assertRaises(KeyError):
                del m.patch_names[2]
            with self.assertRaises(TypeError):
                m.patch_names[2] = None
            # Two labels of one name: the write says so and writes nothing.
            m.patch_names[2] = "south"
            os.remove(path)
            with self.assertRaises(anitet.AnitetError) as e:
                m.write(path)
            self.assertIn("south", e.exception.message)
            self.assertFalse(os.path.exists(path))

    def test_build_layers(self):
        # Stage 1 alone: the input's triangles under their labels, then the new front's under 5.
        t1 = anitet.build_layers(self.surface, bl_patches=[1, 2, 3], bl_first_height=0.02,
                                 bl_growth=1.25, bl_layers=3)
        patches, given = rows(t1.boundary_patches()), boundary_layer.sphere_in_box()[2]
        self.assertEqual(patches[:len(given)], list(given))
        self.assertGreater(len(patches), len(given))
        self.assertEqual(set(patches[len(given):]), {5})
        s, n = t1.run_stats, mesh_sphere.NPOINTS
        self.assertEqual((s.layers_used, s.recovery_strategy, s.refine_passes, s.tets),
                         (1, 0, 0, t1.num_tets))
        self.assertEqual((s.bl_layers, s.bl_wall_vertices, s.bl_full_columns), (3, n, n))
        self.assertTrue(0 < s.bl_tets < s.tets)
        self.assertAlmostEqual(s.bl_first_height_mean, 0.02, delta=0.002)
        self.assertIn("layers", t1.run_report())
        # Pushes one by one: the same T1.
        again = self.surface.build_layers(anitet.Options(bl_patches=(1, 2, 3), bl_first_height=0.02,
                                                         bl_growth=1.25, bl_layers=3,
                                                         push_tasks_min_vertices=0))
        self.assertEqual(again.counts(), t1.counts())
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.build_layers(self.surface, push_tasks_min_vertices=-1)
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
        self.assertIn("push_tasks_min_vertices", e.exception.message)
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.build_layers(anitet.Surface.from_arrays(CUBE_POINTS, CUBE_TRIS[:11]))
        self.assertEqual(e.exception.code, anitet.ERR_OPEN_BOUNDARY)

    def test_bl_sizing_growth(self):
        """Options version 5: bl_sizing_growth 1.3 over the layers' 1.1 coarsens the interior
        faster (fewer tets, on a cheap run); the CLI's errors."""
        cheap = dict(bl_patches=[1, 2, 3], bl_first_height=0.05, bl_growth=1.1, bl_layers=3,
                     bl_sizing=True, size_scale=2.0, optimize=False, anisotropic_cycles=0)
        scope = anitet._api._options_arg(None, dict(cheap, bl_sizing_growth=1.3))
        self.assertEqual(scope.struct.bl_sizing_growth, 1.3)
        layers_growth = self.surface.mesh(**cheap)
        faster = self.surface.mesh(bl_sizing_growth=1.3, **cheap)
        self.assertLess(faster.num_tets, layers_growth.num_tets)
        for fields, words in (({"bl_sizing_growth": 1.05}, "at least bl_growth (1.1)"),
                              ({"bl_sizing_growth": float("nan")}, "bl_sizing_growth is nan"),
                              ({"bl_sizing_growth": 1.3, "bl_sizing": False}, "needs bl_sizing 1")):
            with self.assertRaises(anitet.AnitetError) as e:
                self.surface.mesh(**dict(cheap, **fields))
            self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT, fields)
            self.assertIn(words, e.exception.message)

    def test_bl_first_height(self):
        cf = 0.026 * 1e6 ** (-1.0 / 7.0)
        self.assertAlmostEqual(anitet.bl_first_height(1.0, 1e6, 1.0), 1.0 / (1e6 * (cf / 2) ** 0.5),
                               delta=1e-18)
        for args in ((0.0, 1e6, 1.0), (1.0, float("nan"), 1.0), (1.0, 1e6, -1.0)):
            with self.assertRaises(anitet.AnitetError) as e:
                anitet.bl_first_height(*args)
            self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)


class BlCells(unittest.TestCase):
    """Options.bl_cells "prisms": the sphere's boundary layer as prism cells, on the cheapest run
    (2 layers, no refinement or optimization)."""

    def test_prisms(self):
        surface = anitet.Surface.from_arrays(*boundary_layer.sphere_in_box())
        mesh = surface.mesh(bl_patches=[1, 2, 3], bl_first_height=0.02, bl_layers=2, refine=False,
                            optimize=False, bl_cells="prisms")
        nt = mesh.num_tets
        self.assertEqual(mesh.run_stats.tets, nt)  # the mesh keeps every tet
        self.assertEqual(mesh.num_prisms, 2 * mesh_sphere.NTRI)
        stats = mesh.run_stats  # version 3: the merge's figures
        self.assertEqual(stats.bl_prisms, mesh.num_prisms)
        self.assertEqual(3 * stats.bl_prisms + stats.bl_prism_tets_left, stats.bl_tets)
        prisms, tets, regions = rows(mesh.prisms()), rows(mesh.tets()), list(mesh.regions())
        tet_prism = list(mesh.tet_prisms())
        self.assertEqual(len(tet_prism), nt)
        for t, p in enumerate(tet_prism):
            if p >= 0:
                self.assertTrue(set(tets[t]) <= set(prisms[p]), t)
                self.assertEqual(regions[t], 1)
        self.assertEqual(sorted(collections.Counter(p for p in tet_prism if p >= 0).values()),
                         [3] * mesh.num_prisms)
        self.assertEqual(list(mesh.tet_prisms(index_base=1)), [p + 1 if p >= 0 else -1 for p in tet_prism])
        self.assertEqual(rows(mesh.prisms(index_base=1))[0], tuple(v + 1 for v in prisms[0]))
        with tempfile.TemporaryDirectory() as tmp:
            foam = os.path.join(tmp, "case", "constant", "polyMesh")
            mesh.write(foam)
            with open(os.path.join(foam, "owner")) as f:
                self.assertIn("nCells:%d " % (nt - 2 * mesh.num_prisms), f.read())
            with self.assertRaises(anitet.AnitetError) as caught:
                mesh.write(os.path.join(tmp, "bl.mesh"))
            self.assertEqual(caught.exception.code, anitet.ERR_UNSUPPORTED_FORMAT)
            self.assertIn("prisms", str(caught.exception))
            self.assertFalse(os.path.exists(os.path.join(tmp, "bl.mesh")))

    def test_errors(self):
        surface = anitet.Surface.from_arrays(*boundary_layer.sphere_in_box())
        with self.assertRaises(anitet.AnitetError) as caught:
            surface.mesh(bl_cells="prisms")
        self.assertEqual(caught.exception.code, anitet.ERR_INVALID_ARGUMENT)
        self.assertIn("needs boundary-layer walls", str(caught.exception))
        with self.assertRaises(ValueError):
            surface.mesh(bl_patches=[1, 2, 3], bl_first_height=0.02, bl_cells="hexes")
        with self.assertRaises(anitet.AnitetError) as caught:
            anitet.build_layers(surface, bl_patches=[1, 2, 3], bl_first_height=0.02, bl_cells="prisms")
        self.assertIn("anitet_mesher_run", str(caught.exception))
        mesh = anitet.Mesh.from_arrays([CUBE_POINTS[i] for i in (0, 1, 3, 4)], [(0, 1, 2, 3)])
        self.assertEqual((mesh.num_prisms, len(mesh.prisms())), (0, 0))
        self.assertEqual(list(mesh.tet_prisms()), [-1])


class Metrics(unittest.TestCase):
    def test_uniform_and_analytic(self):
        u = anitet.Metric.uniform(0.5)
        self.assertEqual(u.evaluate(1, 2, 3), (4.0, 0.0, 4.0, 0.0, 0.0, 4.0))
        a = anitet.Metric.analytic(lambda x, y, z: (1.0 + x, 0, 1, 0, 0, 1))
        self.assertEqual(a.evaluate(2, 0, 0), (3.0, 0.0, 1.0, 0.0, 0.0, 1.0))
        with self.assertRaises(anitet.AnitetError):
            anitet.Metric.uniform(-1)

    def test_failing_callback(self):
        def metric(x, y, z):
            if z < 0:
                raise ArithmeticError("below")
            return (1, 0, 1, 0, 0, 1)

        a = anitet.Metric.analytic(metric)
        with self.assertRaises(anitet.AnitetError) as e:
            a.evaluate(0, 0, -1)
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
        self.assertIsInstance(e.exception.__cause__, ArithmeticError)
        with self.assertRaises(anitet.AnitetError) as e:
            sphere()[0].mesh(a)
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
        self.assertIn("metric callback returned", e.exception.message)

    def test_mesh_with_metric(self):
        s = sphere()[0]
        m = s.mesh(anitet.Metric.analytic(mesh_sphere.stretched_metric))
        self.assertEqual(m.metric_components, 6)
        values = rows(m.metric())
        self.assertEqual(len(values), m.num_points)
        p = rows(m.points())[5]
        self.assertEqual(values[5], mesh_sphere.stretched_metric(*p))

    def assert_size(self, metric, point, h, places=12):
        t = metric.evaluate(*point)
        for c, expected in enumerate((1 / h**2, 0, 1 / h**2, 0, 0, 1 / h**2)):
            self.assertAlmostEqual(t[c] * h**2, expected * h**2, places=places)

    def test_from_points(self):
        background = anitet.Mesh.read(os.path.join(DATA, "io", "box.mesh"))  # 8 points, 6 tets
        sizes = anitet.Metric.from_points(background, [0.25] * 8)
        self.assert_size(sizes, (0.5, 0.05, 1.0), 0.25)
        tensors = anitet.Metric.from_points(background, [(100, 0, 25, 0, 0, 6.25)] * 8)
        t = tensors.evaluate(1.0, 0.02, 0.5)
        self.assertAlmostEqual(t[0], 100, places=10)
        self.assertAlmostEqual(t[2], 25, places=10)
        self.assertAlmostEqual(t[5], 6.25, places=10)
        for values, components, text in (([0.25] * 7, None, "num_values is 7"),
                                         ([0.25] * 8, 3, "components is 3"),
                                         ([0.25] * 7 + [-1.0], None, "point 7")):
            with self.assertRaises(anitet.AnitetError) as e:
                anitet.Metric.from_points(background, values, components)
            self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
            self.assertIn(text, e.exception.message)
        with self.assertRaises(TypeError):
            anitet.Metric.from_points(None, [0.25] * 8)

    def test_read_sol_and_mesh(self):
        background = anitet.Mesh.read(os.path.join(DATA, "io", "box.mesh"))
        background.set_metric([0.25] * 8)
        with tempfile.TemporaryDirectory() as d:
            sol, mesh = os.path.join(d, "bg.sol"), os.path.join(d, "bg.mesh")
            background.write(mesh)
            background.write_metric(sol)
            metric = anitet.Metric.read(sol, mesh)
            for path, bg, code in ((sol, None, anitet.ERR_INVALID_ARGUMENT),
                                   (os.path.join(d, "missing.sol"), mesh, anitet.ERR_FILE_NOT_FOUND),
                                   (sol, os.path.join(d, "missing.mesh"), anitet.ERR_FILE_NOT_FOUND),
                                   (mesh, None, anitet.ERR_UNSUPPORTED_FORMAT)):
                with self.assertRaises(anitet.AnitetError) as e:
                    anitet.Metric.read(path, bg)
                self.assertEqual(e.exception.code, code)
        self.assert_size(metric, (0.7, 0.03, 0.2), 0.25)  # the file is no longer needed
        m = sphere()[0].mesh(metric)
        self.assertEqual(m.metric_components, 6)
        for t in rows(m.metric()):
            self.assertAlmostEqual(t[0], 16.0, places=9)

    @unittest.skipUnless(os.environ.get("ANITET_METRIC_VDB_DIR"), "no .vdb fixture directory")
    def test_read_vdb(self):
        d = os.environ["ANITET_METRIC_VDB_DIR"]
        metric = anitet.Metric.read(os.path.join(d, "size_linear.vdb"))  # h = 0.2 + 0.1 x
        self.assert_size(metric, (0.5, 0.3, 0.7), 0.25)
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.Metric.read(os.path.join(d, "size_linear.vdb"), os.path.join(DATA, "io", "box.mesh"))
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)

    def test_surface_sizing_and_write(self):
        s = sphere()[0]
        field = anitet.Metric.surface_sizing(s, hmax=0.1)  # the field mesh_surface follows, bounded
        t = field.evaluate(0, 0, 0)
        self.assertGreaterEqual(t[0], 100 * (1 - 1e-6))
        self.assertEqual(len(anitet.Metric.surface_sizing(s).evaluate(0, 0, 0)), 6)
        uniform = anitet.Metric.uniform(0.3)
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "sizing.vdb")
            field.write(path)  # a grid: written as it is
            back = anitet.Metric.read(path).evaluate(0, 0, 0)
            for c in (0, 2, 5):
                self.assertAlmostEqual(back[c] / t[c], 1.0, delta=1e-5)
            with self.assertRaises(anitet.AnitetError) as e:
                uniform.write(os.path.join(d, "uniform.vdb"))  # sampled: needs a box
            self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
            self.assertIn("box_of", e.exception.message)
            uniform.write(os.path.join(d, "uniform.vdb"), box_of=s)
            self.assert_size(anitet.Metric.read(os.path.join(d, "uniform.vdb")), (0.2, -0.3, 0.1), 0.3,
                             places=4)
            with self.assertRaises(anitet.AnitetError) as e:
                uniform.write(os.path.join(d, "uniform.sol"), s)
            self.assertEqual(e.exception.code, anitet.ERR_UNSUPPORTED_FORMAT)
            with self.assertRaises(TypeError):
                uniform.write(os.path.join(d, "uniform.vdb"), box_of=uniform)
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.Metric.surface_sizing(s, hgrad=0.5)
        self.assertIn("hgrad", e.exception.message)
        with self.assertRaises(TypeError):
            anitet.Metric.surface_sizing(None)

    def test_sample_and_read_on_mesh(self):
        mesh = anitet.Mesh.read(os.path.join(DATA, "io", "box.mesh"))  # x in [0, 1]

        def stretched(x, y, z):
            if x > 1.5:
                raise ArithmeticError("beyond x = 1.5")
            return (100, 0, 4, 0, 0, 4)

        mesh.sample_metric(anitet.Metric.uniform(0.25))
        self.assertEqual(rows(mesh.metric()), [0.25] * 8)  # sizes where isotropic
        stretched_metric = anitet.Metric.analytic(stretched)
        mesh.sample_metric(stretched_metric)
        self.assertEqual(rows(mesh.metric()), [(100, 0, 4, 0, 0, 4)] * 8)
        with tempfile.TemporaryDirectory() as d:
            sol = os.path.join(d, "sampled.sol")
            mesh.write_metric(sol)
            t = anitet.Metric.read_on_mesh(sol, mesh).evaluate(0.5, 0.05, 0.5)
            self.assertAlmostEqual(t[0], 100, places=9)
            self.assertAlmostEqual(t[2], 4, places=9)
            for path, code in ((os.path.join(d, "missing.sol"), anitet.ERR_FILE_NOT_FOUND),
                               (os.path.join(d, "sampled.vdb"), anitet.ERR_UNSUPPORTED_FORMAT)):
                with self.assertRaises(anitet.AnitetError) as e:
                    anitet.Metric.read_on_mesh(path, mesh)
                self.assertEqual(e.exception.code, code)
            with self.assertRaises(TypeError):
                anitet.Metric.read_on_mesh(sol, None)
        # A callback failing at a point: AnitetError naming it, the metric unchanged.
        far = anitet.Mesh.from_arrays([[2 * c for c in p] for p in CUBE_POINTS], [(0, 1, 2, 4)])
        far.sample_metric(anitet.Metric.uniform(0.5))
        with self.assertRaises(anitet.AnitetError) as e:
            far.sample_metric(stretched_metric)
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
        self.assertEqual(far.metric_components, 1)
        with self.assertRaises(TypeError):
            far.sample_metric(None)


class GeoFrames(unittest.TestCase):
    """A surface in longitude, latitude and height meshed in a local frame and moved back."""

    # The unit cube as a box of 0.01 deg x 0.01 deg x 1000 m at (lon 7.44, lat 46.95).
    LONLAT = [(7.44 + 0.01 * x, 46.95 + 0.01 * y, 1000.0 * z) for x, y, z in CUBE_POINTS]

    def test_mesh_in_a_local_frame(self):
        geo = anitet.Surface.from_arrays(self.LONLAT, CUBE_TRIS)
        local = anitet.Surface.from_arrays(self.LONLAT, CUBE_TRIS)
        frame = anitet.GeoFrame.centred(local)
        lat, lon, h = frame.origin
        self.assertAlmostEqual(lat, 46.955, places=9)
        self.assertAlmostEqual(lon, 7.445, places=9)
        self.assertAlmostEqual(h, 500.0, places=9)
        self.assertIsNone(frame.utm_zone)
        local.to_local(frame)
        p = rows(local.points())  # metres: about 760 m east-west, 1112 north-south, 1000 high
        self.assertAlmostEqual(p[1][0] - p[0][0], 760.0, delta=10.0)
        self.assertAlmostEqual(p[3][1] - p[0][1], 1112.0, delta=10.0)
        self.assertAlmostEqual(p[4][2] - p[0][2], 1000.0, delta=1.0)
        mesh = local.mesh(anitet.Metric.uniform(300.0))
        mesh.to_geodetic(frame, geo)
        points = rows(mesh.points())
        self.assertGreater(len(points), 8)
        self.assertEqual(points[:8], self.LONLAT)  # exactly as given
        for x, y, z in points:
            self.assertTrue(7.44 - 1e-9 < x < 7.45 + 1e-9 and 46.95 - 1e-9 < y < 46.96 + 1e-9)
        # UTM: the origin's zone, 32 north at 7.44 E.
        utm = anitet.GeoFrame.create(46.95, 7.44, kind=anitet.GEO_UTM)
        self.assertEqual(utm.utm_zone, (32, True))
        self.assertIn("utm_zone=(32, True)", repr(utm))

    def test_errors(self):
        for args, words in (((46.0, 7.0, 0.0, 7), "kind is 7"), ((95.0, 7.0), "lat"),
                            ((float("nan"), 7.0), "lat")):
            with self.assertRaises(anitet.AnitetError) as e:
                anitet.GeoFrame.create(*args)
            self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
            self.assertIn(words, e.exception.message)
        bad = list(self.LONLAT)
        bad[5] = (bad[5][0], 120.0, bad[5][2])
        s = anitet.Surface.from_arrays(bad, CUBE_TRIS)
        with self.assertRaises(anitet.AnitetError):
            anitet.GeoFrame.centred(s)
        frame = anitet.GeoFrame.create(46.95, 7.44)
        with self.assertRaises(anitet.AnitetError):
            s.to_local(frame)
        self.assertEqual(rows(s.points()), bad)  # nothing moved
        made = anitet.Mesh.from_arrays(self.LONLAT, [(0, 1, 3, 4)])
        made.to_local(frame)
        with self.assertRaises(anitet.AnitetError) as e:
            made.to_geodetic(frame, s)
        self.assertIn("not made by anitet_mesher_run", e.exception.message)
        made.to_geodetic(frame)
        for got, given in zip(rows(made.points()), self.LONLAT):
            for a, b, delta in zip(got, given, (1e-9, 1e-9, 1e-6)):
                self.assertAlmostEqual(a, b, delta=delta)
        for call in (lambda: s.to_local(None), lambda: made.to_geodetic(frame, made),
                     lambda: anitet.GeoFrame.centred(made)):
            with self.assertRaises(TypeError):
                call()
        frame.close()
        self.assertEqual(repr(frame), "GeoFrame(closed)")
        with self.assertRaises(anitet.AnitetError):
            made.to_local(frame)


class Meshes(unittest.TestCase):
    TET = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    FACES = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]

    def test_arrays_metric_files(self):
        m = anitet.Mesh.from_arrays(self.TET, [(0, 1, 2, 3)], regions=[7],
                                    boundary_triangles=self.FACES, boundary_patches=[1, 2, 3, 4])
        self.assertEqual(m.counts(), (4, 1, 4))
        self.assertEqual(rows(m.regions()), [7])
        self.assertEqual(rows(m.boundary_patches()), [1, 2, 3, 4])
        m.set_metric([0.5, 1.0, 1.5, 2.0])
        self.assertEqual(m.metric_components, 1)
        self.assertEqual(rows(m.metric()), [0.5, 1.0, 1.5, 2.0])
        m.set_metric([(1, 0, 1, 0, 0, 1)] * 4)
        self.assertEqual(m.metric_components, 6)
        with self.assertRaises(anitet.AnitetError) as e:
            m.set_metric([1.0, 2.0])
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
        with tempfile.TemporaryDirectory() as d:
            m.write(os.path.join(d, "tet.vtu"))
            m.write_metric(os.path.join(d, "tet.sol"))
            back = anitet.Mesh.read(os.path.join(d, "tet.vtu"))
            self.assertEqual(back.counts()[:2], (4, 1))
            with self.assertRaises(anitet.AnitetError) as e:
                m.write(os.path.join(d, "tet.xyz"))
            self.assertEqual(e.exception.code, anitet.ERR_UNSUPPORTED_FORMAT)
        m.set_metric(None)
        self.assertIsNone(m.metric())
        faces = anitet.Surface.from_arrays(self.TET, self.FACES)
        q = m.quality(faces)
        self.assertTrue(q.valid and q.boundary_constrained)
        self.assertEqual(q.as_dict()["tets"], 1)
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.Mesh.from_arrays(self.TET, [(0, 1, 2, 4)])
        self.assertEqual(e.exception.code, anitet.ERR_BAD_INDEX)

    def test_read(self):
        m = anitet.Mesh.read(os.path.join(DATA, "io", "box.mesh"))
        self.assertEqual(m.counts(), (8, 6, 12))
        self.assertEqual(rows(m.tets(index_base=1))[0], (1, 2, 4, 8))


def pipe(n=16, rings=7, length=2.0):
    """A pipe along z (radius 1): wall 1, inlet 2 (z = 0), outlet 3 (z = length), fan caps."""
    import math
    points = [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n), length * j / (rings - 1))
              for j in range(rings) for i in range(n)]
    c0, c1, top = len(points), len(points) + 1, n * (rings - 1)
    points += [(0.0, 0.0, 0.0), (0.0, 0.0, length)]
    tris, labels = [], []
    for j in range(rings - 1):
        for i in range(n):
            a, b = j * n + i, j * n + (i + 1) % n
            tris += [(a, b, b + n), (a, b + n, a + n)]
            labels += [1, 1]
    for i in range(n):
        tris += [(i, c0, (i + 1) % n), (top + i, top + (i + 1) % n, c1)]
        labels += [2, 3]
    return points, tris, labels


class SlidePatches(unittest.TestCase):
    """Options version 4: a boundary layer on a pipe's wall sliding along its caps."""

    WALL = dict(bl_patches=[1], bl_first_height=0.01, bl_layers=4)

    @classmethod
    def setUpClass(cls):
        cls.points, cls.tris, cls.labels = pipe()
        cls.surface = anitet.Surface.from_arrays(cls.points, cls.tris, cls.labels)

    def test_slide(self):
        with self.assertRaises(anitet.AnitetError) as e:
            self.surface.mesh(**self.WALL)
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
        self.assertIn("options->bl_slide_patches 2", e.exception.message)
        m = self.surface.mesh(bl_slide_patches=[2, 3], **self.WALL)
        s = m.run_stats
        self.assertEqual((s.bl_layers, s.bl_wall_vertices, s.bl_full_columns), (4, 16 * 7, 16 * 7))
        self.assertEqual((s.slide_junction_columns, s.slide_lowered_columns), (32, 0))
        report = m.run_report()["slide_patches"]
        self.assertEqual(s.slide_triangles_added,
                         sum(p["triangles_after"] - p["triangles_before"] for p in report["patches"]))
        self.assertEqual([p["label"] for p in report["patches"]], [2, 3])
        self.assertEqual(report["junction_vertices"], 32)
        patches = rows(m.boundary_patches())
        self.assertEqual(patches[:2 * 16 * 6], [1] * (2 * 16 * 6))
        self.assertGreater(patches.count(2), 16)
        self.assertTrue(m.quality().valid)
        # An Options, one int, a NumPy array: the same struct.
        scope = anitet._api._options_arg(anitet.Options(bl_slide_patches=3, **self.WALL), {})
        self.assertEqual((scope.struct.bl_num_slide_patches, scope.struct.bl_slide_patches[0]), (1, 3))
        if anitet.HAVE_NUMPY:
            import numpy
            caps = numpy.array([2, 3], dtype=numpy.int32)
            scope = anitet._api._options_arg(None, dict(self.WALL, bl_slide_patches=caps))
            self.assertEqual(ctypes.addressof(scope.struct.bl_slide_patches.contents), caps.ctypes.data)
        t1 = self.surface.build_layers(bl_slide_patches=(2, 3), **self.WALL)
        self.assertIn("slide_patches", t1.run_report())

    def test_errors(self):
        for fields, words in (({"bl_patches": []}, "needs boundary-layer walls"),
                              ({"bl_slide_patches": [1, 2, 3]}, "both as a wall and as a slide patch")):
            with self.assertRaises(anitet.AnitetError) as e:
                self.surface.mesh(**dict(dict(self.WALL, bl_slide_patches=[2, 3]), **fields))
            self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
            self.assertIn(words, e.exception.message)
        with self.assertRaises(TypeError):
            self.surface.mesh(bl_slide_patches=[2.5], **self.WALL)


class PatchTypes(unittest.TestCase):
    def test_types_in_openfoam(self):
        m = anitet.Mesh.read(os.path.join(DATA, "io", "box.mesh"))
        self.assertEqual(m.patch_type(3), "wall")
        m.patch_names[2] = "inlet"
        self.assertEqual(m.patch_type(2), "inlet")
        m.set_patch_type(1, "symmetry")
        m.set_patch_type(4, anitet.PATCH_TYPE_FARFIELD)
        self.assertEqual(m.patch_type(4), "farfield")
        m.set_patch_type(4, None)
        self.assertEqual(m.patch_type(4), "wall")
        m.set_patch_type(5, "Outlet")
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "case", "constant", "polyMesh")
            m.write(path)
            with open(os.path.join(path, "boundary")) as f:
                types = dict(re.findall(r"^    (\w+)\n    \{\n        type +(\w+);", f.read(), re.M))
        self.assertEqual(types, {"patch1": "symmetryPlane", "inlet": "patch", "patch3": "wall",
                                 "patch4": "wall", "patch5": "patch", "patch6": "wall"})
        for label, type_, error in ((1, "slip", ValueError), (1, 6, anitet.AnitetError),
                                    (9, "wall", anitet.AnitetError)):
            with self.assertRaises(error) as e:
                m.set_patch_type(label, type_)
        self.assertIn("patch label 9", e.exception.message)
        with self.assertRaises(anitet.AnitetError):
            m.patch_type(9)
        self.assertEqual(m.patch_type(1), "symmetry")  # unchanged by the errors


class Fields(unittest.TestCase):
    """Per-vertex fields: arrays, .sol/.solb files, transfer between meshes."""

    @staticmethod
    def grid(n, size):
        """A mesh of n^3 cubes of side size/n, six tets each."""
        points = [(size * i / n, size * j / n, size * k / n)
                  for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)]
        tets = []
        at = lambda i, j, k: (k * (n + 1) + j) * (n + 1) + i  # noqa: E731
        for k in range(n):
            for j in range(n):
                for i in range(n):
                    c = [at(i + (v & 1), j + (v >> 1 & 1), k + (v >> 2 & 1)) for v in range(8)]
                    for a, b in ((1, 3), (3, 2), (2, 6), (6, 4), (4, 5), (5, 1)):
                        tets.append((c[0], c[a], c[b], c[7]))
        tets = [t if Fields.volume(points, t) > 0 else (t[0], t[2], t[1], t[3]) for t in tets]
        return anitet.Mesh.from_arrays(points, tets), points

    @staticmethod
    def volume(p, t):
        a, b, c, d = (p[v] for v in t)
        u, v, w = [[q[i] - a[i] for i in range(3)] for q in (b, c, d)]
        return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                u[2] * (v[0] * w[1] - v[1] * w[0]))

    @staticmethod
    def record(p):
        x, y, z = p
        return (1 + 2 * x - y + 3 * z, x, y - z, 2 * z, 10 + x, 0.5, 10 + y, 0.0, 0.25 * z, 10 + z)

    KINDS = ("scalar", "vector", "tensor")

    def test_arrays_and_files(self):
        values = [self.record((i, 2 * i, 3 * i)) for i in range(5)]
        f = anitet.Fields.from_arrays(self.KINDS, values)
        self.assertEqual(f.counts(), (3, 10, 5))
        self.assertEqual(f.kinds, [anitet.FIELD_KIND_SCALAR, anitet.FIELD_KIND_VECTOR,
                                   anitet.FIELD_KIND_SYM_TENSOR])
        self.assertEqual(rows(f.values), values)
        self.assertEqual(rows(f.field(0)), [v[0] for v in values])
        self.assertEqual(rows(f.field(1)), [v[1:4] for v in values])
        with tempfile.TemporaryDirectory() as d:
            for name in ("f.sol", "f.solb"):
                f.write(os.path.join(d, name))
                back = anitet.Fields.read(os.path.join(d, name))
                self.assertEqual(rows(back.values), values)
            with self.assertRaises(anitet.AnitetError) as e:
                f.write(os.path.join(d, "f.txt"))
            self.assertEqual(e.exception.code, anitet.ERR_UNSUPPORTED_FORMAT)
        with self.assertRaises(anitet.AnitetError) as e:
            f.transfer_report()
        self.assertIn("not made by anitet_mesh_transfer_fields", e.exception.message)
        with self.assertRaises(ValueError):
            anitet.Fields.from_arrays(["scalar", "vector"], [(1, 2, 3)])  # 3 values, records of 4
        with self.assertRaises(ValueError):
            anitet.Fields.from_arrays(["matrix"], [1.0])
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.Fields.from_arrays([4], [1.0])
        self.assertIn("kind 0 is 4", e.exception.message)

    @unittest.skipUnless(anitet.HAVE_NUMPY, "views need NumPy")
    def test_views_without_copy(self):
        import numpy
        f = anitet.Fields.from_arrays(["vector"], numpy.arange(12.0).reshape(4, 3))
        v = f.values
        self.assertFalse(v.flags.writeable)
        self.assertFalse(v.flags.owndata)
        self.assertEqual(v.ctypes.data, f.values.ctypes.data)  # the library's memory each time
        f.close()
        del f
        self.assertEqual(v[3].tolist(), [9.0, 10.0, 11.0])  # the view keeps the memory

    def test_transfer(self):
        old, old_points = self.grid(4, 4.0)
        new, new_points = self.grid(3, 3.0)
        fields = anitet.Fields.from_arrays(self.KINDS, [self.record(p) for p in old_points])
        moved = old.transfer_fields(fields, new, tensors="linear")
        self.assertEqual(moved.counts(), (3, 10, len(new_points)))
        worst = max(abs(a - b) for p, r in zip(new_points, rows(moved.values)) for a, b in zip(r, self.record(p)))
        self.assertLess(worst, 1e-12)
        self.assertEqual(moved.transfer_report(), anitet.TransferReport(0, 0.0, [False, False, False]))
        auto = anitet.transfer_fields(old, fields, new)
        self.assertEqual(auto.transfer_report().log_euclidean, [False, False, True])
        one = anitet.transfer_fields(old, fields, new, num_threads=1)  # the same on any number
        self.assertEqual(rows(one.values), rows(auto.values))
        with self.assertRaises(anitet.AnitetError) as e:
            old.transfer_fields(fields, new, num_threads=-1)
        self.assertIn("num_threads is -1", e.exception.message)
        # Points outside: a mesh reaching past the old one.
        big, _ = self.grid(2, 6.0)
        report = old.transfer_fields(fields, big, anitet.TENSORS_AUTO).transfer_report()
        self.assertGreater(report.outside, 0)
        self.assertAlmostEqual(report.max_outside_distance, 2 * 3 ** 0.5)
        # Errors: fields of another mesh, a tensor mode, handles of the wrong kind.
        with self.assertRaises(anitet.AnitetError) as e:
            new.transfer_fields(fields, old)
        self.assertIn("another mesh", e.exception.message)
        with self.assertRaises(ValueError):
            old.transfer_fields(fields, new, tensors="cubic")
        with self.assertRaises(anitet.AnitetError):
            old.transfer_fields(fields, new, tensors=5)
        with self.assertRaises(TypeError):
            anitet.transfer_fields(old, [1.0], new)


class Adapt(unittest.TestCase):
    """anitet.adapt on the UGAWG linear cube: one pass to the metric at the points with a field
    carried, the metric as a Metric, and the errors."""

    @staticmethod
    def linear_metric(z):
        hz = 0.001 + 2 * (0.1 - 0.001) * abs(z - 0.5)
        return (100.0, 0.0, 100.0, 0.0, 0.0, 1.0 / (hz * hz))

    def setUp(self):
        self.cube = anitet.Mesh.read(os.path.join(UGAWG, "cube-linear-00.mesh"))
        self.points = rows(self.cube.points())
        self.metric = [self.linear_metric(p[2]) for p in self.points]

    def test_one_pass(self):
        fields = anitet.Fields.from_arrays(["scalar"], [1 + 2 * x - y + 3 * z for x, y, z in self.points])
        stages = []
        result = anitet.adapt(self.cube, self.metric, fields=fields, progress=lambda s, f: stages.append(s))
        mesh, carried, stats = result
        self.assertEqual(stats.vertices_in, len(self.points))
        self.assertEqual(mesh.counts(), (stats.vertices, stats.tets, stats.boundary_triangles))
        self.assertGreaterEqual(stats.edges_in_range, 0.9)
        self.assertGreater(stats.mean_ratio_min, 0.0)
        self.assertTrue(mesh.quality().valid)
        self.assertEqual(mesh.metric_components, 6)
        worst = max(abs(v - (1 + 2 * x - y + 3 * z)) for (x, y, z), v in zip(rows(mesh.points()), carried.field(0)))
        self.assertLess(worst, 1e-9)
        self.assertIn("transfer", stages)
        self.assertEqual(stages[-1], "done")

    def test_metric_handle(self):
        metric = anitet.Metric.analytic(lambda x, y, z: self.linear_metric(z))
        mesh, fields, stats = self.cube.adapt(metric, keep_surface=True, max_cycles=2, num_threads=1)
        self.assertIsNone(fields)
        self.assertEqual(mesh.num_boundary_triangles, self.cube.num_boundary_triangles)
        self.assertEqual(stats.surface_splits + stats.surface_moves, 0)

    def test_errors(self):
        with self.assertRaises(anitet.AnitetError) as e:
            self.cube.adapt(self.metric[:10])
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
        self.assertIn("metric_len is 60", e.exception.message)
        bad = list(self.metric)
        bad[3] = (1.0, 2.0, 1.0, 0.0, 0.0, 1.0)  # not positive definite
        with self.assertRaises(anitet.AnitetError) as e:
            self.cube.adapt(bad)
        self.assertIn("point 3 (0-based)", e.exception.message)
        with self.assertRaises(anitet.AnitetError) as e:
            self.cube.adapt(self.metric, max_cycles=-1)
        self.assertIn("max_cycles is -1", e.exception.message)
        with self.assertRaises(anitet.AnitetError) as e:
            self.cube.adapt(self.metric, progress=lambda stage, fraction: False)
        self.assertEqual(e.exception.code, anitet.ERR_CANCELLED)
        with self.assertRaises(ZeroDivisionError):
            self.cube.adapt(self.metric, progress=lambda stage, fraction: 1 / 0)
        with self.assertRaises(TypeError):
            anitet.adapt(self.metric, self.cube)


class Arrays(unittest.TestCase):
    def test_output_types(self):
        s = anitet.Surface.from_arrays(CUBE_POINTS, CUBE_TRIS)
        if anitet.HAVE_NUMPY:
            import numpy
            self.assertIsInstance(s.points(), numpy.ndarray)
            self.assertEqual(s.points().shape, (8, 3))
            self.assertEqual(s.triangles().dtype, numpy.int32)
            # NumPy inputs of other dtypes are converted.
            t = anitet.Surface.from_arrays(numpy.array(CUBE_POINTS, dtype=numpy.float32),
                                           numpy.array(CUBE_TRIS, dtype=numpy.int64))
            self.assertEqual(t.counts(), (8, 12))
        else:
            self.assertIsInstance(s.points(), list)
            self.assertEqual(s.points()[1], (1.0, 0.0, 0.0))


class Partitions(unittest.TestCase):
    """anitet.partition_mesh: the header's promises, seen from Python, and NumPy views."""

    @classmethod
    def setUpClass(cls):
        cls.mesh = anitet.mesh_surface(sphere()[0])

    def check(self, partition, num_parts):
        info = partition.info()
        self.assertEqual(info.num_parts, num_parts)
        self.assertLessEqual(info.imbalance, 0.03 + 1e-12)
        tet_parts = list(partition.tet_parts())
        self.assertEqual(len(tet_parts), self.mesh.num_tets)
        own = [0] * len(tet_parts)
        parts = list(partition)
        self.assertEqual(len(parts), num_parts)
        for p, part in enumerate(parts):
            nv, nov, nt, nto, nb, nob = part.counts()
            self.assertEqual(part.index, p)
            ids = [int(g) for g in part.tet_global_ids]
            owners = [int(o) for o in part.tet_owners]
            layers = [int(x) for x in part.tet_layers]
            for i, g in enumerate(ids):
                self.assertEqual(owners[i], tet_parts[g])
                self.assertEqual(layers[i] == 0, i < nto)
                if i < nto:
                    own[g] += 1
                else:  # a ghost tet is own on its owner
                    owner = parts[owners[i]]
                    self.assertIn(g, [int(x) for x in owner.tet_global_ids[:owner.counts()[3]]])
            self.assertEqual(len(rows(part.tets)), nt)
            self.assertEqual(len(rows(part.points)), nv)
            # p's send lists name the global ids of its neighbours' recv lists from p.
            for send, recv, ids_of in ((anitet.HALO_VERTEX_SEND, anitet.HALO_VERTEX_RECV, "vertex_global_ids"),
                                       (anitet.HALO_TET_SEND, anitet.HALO_TET_RECV, "tet_global_ids")):
                mine = getattr(part, ids_of)
                for q, items in part.halo(send).items():
                    theirs = getattr(parts[q], ids_of)
                    back = parts[q].halo(recv)[p]
                    self.assertEqual([int(mine[i]) for i in items], [int(theirs[i]) for i in back])
        self.assertEqual(own, [1] * len(own))

    def test_parts(self):
        for n in (1, 2, 5):
            self.check(self.mesh.partition(n), n)
        self.check(anitet.partition_mesh(self.mesh, 3, ghost_layers=2, num_threads=1), 3)

    def test_weights(self):
        weights = [1.0 + (t % 3) for t in range(self.mesh.num_tets)]
        p = self.mesh.partition(3, tet_weights=weights)
        self.assertAlmostEqual(p.info().total_weight, sum(weights))
        self.check(p, 3)

    def test_views_without_copy_outlive_their_partition(self):
        p = self.mesh.partition(2)
        part = p[1]
        tets, points = part.tets, part.points
        expected = rows(tets)
        if anitet.HAVE_NUMPY:
            import numpy
            self.assertEqual(tets.shape[1], 4)
            self.assertEqual(points.shape[1], 3)
            self.assertFalse(tets.flags.owndata)
            self.assertFalse(tets.flags.writeable)
            self.assertTrue(numpy.shares_memory(tets, part.tets))  # the library's memory, twice
            self.assertEqual(part.vertex_global_ids.dtype, numpy.int64)
        else:
            self.assertIsInstance(tets, list)
        p.close()
        del p, part
        import gc
        gc.collect()
        self.assertEqual(rows(tets), expected)  # the view holds the memory

    def test_closed_partition(self):
        p = self.mesh.partition(2)
        p.close()
        with self.assertRaises(anitet.AnitetError) as e:
            p.info()
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)

    def test_bytes(self):
        part = self.mesh.partition(3)[2]
        data = part.to_bytes()
        copy = anitet.Part.from_bytes(data)
        self.assertEqual(copy.to_bytes(), data)
        self.assertEqual(rows(copy.tets), rows(part.tets))
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.Part.from_bytes(data[:-3])
        self.assertEqual(e.exception.code, anitet.ERR_PARSE)

    def test_errors(self):
        n = self.mesh.num_tets
        for bad in (0, -1, n + 1):
            with self.assertRaises(anitet.AnitetError) as e:
                self.mesh.partition(bad)
            self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)
        with self.assertRaises(anitet.AnitetError) as e:
            self.mesh.partition(2, tet_weights=[1.0] * (n - 1))
        self.assertIn("num_tet_weights", e.exception.message)
        with self.assertRaises(anitet.AnitetError):
            self.mesh.partition(2, ghost_layers=-1)
        with self.assertRaises(IndexError):
            self.mesh.partition(2)[2]
        with self.assertRaises(TypeError):
            anitet.partition_mesh("mesh", 2)

class Meshes2d(unittest.TestCase):
    """The 2D mesher: arrays and files in, the mesh's arrays out, an analytic anisotropic metric,
    longitude/latitude input, cancellation and the errors on bad input."""

    SQUARE = [(0, 0), (4, 0), (4, 4), (0, 4), (1.5, 1.5), (2.5, 1.5), (2.5, 2.5), (1.5, 2.5)]
    SEGMENTS = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4)]

    def square(self):
        return anitet.Pslg.from_arrays(self.SQUARE, self.SEGMENTS, labels=[1] * 4 + [2] * 4, holes=[(2, 2)])

    def test_square_with_hole(self):
        p = self.square()
        self.assertEqual(p.counts(), (8, 8, 1))
        m = anitet.mesh2d(p, split_segments=True, hsize=0.25)
        n, t, e = m.counts()
        self.assertGreater(t, 100)
        self.assertEqual(rows(m.points())[:8], [tuple(float(c) for c in q) for q in self.SQUARE])
        pts, tris = rows(m.points()), rows(m.triangles())
        area = sum(0.5 * ((pts[b][0] - pts[a][0]) * (pts[c][1] - pts[a][1]) -
                          (pts[b][1] - pts[a][1]) * (pts[c][0] - pts[a][0])) for a, b, c in tris)
        self.assertAlmostEqual(area, 15.0, places=9)
        self.assertEqual(len(rows(m.edges())), e)
        self.assertEqual(sorted(set(rows(m.edge_labels()))), [1, 2])
        self.assertEqual(min(min(x) for x in rows(m.triangles(index_base=1))), 1)
        q = m.quality()
        self.assertGreaterEqual(q["min_angle_deg"], 25.0)
        self.assertGreaterEqual(q["mean_radius_ratio"], 0.9)
        with tempfile.TemporaryDirectory() as d:
            for ext in ("mesh", "msh", "vtu", "14"):
                m.write(os.path.join(d, "square." + ext))
                self.assertTrue(os.path.exists(os.path.join(d, "square." + ext)))
        # Kept whole (the default): 8 edges, the input's 8 segments.
        self.assertEqual(p.mesh().counts()[2], 8)

    def test_anisotropic_metric_callback(self):
        """The case of docs/mesh2d.md through an analytic metric: >= 97% of the edges in range."""
        import math

        def polar(x, y, z):
            dx, dy = x - 0.5, y - 0.5
            r = math.hypot(dx, dy)
            nx, ny = (dx / r, dy / r) if r > 0 else (1.0, 0.0)
            hr = 0.001 + 2 * (0.1 - 0.001) * abs(r - 0.25)
            a, b = hr ** -2, 100.0
            return (a * nx * nx + b * ny * ny, (a - b) * nx * ny, a * ny * ny + b * nx * nx)

        p = anitet.Pslg.read(os.path.join(DATA, "mesh2d", "square_minus_disk.poly"))
        m = anitet.mesh2d(p, anitet.Metric.analytic(polar))
        self.assertGreaterEqual(m.quality()["edges_in_range"], 0.97)

    def test_geodetic(self):
        p = anitet.Pslg.read(os.path.join(DATA, "mesh2d", "coast45.geojson"))
        n_input = p.counts()[0]
        m = anitet.mesh2d(p, geodetic=True, hsize=5000.0)  # the coast's spacing
        pts = rows(m.points())
        with open(os.path.join(DATA, "mesh2d", "coast45.geojson")) as f:
            import json
            first = json.load(f)["features"][0]["geometry"]["coordinates"][0][0]
        self.assertEqual(pts[0], tuple(first))  # the input's points, exactly
        self.assertTrue(all(-64.5 < x < -61.5 and 43.9 < y < 46.1 for x, y in pts[n_input:]))
        self.assertGreaterEqual(m.quality()["edges_in_range"], 0.95)

    def test_progress_and_cancel(self):
        stages = []
        anitet.mesh2d(self.square(), progress=lambda stage, f: stages.append(stage))
        self.assertEqual(stages[:3], ["validate", "sizing", "front"])
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.mesh2d(self.square(), progress=lambda stage, f: stage != "refine")
        self.assertEqual(e.exception.code, anitet.ERR_CANCELLED)

    def test_bad_input_named(self):
        p = anitet.Pslg.read(os.path.join(DATA, "mesh2d", "crossing.poly"))
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.mesh2d(p)
        self.assertEqual(e.exception.code, anitet.ERR_SELF_INTERSECTION)
        self.assertIn("segment 2 (line 9) and segment 4 (line 11)", e.exception.message)
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.Pslg.from_arrays(self.SQUARE, [(0, 1), (1, 2), (2, 9)])
        self.assertEqual(e.exception.code, anitet.ERR_BAD_INDEX)
        with self.assertRaises(anitet.AnitetError) as e:
            anitet.mesh2d(self.square(), hgrad=0.5)
        self.assertEqual(e.exception.code, anitet.ERR_INVALID_ARGUMENT)


if __name__ == "__main__":
    print("anitet %s, numpy: %s" % (anitet.version(), anitet.HAVE_NUMPY))
    unittest.main(verbosity=2)
