"""Writing a generated docs page, or checking that the committed one is current (the pages'
scripts share it, so a stale page fails the same way whichever script made it)."""
import os
import sys


def write_or_check(target, text, check, regenerate_hint):
    """Writes text to target; with check, returns 1 (saying how to regenerate) when target differs."""
    if check:
        old = open(target, encoding="utf-8").read() if os.path.exists(target) else ""
        if old != text:
            print(f"{target} is stale: {regenerate_hint}", file=sys.stderr)
            return 1
        print(f"{target} is up to date")
        return 0
    with open(target, "w", encoding="utf-8") as fh:
        fh.write(text)
    return 0
