#!/usr/bin/python3
"""Issue 49's acceptance tables from one_core.sh's runs.tsv (medians over the rounds).

tets/s is tets over CPU seconds (user+sys of the pinned process): on a shared machine a pinned
process's CPU time moves far less than its wall time. Wall-time figures are given beside it."""
import csv
import statistics
import sys


def load(path):
    rows = list(csv.DictReader(open(path), delimiter="\t"))
    for r in rows:
        for k in ("wall", "user", "sys", "load1", "rr_mean", "rr_min", "rr_min_interior"):
            r[k] = float(r[k])
        r["tets"] = int(r["tets"])
        r["cpu"] = r["user"] + r["sys"]
    return rows


def runs_of(rows, surface, name):
    sel = [r for r in rows if r["surface"] == surface and r["run"] == name]
    if name == "anitet-sized" and sel:
        # Round 1 may hold calibration tries: keep the runs at the size finally chosen.
        sel = [r for r in sel if r["size"] == sel[-1]["size"]]
    return sel


def summary(sel):
    """Median figures of one program on one input; None when a run failed."""
    if not sel or any(r["status"] != "ok" for r in sel):
        return None
    med = lambda k: statistics.median(r[k] for r in sel)
    last = sel[-1]
    return {"tets": last["tets"], "cpu": med("cpu"), "wall": med("wall"), "rr_mean": last["rr_mean"],
            "rr_min_interior": last["rr_min_interior"], "size": last["size"],
            "ok": last["valid"] == "True" and last["bc"] == "True",
            "load": (min(r["load1"] for r in sel), max(r["load1"] for r in sel)), "n": len(sel)}


def load_text(*figs):
    lo = min(f["load"][0] for f in figs if f)
    hi = max(f["load"][1] for f in figs if f)
    lo, hi = f"{lo:.1f}", f"{hi:.1f}"
    return lo if lo == hi else f"{lo}-{hi}"


def rr(x):
    return "none" if x != x else f"{x:.3f}"  # nan: no tet off the surface


def yes(flag):
    return "**yes**" if flag else "**no**"


def failed(sel):
    return next((r["status"] for r in sel if r["status"] != "ok"), "no run")


