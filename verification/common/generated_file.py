"""A file written by a derivation script (the manufactured-solution headers of the V&V cases):
write it, or with --check say whether the committed copy is current (exit 1 if stale)."""
import pathlib
import sys


def write_or_check(target: pathlib.Path, text: str, script: str) -> int:
    if "--check" in sys.argv:
        current = target.read_text() if target.exists() else ""
        if current != text:
            print(f"{target} is stale: rerun {pathlib.Path(script).name}", file=sys.stderr)
            return 1
        print(f"{target} is up to date")
        return 0
    target.write_text(text)
    print(f"wrote {target}")
    return 0
