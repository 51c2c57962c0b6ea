"""Finding the generated sections of a docs page and putting new text into them.

A section starts with a marker comment on a line of its own and ends with the next
end marker (docs/reports.md, "Measured sections of the docs pages"):

    <!-- measured: validation.capsule_shear runs: capillary,D,theta_deg -->
    ... generated Markdown ...
    <!-- end measured -->

After the case name come optional settings, each `key: a,b,c`:
  runs     the run-row columns to show (default: no runs table)
  metrics  the metrics to show, by name or shell-style pattern (default: all)
  params   the record's parameters to show, by name or pattern (default: none)
  where    run rows to keep, `column=value` or `column=a|b` (several: a row must match all)
  parts    what to show, of head (verdict, requirement, reference), metrics, params, runs
           (default: all of them that apply), for a second section of one case
"""
import re
from dataclasses import dataclass, field

START = re.compile(r"^\s*<!--\s*measured:\s*(?P<body>.*?)\s*-->\s*$")
END = re.compile(r"^\s*<!--\s*end measured\s*-->\s*$")
SETTING = re.compile(r"(?:^|\s)(runs|metrics|params|where|parts):\s*")
PARTS = ("head", "metrics", "params", "runs")


class MarkerError(Exception):
    """A page whose markers cannot be paired or read; the message names the line."""


@dataclass
class Section:
    case: str
    runs: list = field(default_factory=list)      # run-row columns, in order
    metrics: list = field(default_factory=list)   # metric names or patterns; [] = all
    params: list = field(default_factory=list)    # parameter names or patterns; [] = none
    where: list = field(default_factory=list)     # (column, value) pairs
    parts: list = field(default_factory=lambda: list(PARTS))
    start: int = 0        # index of the start-marker line
    end: int = 0          # index of the end-marker line
    body: str = ""        # the text between the two marker lines, as on the page

    @property
    def line(self):
        """1-based line number of the start marker, for messages."""
        return self.start + 1


def parse_marker(body, line_no):
    """A Section (without position) from the text of a start marker."""
    parts = SETTING.split(body.strip())
    case = parts[0].strip()
    if not case or " " in case:
        raise MarkerError(f"line {line_no}: marker needs one case name, got {body!r}")
    section = Section(case=case)
    for key, value in zip(parts[1::2], parts[2::2]):
        items = [v.strip() for v in value.split(",") if v.strip()]
        if not items:
            raise MarkerError(f"line {line_no}: '{key}:' without a value")
        if key == "where":
            section.where = [_where_pair(item, line_no) for item in items]
        elif key == "parts" and set(items) - set(PARTS):
            raise MarkerError(f"line {line_no}: 'parts:' takes {', '.join(PARTS)}, got {value!r}")
        else:
            setattr(section, key, items)
    return section


def _where_pair(item, line_no):
    column, sep, value = item.partition("=")
    if not sep or not column.strip():
        raise MarkerError(f"line {line_no}: 'where:' takes column=value, got {item!r}")
    return column.strip(), value.strip()


def find_sections(text):
    """The sections of a page, in order; raises MarkerError on unpaired markers."""
    lines = text.split("\n")
    sections, current = [], None
    for i, line in enumerate(lines):
        start = START.match(line)
        if start:
            if current is not None:
                raise MarkerError(f"line {i + 1}: a measured section starts inside the one "
                                  f"opened at line {current.line}")
            current = parse_marker(start.group("body"), i + 1)
            current.start = i
        elif END.match(line):
            if current is None:
                raise MarkerError(f"line {i + 1}: 'end measured' without a start marker")
            current.end = i
            current.body = "\n".join(lines[current.start + 1:i])
            sections.append(current)
            current = None
    if current is not None:
        raise MarkerError(f"line {current.line}: measured section for {current.case} "
                          "has no 'end measured'")
    return sections


def replace_bodies(text, new_bodies):
    """The page with each section's body replaced; new_bodies maps a section's start
    line index to its new body (sections not in the map keep theirs)."""
    lines = text.split("\n")
    out, i = [], 0
    for section in find_sections(text):
        out += lines[i:section.start + 1]
        body = new_bodies.get(section.start)
        out += (body.split("\n") if body is not None
                else lines[section.start + 1:section.end])
        i = section.end
    out += lines[i:]
    return "\n".join(out)
