#!/usr/bin/python3
"""report.html of a sweep report (msbench report writes this script into the report directory and
runs it after the figures; run it again by hand with `python3 make_html.py REPORT_DIR`).

One self-contained page, no network: report.md's sections as HTML (every table sortable by a
click on any column heading; the findings' verdicts coloured), the figures embedded (table1.png,
coverage_<world>.png, ablation_levels_<world>.png), the gallery beside it (gallery.png), and a
table of the runs with each run's top-down picture and video linked where the run directory has
them, its claimed and verified area (from report_runs.csv: msbench's reading of the checked records) and
a flag where the method claims more than msbench could verify. The same inputs give the same page, byte for byte. Needs Debian's python3-markdown.
"""
import base64
import csv
import hashlib
import html
import os
import re
import sys
import urllib.parse

import markdown

# A run whose verified area is below this share of its claimed area is flagged.
VERIFIED_FLAG_SHARE = 0.9

STYLE = """
body { font: 14px/1.45 system-ui, sans-serif; margin: 1.5em auto; max-width: 1400px; padding: 0 1em; color: #222; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 7px; text-align: left; vertical-align: top; }
th { background: #f0f0f0; cursor: pointer; user-select: none; white-space: nowrap; }
th.sorted-asc::after { content: " \\25B2"; } th.sorted-desc::after { content: " \\25BC"; }
td.holds { background: #d8f5d0; } td.fails { background: #f9d0d0; } td.undecided { background: #fbefc8; }
td.flag { background: #f9d0d0; }
img.figure { max-width: 100%; border: 1px solid #ddd; margin: 0.5em 0; }
img.thumb { width: 220px; border: 1px solid #ddd; }
video { width: 320px; }
"""

# Sorting: a click on a heading sorts the table's rows by that column (numbers by their first
# number, else text), a second click reverses.
SCRIPT = """
function cellKey(td) {
  const t = td.textContent.trim();
  const m = t.match(/^[^0-9-]*(-?[0-9]+(\\.[0-9]+)?)/);
  return m ? [0, parseFloat(m[1]), t] : [1, 0, t];
}
function sortBy(th) {
  const table = th.closest('table'), body = table.tBodies[0];
  const col = Array.from(th.parentNode.children).indexOf(th);
  const asc = !th.classList.contains('sorted-asc');
  table.querySelectorAll('th').forEach(h => h.classList.remove('sorted-asc', 'sorted-desc'));
  th.classList.add(asc ? 'sorted-asc' : 'sorted-desc');
  const rows = Array.from(body.rows);
  rows.sort((a, b) => {
    const x = cellKey(a.cells[col]), y = cellKey(b.cells[col]);
    const c = x[0] - y[0] || (x[0] === 0 ? x[1] - y[1] : x[2].localeCompare(y[2]));
    return asc ? c : -c;
  });
  rows.forEach(r => body.appendChild(r));
}
document.querySelectorAll('table th').forEach(th => th.addEventListener('click', () => sortBy(th)));
"""


def data_uri(path):
    with open(path, "rb") as f:
        return "data:image/png;base64," + base64.b64encode(f.read()).decode("ascii")


# Characters that reorder or hide text (bidirectional overrides and isolates, marks, zero-width
# joiners) and control characters: a name from a file never carries them into the page.
_HIDDEN = re.compile("[\u0000-\u0008\u000b\u000c\u000e-\u001f\u007f\u200b-\u200f\u202a-\u202e"
                     "\u2066-\u2069\ufeff]")
# The elements Markdown makes of msbench's report.md; anything else is shown as text.
_ALLOWED_TAGS = {"h1", "h2", "h3", "h4", "p", "table", "thead", "tbody", "tr", "th", "td", "ul", "ol", "li", "code",
                 "pre", "em", "strong", "br", "hr", "blockquote"}
_TAG = re.compile(r"<(/?)([a-zA-Z][a-zA-Z0-9]*)((?:\s[^<>]*)?)>")


def name_text(text):
    """A name from a file (a run id, a world, a series) for one table cell: the characters
    msbench's mdText removes for report.md (hidden characters and every control character, line
    breaks included) removed, then HTML-escaped — the same rule as the names report.md shows."""
    return html.escape(re.sub("[\t\n\r]", "", _HIDDEN.sub("", text)))


def inert(text):
    """report.md made inert before Markdown: raw HTML shown as text (report.md holds none of its
    own), hidden characters removed."""
    return _HIDDEN.sub("", text).replace("<", "&lt;")


def allowed_only(body):
    """Markdown's output with every element outside _ALLOWED_TAGS, and every attribute but a
    table cell's alignment, shown as text: a link or an image written in Markdown syntax inside a
    name is never one."""
    def keep(m):
        closing, tag, attrs = m.group(1), m.group(2).lower(), m.group(3)
        if tag not in _ALLOWED_TAGS:
            return html.escape(m.group(0))
        if attrs and not re.fullmatch(r'\s+style="text-align: (left|right|center);"', attrs):
            attrs = ""
        return f"<{closing}{tag}{attrs}>"
    return _TAG.sub(keep, body)


def body_of_markdown(report_dir):
    """report.md as HTML, its tables with a <tbody> and its verdict cells coloured."""
    with open(os.path.join(report_dir, "report.md"), encoding="utf-8", errors="replace") as f:
        text = f.read()
    body = allowed_only(markdown.markdown(inert(text), extensions=["tables"], output_format="html"))
    for verdict in ("holds", "fails", "undecided"):
        body = re.sub(r"<td>([✓✗?] %s)</td>" % verdict, r'<td class="%s">\1</td>' % verdict, body)
    return body


