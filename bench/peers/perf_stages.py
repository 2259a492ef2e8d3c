#!/usr/bin/python3
"""Where anitet's CPU time goes, by pipeline stage and sub-step, from a perf profile.

    perf record -F 499 --call-graph fp -o run.data anitet mesh IN -o OUT -v   (frame pointers:
        a build with CMAKE_CXX_FLAGS=-fno-omit-frame-pointer)
    perf script -i run.data -F ip,sym,dso > run.script
    bench/peers/perf_stages.py run.script [CPU_SECONDS]

Each sample goes to the first stage (in the list below) one of its frames matches; under each
stage, its hottest leaf functions; then the kernel samples (page faults: zeroing fresh pages) by
the first anitet frame above them. CPU_SECONDS (user+sys of the run) turns shares into seconds."""
import collections
import re
import sys

STAGES = [("write/output", r"write_mesh|write_medit|Mesher::write"),
          ("quality report", r"compute_quality_report"),
          ("optimize: CVT", r"Optimizer::cvt_pass"),
          ("optimize: flips", r"flip_sweep"),
          ("optimize: slivers", r"Optimizer::(sliver|perturb)"),
          ("optimize: other", r"Optimizer::run|optimize_mesh"),
          ("refine: edge lists", r"refine_detail::(collect_edges|update_edges)"),
          ("refine: split choice", r"Refiner::choose_splits"),
          ("refine: insertion", r"BatchInserter::insert|Refiner::insert_in_metric"),
          ("refine: collapses", r"Refiner::collapse_pass"),
          ("refine: metric flips", r"Refiner::metric_flip"),
          ("refine: other", r"Refiner::run|refine_mesh"),
          ("sizing field", r"metric::|surface_sizing"),
          ("layers (stage 1)", r"build_layers|LayerBuilder"),
          ("recovery (stage 2)", r"recover|Recovery"),
          ("coupling", r"couple"),
          ("read input", r"read_surface")]


def samples(path):
    """Yields each sample's frames, leaf first, as (in kernel, symbol without arguments)."""
    cur = []
    for line in open(path, errors="replace"):
        if not line.strip():
            if cur:
                yield cur
            cur = []
            continue
        m = re.match(r"\s+[0-9a-f]+\s+(.*)\s+\((.*)\)$", line.rstrip())
        if not m:
            continue
        sym = re.sub(r"\+0x[0-9a-f]+$", "", m.group(1)).replace("(anonymous namespace)", "{anon}")
        cur.append(("kernel" in m.group(2), re.sub(r"\(.*", "", sym)))
    if cur:
        yield cur


def main():
    secs = float(sys.argv[2]) if len(sys.argv) > 2 else None
    total = 0
    by_stage = collections.Counter()
    leaves = collections.defaultdict(collections.Counter)
    kernel_by_caller = collections.Counter()
    for frames in samples(sys.argv[1]):
        total += 1
        names = [f for _, f in frames]
        stage = next((s for s, rx in STAGES if any(re.search(rx, f) for f in names)), "other")
        by_stage[stage] += 1
        leaves[stage][names[0]] += 1
        if frames[0][0]:
            kernel_by_caller[next((f for k, f in frames if not k and "anitet" in f), "?")] += 1
    print(f"{total} samples" + (f", {secs:.1f} CPU s" if secs else ""))
    for stage, n in by_stage.most_common():
        print(f"{n / total * 100:5.1f}%" + (f" {n / total * secs:6.2f} s" if secs else "") + f"  {stage}")
        for leaf, k in leaves[stage].most_common(6):
            if k / total >= 0.004:
                print(f"        {k / total * 100:5.1f}%  {leaf[:110]}")
    print("\nkernel samples by the first anitet frame above them:")
    for caller, n in kernel_by_caller.most_common(8):
        print(f"  {n / total * 100:5.1f}%  {caller[:110]}")


if __name__ == "__main__":
    main()
