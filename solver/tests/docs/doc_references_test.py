#!/usr/bin/env python3
"""Every reference to a section of a page in docs/ names a section that page has.

The code and the pages cite sections as  docs/<page>.md, "Title"  or  docs/<page>.md "Title"
(straight or curly quotes, possibly broken over comment lines). A reference resolves when some
section of that page starts with the title: a heading (its number, as in "5. " or "E1. ", left
aside) or a paragraph that opens with a bold or italic lead-in (**Title.** or *Title*). Titles may
be cited without their date, e.g. "Pair lists" for "Pair lists and a portable exponential
(2026-12-04)". A page that does not exist, or a title no section starts with, fails the test with
the file and line of the reference.

usage: doc_references_test.py SOURCE_DIR
"""
import os
import pathlib
import re
import sys

SUFFIXES = {".cpp", ".hpp", ".h", ".md", ".txt", ".sh", ".py", ".toml", ".in"}
# docs/<page>.md (or <page>.md alone, when docs/ has such a page), then an optional comma or an
# opening parenthesis, then a quoted title. Between the parts, and inside the title, only spaces,
# line breaks and the comment leaders (// or #) of a continued comment.
GAP = r"(?:[ \t]|\n[ \t]*(?://|#)?[ \t]*)*"
BREAK = r"\n[ \t]*(?://|#)?[ \t]*"  # a line break inside a comment or a paragraph
REFERENCE = re.compile(r"(docs/)?([A-Za-z0-9_-]+\.md)" + GAP + r",?" + GAP + r"\(?" +
                       r"[\"“]([A-Za-z0-9\[`](?:[^\"”\n]|" + BREAK + r")*)[\"”]")
HEADING = re.compile(r"^#{1,6}[ \t]+(?:[A-Z]?[0-9]+[a-z]?\.[ \t]+)?(.+?)[ \t]*#*[ \t]*$", re.MULTILINE)
LEAD_IN = re.compile(r"^(?:[-*][ \t]+)?\*{1,2}([^*\n]+)\*{1,2}", re.MULTILINE)


def section_titles(page: pathlib.Path) -> list[str]:
    """The titles a reference may cite: the headings and the paragraphs' bold or italic lead-ins."""
    text = page.read_text(encoding="utf-8")
    return [h.replace("`", "") for h in HEADING.findall(text) + LEAD_IN.findall(text)]


def source_files(root: pathlib.Path):
    """The repository's text files, in a fixed order; .git and build folders (build, build-dev, ...)
    are not entered."""
    for folder, subfolders, files in os.walk(root):
        subfolders[:] = sorted(d for d in subfolders if d != ".git" and not d.startswith("build"))
        for name in sorted(files):
            path = pathlib.Path(folder) / name
            if path.suffix in SUFFIXES:
                yield path


def main() -> int:
    root = pathlib.Path(sys.argv[1]).resolve()
    docs = root / "docs"
    cache: dict[str, list[str] | None] = {}
    checked, failures = 0, []
    for path in source_files(root):
        text = path.read_text(encoding="utf-8", errors="replace")
        for match in REFERENCE.finditer(text):
            prefixed, page = match.group(1) is not None, match.group(2)
            title = re.sub(BREAK, " ", match.group(3)).strip().replace("`", "")
            if not prefixed and not (docs / page).is_file():
                continue  # a file named alone that is not a docs page (README.md "...")
            if page not in cache:
                cache[page] = section_titles(docs / page) if (docs / page).is_file() else None
            line = text.count("\n", 0, match.start()) + 1
            where = f"{path.relative_to(root)}:{line}"
            checked += 1
            if cache[page] is None:
                failures.append(f"{where}: docs/{page} does not exist")
            elif not any(h.startswith(title) for h in cache[page]):
                failures.append(f'{where}: docs/{page} has no section starting with "{title}"')
    for f in failures:
        print("FAIL", f)
    print(f"{checked} references to sections of docs/ checked, {len(failures)} unresolved")
    if checked == 0:
        print("FAIL no reference found: the pattern no longer matches how the repository cites its pages")
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