def figures_html(report_dir):
    """The figures: embedded, except the gallery (large), shown from beside the page."""
    names = sorted(os.listdir(report_dir))
    parts = []
    for name in ["table1.png"] + [n for n in names if re.match(r"(coverage|ablation_levels)_.*\.png$", n)]:
        path = os.path.join(report_dir, name)
        if os.path.exists(path):
            parts.append(f'<p><img class="figure" alt="{html.escape(name)}" src="{data_uri(path)}"></p>')
    if os.path.exists(os.path.join(report_dir, "gallery.png")):
        parts.append('<p><a href="gallery.png"><img class="figure" alt="gallery" src="gallery.png"></a></p>')
    return ("<h2>Figures</h2>\n" + "\n".join(parts)) if parts else ""


def run_row(run, final_dir):
    """One run's row: id, world, series, status, claimed and verified A, earned score, pictures, video."""
    run_dir = os.path.abspath(run["dir"] or "")
    # The run's directory as a URL path: every character but letters, digits and "_.-~/" as %XX,
    # so a control character or a quote in a run id stays out of the attribute.
    rel = urllib.parse.quote(os.path.relpath(run_dir, final_dir))
    # The areas msbench read from the run's checked record (report_runs.csv); a run's own files
    # are never opened here, but for the pictures it links.
    claimed = float(run["area_m2"]) if run.get("area_m2") else None
    verified = float(run["verified_area_m2"]) if run.get("verified_area_m2") else None
    share = verified / claimed if claimed and verified is not None else None
    flagged = share is not None and share < VERIFIED_FLAG_SHARE
    cells = [name_text(run[k] or "") for k in ("id", "world", "series", "run_status")]
    cells.append("" if claimed is None else f"{claimed:.0f}")
    cells.append("" if verified is None else f"{verified:.0f}")
    share_text = "" if share is None else f"{share:.2f}" + (" ⚑ claims more than verified" if flagged else "")
    cells.append(share_text)
    earned = run.get("score_earned_m3")  # absent from reports before the earned score
    cells.append(f"{float(earned):.0f}" if earned else "")
    pic = os.path.join(run_dir, "topdown.png")
    cells.append(f'<a href="{html.escape(rel)}/topdown.png"><img class="thumb" loading="lazy" alt="top-down" '
                 f'src="{html.escape(rel)}/topdown.png"></a>' if os.path.isfile(pic) else "")
    video = os.path.join(run_dir, "video.mp4")
    cells.append(f'<video controls preload="metadata" src="{html.escape(rel)}/video.mp4"></video>'
                 if os.path.isfile(video) else "")
    tds = "".join(f'<td class="flag">{c}</td>' if i == 6 and flagged else f"<td>{c}</td>" for i, c in enumerate(cells))
    return f"<tr>{tds}</tr>"


def runs_html(report_dir, final_dir):
    with open(os.path.join(report_dir, "report_runs.csv"), newline="", encoding="utf-8", errors="replace") as f:
        runs = list(csv.DictReader(f))
    # Runs not yet run have no pictures: counted, not listed (a sweep of 100 000 pending runs).
    pending = sum(1 for r in runs if r.get("status") == "pending")
    runs = [r for r in runs if r.get("status") != "pending"]
    if not runs:
        return f"<h2>Run pictures</h2>\n<p>{pending} runs not yet run.</p>\n" if pending else ""
    head = "".join(f"<th>{h}</th>" for h in ("run", "world", "series", "status", "A claimed (m²)",
                                              "verified A (m²)", "verified / claimed", "earned (m³)", "top-down",
                                              "video"))
    rows = "\n".join(run_row(r, final_dir) for r in runs)
    return ("<h2>Run pictures</h2>\n<p>Each run's top-down map and video where its directory has them "
            f"(<code>msbench video RUN</code> adds one); ⚑: verified area below {VERIFIED_FLAG_SHARE:.0%} of the "
            "claimed (docs/metrics.md, \"Verified coverage\")"
            + (f"; {pending} runs not yet run are not listed" if pending else "") + ".</p>\n"
            f"<table><thead><tr>{head}</tr></thead><tbody>\n{rows}\n</tbody></table>")


def csp():
    """The page's Content-Security-Policy: its own style and script (by hash) and nothing else
    runs; images from beside the page or embedded, videos from beside it."""
    def sha(text):
        return "'sha256-" + base64.b64encode(hashlib.sha256(text.encode("utf-8")).digest()).decode("ascii") + "'"
    return (f"default-src 'none'; style-src {sha(STYLE)}; script-src {sha(SCRIPT)}; img-src 'self' data: file:; "
            "media-src 'self' file:; base-uri 'none'; form-action 'none'")


def page(report_dir, final_dir):
    body = body_of_markdown(report_dir)
    title = re.search(r"<h1>(.*?)</h1>", body)
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<meta http-equiv=\"Content-Security-Policy\" content=\"{csp()}\">\n"
            f"<title>{title.group(1) if title else 'msbench report'}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n"
            f"{body}\n{figures_html(report_dir)}\n{runs_html(report_dir, final_dir)}\n"
            f"<script>{SCRIPT}</script>\n</body>\n</html>\n")


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: make_html.py REPORT_DIR [FINAL_DIR]")
    report_dir = sys.argv[1]
    # Links to the runs are relative to where the page will live (the report is written staged).
    final_dir = os.path.abspath(sys.argv[2] if len(sys.argv) == 3 else report_dir)
    text = page(report_dir, final_dir)
    with open(os.path.join(report_dir, "report.html"), "w", encoding="utf-8") as f:
        f.write(text)
    print(f"report.html written to {report_dir}")


if __name__ == "__main__":
    main()
