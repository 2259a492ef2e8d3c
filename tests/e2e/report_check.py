#!/usr/bin/env python3
"""report_check.py REPORT.html [PNG] [--cut-max N] [--metric-mean LO,HI]

Checks the HTML quality report written by `anitet quality MESH --report REPORT.html`:
  - self-contained: no <script>, <link>, <img>, <iframe> or external url (http:, https:, //...)
    other than the SVG namespace;
  - four histograms (radius-ratio, mean-ratio, dihedral, edge-length), each with exactly
    data-bins "bar-all" and data-bins "bar-bnd" bars, whose data-count values add up to the tet
    count (quality histograms), 6 x tets (dihedral angles) or the edge count (edge lengths), with
    at least one non-empty bar;
  - three cut views (x, y, z), each with as many <polygon> elements as its data-polygons says,
    more than 0, each polygon with 3 or 4 points.
With PNG: the screenshot exists, is a PNG of 1400 x 2000 and its compressed size is non-trivial
(> 20 kB: a blank page of that size compresses to a few kB).
With --cut-max N (the report written with that option): every cut view draws min(N, crossed)
polygons, and at least one view crosses more than N tets (so the cap was exercised).
With --metric-mean LO,HI (the report written with --metric): the edge lengths are in the metric
and their mean is in [LO, HI].
Exits 1 with a message on the first failure.
"""
import re
import struct
import sys
from html.parser import HTMLParser


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


class Report(HTMLParser):
    def __init__(self):
        super().__init__()
        self.body = {}
        self.svgs = []  # [attrs, {"bar-all": [counts], "bar-bnd": [...], "polygon": [points]}]
        self.forbidden = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag in ("script", "link", "img", "iframe", "object", "embed"):
            self.forbidden.append(tag)
        for k, v in attrs:
            if k in ("href", "src", "xlink:href") and v:
                self.forbidden.append("%s=%s" % (k, v))
        if tag == "body":
            self.body = a
        elif tag == "svg":
            self.svgs.append([a, {"bar-all": [], "bar-bnd": [], "polygon": []}])
        elif tag == "rect" and self.svgs and a.get("class") in ("bar-all", "bar-bnd"):
            self.svgs[-1][1][a["class"]].append(int(a["data-count"]))
        elif tag == "polygon" and self.svgs:
            self.svgs[-1][1]["polygon"].append(a.get("points", ""))

    handle_startendtag = handle_starttag


def main():
    args = sys.argv[1:]
    cut_max = None
    if "--cut-max" in args:
        i = args.index("--cut-max")
        cut_max = int(args[i + 1])
        del args[i:i + 2]
    metric_mean = None
    if "--metric-mean" in args:
        i = args.index("--metric-mean")
        metric_mean = [float(x) for x in args[i + 1].split(",")]
        del args[i:i + 2]
    if len(args) not in (1, 2):
        fail("usage: report_check.py REPORT.html [PNG] [--cut-max N] [--metric-mean LO,HI]")
    png_path = args[1] if len(args) == 2 else None
    text = open(args[0], encoding="utf-8").read()
    for m in re.finditer(r"(https?:|url\()[^\s\"')]*", text):
        if m.group(0) != "http://www.w3.org/2000/svg":
            fail("external reference in the page: " + m.group(0))
    p = Report()
    p.feed(text)
    if p.forbidden:
        fail("not self-contained: " + ", ".join(p.forbidden[:5]))
    tets = int(p.body.get("data-tets", "-1"))
    edges = int(p.body.get("data-edges", "-1"))
    if tets <= 0 or edges <= 0:
        fail("body data-tets/data-edges missing or zero: %r" % p.body)
    if metric_mean is not None:
        mean = float(p.body.get("data-edge-mean", "nan"))
        if p.body.get("data-edge-metric") != "1":
            fail("the edge lengths are not in the metric")
        if not metric_mean[0] <= mean <= metric_mean[1]:
            fail("mean metric edge length %g not in [%g, %g]" % (mean, metric_mean[0], metric_mean[1]))
        print("mean metric edge length %g" % mean)
    elif p.body.get("data-edge-metric") != "0":
        fail("edge lengths in a metric, none given")
    hists = {s[0].get("data-name"): s for s in p.svgs if s[0].get("class") == "hist"}
    expect_total = {"radius-ratio": tets, "mean-ratio": tets, "dihedral": 6 * tets, "edge-length": edges}
    for name, total in expect_total.items():
        if name not in hists:
            fail("histogram %s missing (have %s)" % (name, sorted(hists)))
        attrs, els = hists[name]
        bins = int(attrs["data-bins"])
        if len(els["bar-all"]) != bins or len(els["bar-bnd"]) != bins:
            fail("histogram %s: %d bins but %d/%d bars" % (name, bins, len(els["bar-all"]), len(els["bar-bnd"])))
        got = sum(els["bar-all"])
        if got != total:
            fail("histogram %s: bars add up to %d, expected %d" % (name, got, total))
        if not any(c > 0 for c in els["bar-all"]):
            fail("histogram %s: every bar empty" % name)
        if any(b > a for a, b in zip(els["bar-all"], els["bar-bnd"])):
            fail("histogram %s: a boundary bar exceeds its all-tets bar" % name)
        print("histogram %s: %d bins, %d items, %d touching the boundary" % (name, bins, got, sum(els["bar-bnd"])))
    cuts = {s[0].get("data-axis"): s for s in p.svgs if s[0].get("class") == "cut"}
    for axis in "xyz":
        if axis not in cuts:
            fail("cut view %s missing" % axis)
        attrs, els = cuts[axis]
        n = int(attrs["data-polygons"])
        if n <= 0 or len(els["polygon"]) != n:
            fail("cut view %s: data-polygons %d, %d <polygon> elements" % (axis, n, len(els["polygon"])))
        for pts in els["polygon"]:
            k = len(pts.split())
            if k not in (3, 4):
                fail("cut view %s: a polygon with %d points: %r" % (axis, k, pts))
        crossed = int(attrs["data-crossed"])
        if n > crossed or (cut_max is not None and n != min(cut_max, crossed)):
            fail("cut view %s: %d polygons drawn, %d tets crossed, cap %s" % (axis, n, crossed, cut_max))
        print("cut view %s: %d polygons (%d tets crossed)" % (axis, n, crossed))
    if cut_max is not None:
        if not any(int(c[0]["data-crossed"]) > cut_max for c in cuts.values()):
            fail("no cut view crosses more than %d tets: the cap was not exercised" % cut_max)
        if "nearest the centre of the cut" not in text:
            fail("a capped cut view does not say so in its caption")
    if png_path:
        png = open(png_path, "rb").read()
        if png[:8] != b"\x89PNG\r\n\x1a\n":
            fail("screenshot is not a PNG")
        w, h = struct.unpack(">II", png[16:24])
        if (w, h) != (1400, 2000):
            fail("screenshot is %dx%d, expected 1400x2000" % (w, h))
        if len(png) < 20000:
            fail("screenshot only %d bytes: the page looks blank" % len(png))
        print("screenshot: %dx%d, %d bytes" % (w, h, len(png)))
    print("PASS")


main()
