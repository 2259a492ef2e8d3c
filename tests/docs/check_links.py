#!/usr/bin/python3
"""Checks the user documentation: every relative link and anchor in README.md and docs/*.md
resolves, and README.md is at most 12,288 bytes.

    check_links.py [ROOT]      ROOT: the repository (default: two folders up from this script)
    check_links.py --self-test the checker finds a broken file link, a broken anchor and a long
                               README in a made-up tree, and passes a good one

Links are Markdown's inline ones, [text](target) and ![alt](target), outside code; targets with
a scheme (https:, mailto:) are not followed. An anchor must be the GitHub id of a heading of the
target page (lower case, punctuation dropped, spaces as hyphens, -1, -2... for repeats).
Standard library only.
"""
import os
import re
import sys
import tempfile

README_MAX_BYTES = 12288
LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")


def prose_lines(text, blank_code=True):
    """(line number, line) outside fenced code, with inline code spans blanked if asked."""
    fence = None
    for number, line in enumerate(text.split("\n"), 1):
        stripped = line.lstrip()
        if fence:
            if stripped.startswith(fence):
                fence = None
            continue
        m = re.match(r"(```+|~~~+)", stripped)
        if m:
            fence = m.group(1)
            continue
        yield number, re.sub(r"(`+)(?:(?!\1).)+?\1", "", line) if blank_code else line


def slug(heading):
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link's text only
    text = text.replace("`", "").strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    seen, ids = {}, set()
    with open(path, encoding="utf-8") as f:
        text = f.read()
    for _, line in prose_lines(text, blank_code=False):
        m = re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        base = slug(m.group(1))
        count = seen.get(base, 0)
        seen[base] = count + 1
        ids.add(base if count == 0 else "%s-%d" % (base, count))
    ids.update(re.findall(r"<a\s+(?:name|id)=\"([^\"]+)\"", text))
    return ids


def check_file(path, root):
    problems = []
    with open(path, encoding="utf-8") as f:
        text = f.read()
    for number, line in prose_lines(text):
        for target in LINK.findall(line):
            if re.match(r"[a-zA-Z][a-zA-Z0-9+.-]*:", target):
                continue  # https:, mailto: ...
            where = "%s:%d: %s" % (os.path.relpath(path, root), number, target)
            file_part, _, anchor = target.partition("#")
            dest = path
            if file_part:
                dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part))
            if not os.path.exists(dest):
                problems.append(where + ": no such file")
                continue
            if anchor:
                if not dest.endswith(".md") or os.path.isdir(dest):
                    problems.append(where + ": an anchor into a file that is not Markdown")
                elif anchor not in anchors(dest):
                    problems.append(where + ": no heading with this anchor in " +
                                    os.path.relpath(dest, root))
    return problems


def check(root):
    problems = []
    readme = os.path.join(root, "README.md")
    size = os.path.getsize(readme)
    if size > README_MAX_BYTES:
        problems.append("README.md: %d bytes, more than %d" % (size, README_MAX_BYTES))
    docs = os.path.join(root, "docs")
    pages = [readme] + sorted(os.path.join(docs, n) for n in os.listdir(docs) if n.endswith(".md"))
    for page in pages:
        problems += check_file(page, root)
    return problems, len(pages)


def self_test():
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "docs"))

        def write(rel, text):
            with open(os.path.join(root, rel), "w", encoding="utf-8") as f:
                f.write(text)

        write("docs/a.md", "# Page A\n\n## The `x` option, again\n\n```\n## not a heading\n```\n")
        write("README.md", "[a](docs/a.md#the-x-option-again) [s](#readme) `[no](nowhere.md)`\n"
                           "# README\n")
        good, _ = check(root)
        write("README.md", "[a](docs/b.md) [b](docs/a.md#not-a-heading) [c](#missing)\n" +
              "x" * README_MAX_BYTES)
        bad, _ = check(root)
    expected = ["more than", "docs/b.md: no such file", "#not-a-heading: no heading",
                "#missing: no heading"]
    missed = [e for e in expected if not any(e in p for p in bad)]
    if good or missed or len(bad) != 4:
        print("self-test failed:\n  good tree: %s\n  bad tree: %s" % (good, bad))
        return 1
    print("self-test: the checker passes a good tree and finds the 4 problems of a bad one")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    root = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))))
    problems, pages = check(root)
    for p in problems:
        print(p)
    if problems:
        return 1
    print("%d pages: every relative link and anchor resolves; README.md %d bytes (at most %d)"
          % (pages, os.path.getsize(os.path.join(root, "README.md")), README_MAX_BYTES))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
