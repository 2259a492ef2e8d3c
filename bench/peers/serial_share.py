#!/usr/bin/python3
"""How much of an anitet run is serial, from a perf profile with call stacks: a bound on the
speed-up from one core to two that does not depend on the machine's load (issue 49's "two cores
>= 1.8x one core" cannot be timed on a machine loaded 8x over).

    perf record -F 49 --call-graph dwarf,65528 -o run.data anitet mesh IN -o OUT
    perf script -i run.data -F tid,ip,sym,dso > run.script
    bench/peers/serial_share.py run.script

Every sample of a TBB worker is parallel work. A sample of the main thread (the run's first
thread) is parallel work when its stack holds a TBB construct (a tbb::detail frame other than the
task arena the CLI runs in), else serial work. Main-thread stacks that do not reach the arena
frame (unwinding cut short) are shared out as the complete ones are. With a serial share s, two
cores take at least s + (1 - s) / 2 of one core's time: speed-up at most 2 / (1 + s) (less with
imbalance or waits inside the parallel parts). Then the serial samples by stage
(perf_stages.STAGES) with their hottest leaf functions."""
import collections
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import perf_stages  # noqa: E402

ARENA = "task_arena_function"
PARALLEL = re.compile(r"tbb::detail::d1::(?!task_arena_function)")


def samples(path):
    """Yields (thread id, frames leaf first, symbols without arguments) per sample."""
    tid, frames = None, []
    for line in open(path, errors="replace"):
        if not line.strip():
            if tid is not None:
                yield tid, frames
            tid, frames = None, []
        elif not line[0].isspace():
            tid, frames = line.split()[0], []
        else:
            m = re.match(r"\s+[0-9a-f]+\s+(.*)\s+\((.*)\)$", line.rstrip())
            if m:
                sym = re.sub(r"\+0x[0-9a-f]+$", "", m.group(1)).replace("(anonymous namespace)", "{anon}")
                frames.append(re.sub(r"\(.*", "", sym))
    if tid is not None:
        yield tid, frames


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    rows = list(samples(sys.argv[1]))
    if not rows:
        sys.exit(f"no samples in {sys.argv[1]}")
    main_tid = min(rows, key=lambda r: int(r[0]))[0]
    main_rows = [f for t, f in rows if t == main_tid]
    complete = [f for f in main_rows if any(ARENA in x for x in f)]
    serial = [f for f in complete if not any(PARALLEL.search(x) for x in f)]
    if not complete:
        sys.exit("no main-thread stack reaches the task arena: record with --call-graph dwarf,65528")
    share = len(serial) / len(complete) * len(main_rows) / len(rows)
    print(f"{len(rows)} samples, {len(main_rows)} on the main thread ({len(complete)} with whole stacks, "
          f"{len(serial)} of them serial)")
    print(f"serial share {share:.3f}: two cores at most {2 / (1 + share):.2f}x one core")
    by_stage = collections.Counter()
    leaves = collections.defaultdict(collections.Counter)
    for f in serial:
        stage = next((s for s, rx in perf_stages.STAGES if any(re.search(rx, x) for x in f)), "other")
        by_stage[stage] += 1
        leaves[stage][f[0]] += 1
    print("\nserial samples by stage (share of the run):")
    scale = share / len(serial) if serial else 0.0
    for stage, n in by_stage.most_common():
        print(f"  {n * scale * 100:5.1f}%  {stage}")
        for leaf, k in leaves[stage].most_common(4):
            print(f"          {k * scale * 100:5.1f}%  {leaf[:100]}")


if __name__ == "__main__":
    main()
