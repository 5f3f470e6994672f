#!/usr/bin/env python3
"""Public items of the crate, counted in its generated docs (issue 18's count).

    python3 measure/api.py              # cargo doc --no-deps, then count and list by kind
    python3 measure/api.py --no-build   # count the docs already in target/doc
    python3 measure/api.py --max 150    # fail when there are more than 150 (CI)
    python3 measure/api.py --list       # every item's page

An item is a page of rustdoc's for a struct, enum, trait, function, type alias,
constant, static, macro or union under `target/doc/fixshade/`. Not counted: the
prelude's pages (re-exports of items counted where they live) and the redirect
pages rustdoc writes for re-exports (`http-equiv="refresh"`). Methods, fields,
variants and associated items are parts of their item's page, not items.
"""

import argparse
import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DOC = ROOT / "target" / "doc" / "fixshade"
KINDS = ("struct", "enum", "trait", "fn", "type", "constant", "static", "macro", "union")
PAGE = re.compile(r"^(" + "|".join(KINDS) + r")\.[^/]+\.html$")


def items() -> list[Path]:
    out = []
    for page in sorted(DOC.rglob("*.html")):
        rel = page.relative_to(DOC)
        if rel.parts[0] == "prelude" or not PAGE.match(page.name):
            continue
        if 'http-equiv="refresh"' in page.read_text(errors="replace"):
            continue
        out.append(rel)
    return out


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--no-build", action="store_true", help="use the docs in target/doc")
    p.add_argument("--max", type=int, help="fail when there are more items than this")
    p.add_argument("--list", action="store_true", help="print every item's page")
    a = p.parse_args()
    if not a.no_build:
        subprocess.run(["cargo", "doc", "--no-deps", "--quiet"], cwd=ROOT, check=True)
    if not DOC.is_dir():
        sys.exit(f"FAIL: no docs in {DOC} (run without --no-build)")
    found = items()
    kinds = Counter(p.name.split(".")[0] for p in found)
    print(f"{len(found)} public items: " + ", ".join(f"{n} {k}" for k, n in kinds.most_common()))
    if a.list:
        for page in found:
            print(f"  {page}")
    if a.max is not None and len(found) > a.max:
        sys.exit(f"FAIL: {len(found)} public items, more than {a.max}")


if __name__ == "__main__":
    main()
