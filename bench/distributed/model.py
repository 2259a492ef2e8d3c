#!/usr/bin/env python3
"""The time and memory per rank of docs/distributed.md's design ("parts from the coarse mesh on"),
from 1e7 to 1e9 tets on 1 to 1,024 ranks, from per-item costs measured on this machine
(bench/results/distributed/2026-12-07-design-model.md has the runs and the commands).

    bench/distributed/model.py [--triangles T] [--threads K] [--zone Z] [--surface S] [--markdown]

--triangles: the surface's triangles (default 1e6: a large CFD surface); --threads: threads per
rank (default 1: the measured figures are one core's); --zone: rings of the second rounds
(default 6, today's PartsOptions::zone); --surface: replicated (stages 1-2 on every rank, the
design's first form) or distributed (the design past the replicated limit, on paper: modelled as
stages 1-2 split evenly over the ranks, an ideal bound). Prints the per-rank table, then up to which surface
size stages 1-2 can stay replicated for each part size. A model, not a measurement: the
constants marked "assumed" are to be measured when steps 2-4 of issue 51 are built.
"""
import argparse
import math

# --- measured here (one core; wall seconds times the share of core 0 the run got, see measure.sh)
S12_US_PER_TRIANGLE = 45.0     # stages 1-2 + coupling, CPU microseconds per surface triangle (median of 6 surfaces, 21-85)
S12_KB_PER_TRIANGLE = 2.0      # their peak resident memory per triangle (slope armadillo -> armadillo split 1-to-4)
S12_BASE_MB = 26.0             # ... plus this (the process, the libraries)
COUPLED_PER_TRIANGLE = 4.6     # coupled (coarse) tets per surface triangle (4.56-4.69 on 6 surfaces)
STAGE3_US_PER_TET = 7.5        # refinement + optimization, CPU microseconds per final tet (armadillo, 1.03M tets)
BYTES_PER_TET = 190.0          # peak bytes per final tet of one process at 1e7 tets (bench/results/scale: 186-195)
FACETS_PER_PART = 2.5          # interface facets per part / (own tets)^(2/3) (METIS parts of armadillo: 2.1-2.5 at 64-256 parts)
GHOSTS_PER_FACET = 3.5         # one vertex ring of halo tets per interface facet (3.3-3.9)
METRIC_VOLUME_PER_TET = 0.1    # kMetricVolumePerTet (src/refine/refine.cpp): a part of n tets spans (0.1 n)^(1/3) edges
SIZING_FIELD_MB = 40.0         # the default sizing grid: at most 2^22 voxels, 9 bytes each while smoothing

# --- assumed (to be measured in steps 2-4)
ROUND2_SHARE = 0.5             # a second round's cost per tet of its zone, as a share of STAGE3_US_PER_TET
SCOTCH_US_PER_COARSE_TET = 3.0 # serial Scotch 7.0, 8 parts of armadillo's dual graph (bench/results/partition, loaded machine)
SCOTCH_EFFICIENCY = 0.5        # PT-Scotch's parallel efficiency on the coarse graph
MIGRATED_BYTES_PER_TET = 80.0  # a migrated tet with its share of vertices (ids, coordinates, flags)
NETWORK_GBPS = 5.0             # point-to-point bandwidth per rank
OUTPUT_BYTES_PER_TET = 50.0    # binary .vtu: connectivity (4 int64), offset, type, region, ~1/5.5 of a vertex
WRITE_GBPS_PER_RANK = 1.0      # file system bandwidth per rank ...
WRITE_GBPS_TOTAL = 20.0        # ... and in all (a parallel file system)
THREAD_EFFICIENCY = 0.8        # per extra thread in a rank (stages 3b/3c are TBB-parallel)


def halo_share(n):
    """Halo tets over own tets for a part of n tets."""
    return GHOSTS_PER_FACET * FACETS_PER_PART * n ** (-1.0 / 3.0) if n > 0 else 0.0


def zone_share(n, zone):
    """Share of a cube-like part of n tets within `zone` rings (edges) of its faces."""
    side = (METRIC_VOLUME_PER_TET * n) ** (1.0 / 3.0)
    return 1.0 - max(0.0, 1.0 - 2.0 * zone / side) ** 3


def stages12(triangles):
    """Replicated stages 1-2: (seconds, peak MB) on one core."""
    return S12_US_PER_TRIANGLE * 1e-6 * triangles, S12_BASE_MB + S12_KB_PER_TRIANGLE * triangles / 1024.0


