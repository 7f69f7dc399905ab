"""Regenerate the tables of docs/validation/dynamic_curves_vs_f109.md from the committed curve
sweeps and F109's generalized tables (onbottom.checks.f109_generalized).

Run from the repository root: ``PYTHONPATH=src python tools/curves_vs_f109.py`` (rewrites the
page's generated block; ``--check`` only says whether it is current, exit 1 if not).
tests/unit/test_curves_vs_f109.py fails while the page is not current.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from onbottom.report.curves_vs_f109 import current_block, page_block, replace_block

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "validation" / "dynamic_curves_vs_f109.md"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="exit 1 if the page is not current")
    args = ap.parse_args()
    text = PAGE.read_text(encoding="utf-8")
    block = page_block(ROOT)
    if args.check:
        current = current_block(text) == block
        print(f"{PAGE.relative_to(ROOT)}: {'current' if current else 'NOT current'}")
        return 0 if current else 1
    new = replace_block(text, block)
    if new != text:
        tmp = PAGE.with_suffix(".md.tmp")
        tmp.write_text(new, encoding="utf-8")
        tmp.replace(PAGE)
    print(f"{PAGE.relative_to(ROOT)}: {'rewritten' if new != text else 'already current'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