def smooth_table(rows, surfaces):
    print("### Smooth set, default sizes: tets/s (CPU) >= 1.3x HXT's, radius-ratio mean >= HXT's\n")
    print("| input | anitet tets | CPU s | wall s | HXT tets | CPU s | wall s | tets/s anitet | tets/s HXT "
          "| ratio (CPU) | ratio (wall) | rr mean anitet / HXT | valid, kept | load | >= 1.3x | mean >= |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for s in surfaces:
        a, h = summary(runs_of(rows, s, "anitet")), summary(runs_of(rows, s, "hxt"))
        if not a or not h:
            print(f"| {s} | failed: {failed(runs_of(rows, s, 'anitet' if not a else 'hxt'))} |")
            continue
        ra, rh = a["tets"] / a["cpu"], h["tets"] / h["cpu"]
        ratio, wall_ratio = ra / rh, (a["tets"] / a["wall"]) / (h["tets"] / h["wall"])
        print(f"| {s} | {a['tets']:,} | {a['cpu']:.2f} | {a['wall']:.2f} | {h['tets']:,} | {h['cpu']:.2f} | "
              f"{h['wall']:.2f} | {ra / 1e3:.0f}k | {rh / 1e3:.0f}k | {ratio:.2f} | {wall_ratio:.2f} | "
              f"{a['rr_mean']:.3f} / {h['rr_mean']:.3f} | {'yes' if a['ok'] else 'NO'}, "
              f"{'yes' if h['ok'] else 'NO'} | {load_text(a, h)} | {yes(ratio >= 1.3)} | "
              f"{yes(a['rr_mean'] >= h['rr_mean'])} |")
    print()


def sized_table(rows, surfaces):
    print("### Smooth set, `--size` bringing anitet's tet count within 10% of HXT's: wall time <= HXT's\n")
    print("| input | --size | anitet tets | / HXT's | CPU s | wall s | HXT CPU s | HXT wall s | "
          "rr mean anitet / HXT | load | wall <= HXT | CPU <= HXT |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for s in surfaces:
        a, h = summary(runs_of(rows, s, "anitet-sized")), summary(runs_of(rows, s, "hxt"))
        if not a or not h:
            print(f"| {s} | failed: {failed(runs_of(rows, s, 'anitet-sized' if not a else 'hxt'))} |")
            continue
        share = a["tets"] / h["tets"]
        within = " (not within 10%)" if abs(share - 1) > 0.1 else ""
        print(f"| {s} | {a['size']} | {a['tets']:,} | {share:.2f}{within} | {a['cpu']:.2f} | {a['wall']:.2f} | "
              f"{h['cpu']:.2f} | {h['wall']:.2f} | {a['rr_mean']:.3f} / {h['rr_mean']:.3f} | {load_text(a, h)} | "
              f"{yes(a['wall'] <= h['wall'])} | {yes(a['cpu'] <= h['cpu'])} |")
    print()


def sliver_table(rows, surfaces):
    print("### Sliver CAD set: wall time <= 1/4 of HXT's, interior radius ratio min >= 0.05\n")
    print("| input | anitet tets | CPU s | wall s | HXT tets | CPU s | wall s | HXT / anitet wall | "
          "HXT / anitet CPU | interior rr min anitet / HXT | valid, kept | load | <= 1/4 wall | >= 0.05 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for s in surfaces:
        a, h = summary(runs_of(rows, s, "anitet")), summary(runs_of(rows, s, "hxt"))
        if not a:
            print(f"| {s} | failed: {failed(runs_of(rows, s, 'anitet'))} |")
            continue
        if not h:  # HXT failing is a figure too: anitet's side still counts
            hx = failed(runs_of(rows, s, "hxt"))
            print(f"| {s} | {a['tets']:,} | {a['cpu']:.2f} | {a['wall']:.2f} | HXT {hx} | | | | | "
                  f"{rr(a['rr_min_interior'])} / - | {'yes' if a['ok'] else 'NO'} | {load_text(a)} | - | "
                  f"{yes(a['rr_min_interior'] >= 0.05)} |")
            continue
        print(f"| {s} | {a['tets']:,} | {a['cpu']:.2f} | {a['wall']:.2f} | {h['tets']:,} | {h['cpu']:.2f} | "
              f"{h['wall']:.2f} | {h['wall'] / a['wall']:.2f} | {h['cpu'] / a['cpu']:.2f} | "
              f"{rr(a['rr_min_interior'])} / {rr(h['rr_min_interior'])} | {'yes' if a['ok'] else 'NO'}, "
              f"{'yes' if h['ok'] else 'NO'} | {load_text(a, h)} | {yes(h['wall'] >= 4 * a['wall'])} | "
              f"{yes(a['rr_min_interior'] >= 0.05)} |")
    print()


def main():
    rows = load(sys.argv[1])
    order = list(dict.fromkeys(r["surface"] for r in rows))
    smooth = [s for s in order if any(r["surface"] == s and r["set"] == "smooth" for r in rows)]
    sliver = [s for s in order if s not in smooth]
    rounds = max((int(r["round"]) for r in rows), default=0)
    print(f"{rounds} round(s), each program pinned to core 0 (`taskset -c 0`), runs alternated per input; "
          "CPU = user+sys of the pinned process; figures are medians over the rounds; load = 1-minute "
          "load average before the runs (2 cores). tets/s ratio = anitet's over HXT's.\n")
    if smooth:
        smooth_table(rows, smooth)
        sized_table(rows, smooth)
    if sliver:
        sliver_table(rows, sliver)


if __name__ == "__main__":
    main()