def per_rank(tets, ranks, triangles, threads, zone, distributed_surface=False):
    """Seconds and peak MB of the busiest rank, by phase."""
    speed = 1.0 + THREAD_EFFICIENCY * (threads - 1)
    n = tets / ranks
    t12, m12 = stages12(triangles / ranks if distributed_surface else triangles)
    coarse = COUPLED_PER_TRIANGLE * triangles
    if ranks == 1:
        t_part, halo, zone_tets = 0.0, 0.0, 0.0
    else:
        t_part = SCOTCH_US_PER_COARSE_TET * 1e-6 * coarse / (SCOTCH_EFFICIENCY * ranks)
        halo = halo_share(n)
        zone_tets = zone_share(n, zone) * n
    t_mesh = STAGE3_US_PER_TET * 1e-6 * (n + ROUND2_SHARE * zone_tets) / speed
    # Two rounds of refinement and two of optimization each move their zone.
    t_move = 4 * MIGRATED_BYTES_PER_TET * zone_tets / (NETWORK_GBPS * 1e9)
    t_write = OUTPUT_BYTES_PER_TET * tets / min(ranks * WRITE_GBPS_PER_RANK * 1e9, WRITE_GBPS_TOTAL * 1e9)
    m_part = SIZING_FIELD_MB + (BYTES_PER_TET * n * (1.0 + halo) + MIGRATED_BYTES_PER_TET * zone_tets) / 2**20
    return {
        "n": n, "halo": halo, "zone": zone_tets / n if n else 0.0,
        "t12": t12, "t_part": t_part, "t_mesh": t_mesh, "t_move": t_move, "t_write": t_write,
        "t": t12 + t_part + t_mesh + t_move + t_write,
        "m12": m12, "m_part": m_part, "m": max(m12, m_part),
    }


def fmt_time(s):
    if s < 100:
        return "%.1f s" % s
    if s < 6000:
        return "%.0f min" % (s / 60)
    return "%.1f h" % (s / 3600)


def fmt_mem(mb):
    return "%.0f MB" % mb if mb < 1024 else "%.1f GB" % (mb / 1024)


def table(args):
    head = ["tets", "ranks", "tets/rank", "halo", "2nd-round zone", "stages 1-2", "partition", "refine+optimize",
            "migration", "write", "total", "speed-up", "peak memory/rank", "vs 1 rank"]
    rows = []
    for tets in (1e7, 1e8, 1e9):
        one = per_rank(tets, 1, args.triangles, args.threads, args.zone)
        for ranks in (1, 4, 16, 64, 256, 1024):
            r = per_rank(tets, ranks, args.triangles, args.threads, args.zone, args.surface == "distributed")
            rows.append(["%.0e" % tets, str(ranks), "%.2g" % r["n"], "%.1f%%" % (100 * r["halo"]),
                         "%.0f%%" % (100 * r["zone"]), fmt_time(r["t12"]), fmt_time(r["t_part"]),
                         fmt_time(r["t_mesh"]), fmt_time(r["t_move"]), fmt_time(r["t_write"]), fmt_time(r["t"]),
                         "%.1f" % (one["t"] / r["t"]), fmt_mem(r["m"]), "%.2f" % (r["m"] / one["m"])])
    return head, rows


def replicated_limit(args):
    """Largest surface for which replicated stages 1-2 take at most a quarter of the parts' time
    and no more memory than the part's phase."""
    head = ["tets per rank", "part's stages 3b/3c", "part's memory", "triangles (time <= 1/4)",
            "triangles (memory <= part's)", "replicated up to"]
    rows = []
    speed = 1.0 + THREAD_EFFICIENCY * (args.threads - 1)
    for n in (1e5, 1e6, 1e7, 1e8):
        t_mesh = STAGE3_US_PER_TET * 1e-6 * n / speed
        m_part = SIZING_FIELD_MB + BYTES_PER_TET * n * (1 + halo_share(n)) / 2**20
        by_time = 0.25 * t_mesh / (S12_US_PER_TRIANGLE * 1e-6)
        by_mem = max(0.0, (m_part - S12_BASE_MB) * 1024 / S12_KB_PER_TRIANGLE)
        rows.append(["%.0e" % n, fmt_time(t_mesh), fmt_mem(m_part), "%.2g" % by_time, "%.2g" % by_mem,
                     "%.2g" % min(by_time, by_mem)])
    return head, rows


def show(head, rows, markdown):
    if markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for r in rows:
            print("| " + " | ".join(r) + " |")
        return
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(head)]
    print("  ".join(h.rjust(w) for h, w in zip(head, widths)))
    for r in rows:
        print("  ".join(c.rjust(w) for c, w in zip(r, widths)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--triangles", type=float, default=1e6, help="surface triangles (default 1e6)")
    parser.add_argument("--threads", type=int, default=1, help="threads per rank (default 1)")
    parser.add_argument("--zone", type=int, default=6, help="rings of the second rounds' zone (default 6)")
    parser.add_argument("--surface", choices=("replicated", "distributed"), default="replicated",
                        help="stages 1-2 on every rank (default) or split over the ranks (on paper)")
    parser.add_argument("--markdown", action="store_true", help="Markdown tables")
    args = parser.parse_args()
    if args.triangles <= 0 or args.threads < 1 or args.zone < 0:
        parser.error("--triangles > 0, --threads >= 1, --zone >= 0")
    print("Per rank, the busiest: %.2g surface triangles (stages 1-2 %s), %d thread(s) per rank, "
          "second-round zone %d rings" % (args.triangles, args.surface, args.threads, args.zone))
    show(*table(args), args.markdown)
    print()
    print("Stages 1-2 replicated on every rank: up to which surface size (%d thread(s) per rank)" % args.threads)
    show(*replicated_limit(args), args.markdown)


if __name__ == "__main__":
    main()
