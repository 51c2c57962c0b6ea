"""Pieces shared by the HTML sections: escaping, verdict cells, tables, figures, style."""
import html
import re

from . import formatting as fmt

CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", sans-serif; margin: 0 auto;
       max-width: 1200px; padding: .6rem 1.2rem 3rem; color: #1d1d1f; line-height: 1.4;
       box-sizing: border-box; }
h1 { margin: .2rem 0; font-size: 1.6rem; display: flex; align-items: center; gap: .8rem; }
h2 { border-bottom: 2px solid #d0d7de; padding-bottom: .15rem; margin: 1.6rem 0 .5rem; font-size: 1.25rem; }
h3 { margin: .2rem 0; font-size: 1.05rem; display: inline; }
h4 { margin: 1rem 0 .3rem; color: #444; }
.banner .summary { font-weight: 400; font-size: .85rem; margin-left: .5rem; }
.tight { margin: .2rem 0 .4rem; }
table.compact td, table.compact th { padding: .05rem .45rem; }
.scope, .muted { color: #666; font-size: .85rem; }
.scope { margin: .2rem 0; }
.banner { padding: .45rem .9rem; border-radius: 6px; font-weight: 600; margin: .5rem 0; }
.banner.pass { background: #dcf5dc; color: #145214; border: 1px solid #9ad29a; }
.banner.fail { background: #fbdcdb; color: #8a1c1c; border: 1px solid #e59a97; }
h2#failed, h2#problems { margin-top: .6rem; }
.failed { background: #fbdcdb; border: 1px solid #e59a97; border-radius: 6px; padding: .3rem 1.2rem;
          margin-bottom: .8rem; }
.problems { background: #fff4e5; border: 1px solid #f0b45a; border-radius: 6px; padding: .3rem 1.2rem;
            margin-bottom: .8rem; }
.boxes { display: grid; grid-template-columns: 1fr 1.25fr; gap: 1rem; align-items: start; }
.box { border: 1px solid #d0d7de; border-radius: 6px; padding: .2rem .8rem .5rem; background: #fafbfc; }
.box h2 { margin-top: .3rem; font-size: 1.05rem; border: none; }
.big { font-size: 1.5rem; font-weight: 700; }
table { border-collapse: collapse; margin: .3rem 0 .8rem; font-size: .85rem; }
th, td { border: 1px solid #d0d7de; padding: .18rem .45rem; text-align: left; vertical-align: top; }
th { background: #f0f3f6; }
table.full { width: 100%; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tr.family td { background: #eef1f4; font-weight: 600; color: #333; }
td.pass, .badge.pass { background: #dcf5dc; color: #145214; font-weight: 600; }
td.fail, .badge.fail { background: #fbdcdb; color: #8a1c1c; font-weight: 600; }
td.invalid, .badge.invalid { background: #ffe9b3; color: #7a4b00; font-weight: 600; }
td.verdict { text-align: center; width: 4.5rem; }
.badge { border-radius: 4px; padding: 0 .4rem; font-size: .8rem; }
h1 .badge { font-size: 1.1rem; padding: .1rem .6rem; }
.desc, .reason, .src { color: #555; font-size: .78rem; }
.reason { font-style: italic; }
.src { color: #8a6d00; }
td.key { font-size: .82rem; }
.bar { display: inline-block; height: .7rem; background: #7a9cc6; border-radius: 2px;
       vertical-align: middle; }
td.barcell { width: 38%; }
dl.meta { display: grid; grid-template-columns: max-content auto; gap: .1rem 1rem; font-size: .85rem; }
dl.meta dt { font-weight: 600; color: #444; }
dl.meta dd { margin: 0; word-break: break-all; }
details.case { border: 1px solid #d0d7de; border-radius: 6px; margin: .4rem 0; padding: .3rem .8rem; }
details.case[open] { padding-bottom: .8rem; }
details.case > summary { cursor: pointer; }
details.case > summary .muted { margin-left: .6rem; }
details.sub > summary { cursor: pointer; color: #0a4fa0; margin: .5rem 0 .2rem; }
.grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(340px, 1fr)); gap: .6rem; }
figure { margin: .3rem 0 .6rem; }
figure img { max-width: 100%; border: 1px solid #e1e4e8; }
figcaption { font-size: .8rem; color: #555; }
pre { background: #f6f8fa; border: 1px solid #d0d7de; padding: .5rem; overflow-x: auto; font-size: .8rem; }
code { font-size: .9em; }
.wide { overflow-x: auto; }
nav.links { font-size: .9rem; margin: .4rem 0; }
nav.links a { margin-right: 1rem; }
"""

# Opens a closed <details> when a link points at it (the case table links to the sections).
SCRIPT = """
function openTarget() {
  var e = document.getElementById(decodeURIComponent(location.hash.slice(1)));
  if (e && e.tagName === 'DETAILS') { e.open = true; }
}
window.addEventListener('hashchange', openTarget);
window.addEventListener('DOMContentLoaded', openTarget);
"""


def esc(value):
    return html.escape(str(value), quote=True)


def verdict_class(verdict):
    return verdict if verdict in ("pass", "fail") else "invalid"


def verdict_cell(verdict):
    return f'<td class="{verdict_class(verdict)} verdict">{esc(fmt.verdict_text(verdict))}</td>'


def badge(verdict):
    return f'<span class="badge {verdict_class(verdict)}">{esc(fmt.verdict_text(verdict))}</span>'


def anchor_ids(records):
    """record.path -> unique HTML id for its section."""
    ids, used = {}, set()
    for r in records:
        base = "case-" + (re.sub(r"[^A-Za-z0-9_.-]+", "-", r.case).strip("-") or "x")
        anchor, n = base, 2
        while anchor in used:
            anchor, n = f"{base}-{n}", n + 1
        used.add(anchor)
        ids[r.path] = anchor
    return ids


def simple_table(headers, rows, numeric=()):
    head = "".join(f"<th>{esc(h)}</th>" for h in headers)
    body = []
    for row in rows:
        cells = "".join(f"<td class='num'>{esc(v)}</td>" if i in numeric else f"<td>{esc(v)}</td>"
                        for i, v in enumerate(row))
        body.append(f"<tr>{cells}</tr>")
    return f"<div class='wide'><table><tr>{head}</tr>{''.join(body)}</table></div>"


def figure(path, caption):
    if not path:
        return f"<p class='muted'>{esc(caption)}: nothing to plot.</p>"
    return (f"<figure><img src='{esc(path)}' alt='{esc(caption)}' loading='lazy'>"
            f"<figcaption>{esc(caption)}</figcaption></figure>")


def collapsible(title, body, open_=False):
    """A <details> block; `title` is HTML."""
    return (f"<details class='sub'{' open' if open_ else ''}><summary>{title}</summary>"
            f"{body}</details>")
