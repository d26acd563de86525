#!/usr/bin/python3
"""report.html in a real browser (docs/sweeps.md, "The report page"): a small sweep with videos,
its report, and the page opened in headless Chromium. Checks that the page runs without script
errors under its Content-Security-Policy, that every image and every video loads, and that a click
on a column heading reorders the rows. Then a report whose every name carries markup (a script,
an event handler, a table break, a Markdown link, bidirectional controls) is opened: nothing of
it runs and the page holds no element it injected. Exit 77 (ctest: skipped) with a message when
Chromium is not installed.

usage: report_html_browser_test.py MSBENCH SOURCE_DIR WORK_DIR
"""
import base64
import csv
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys

# Injected first into <head>: records script errors and failed loads, then, once the page and
# its videos' metadata have loaded, checks the images, sorts the runs table by its first column
# twice and writes what it found into the title (read back from the dumped DOM).
PROBE = r"""<script>
window.__errors = [];
window.addEventListener('error', e => {
  const t = e.target;
  if (t && (t.tagName === 'IMG' || t.tagName === 'VIDEO')) window.__errors.push('load failed: ' + (t.currentSrc || t.src));
  else window.__errors.push('script error: ' + e.message);
}, true);
window.addEventListener('load', () => {
  const videos = Array.from(document.querySelectorAll('video'));
  const ready = videos.map(v => new Promise(res => {
    if (v.readyState >= 1) return res(true);
    v.addEventListener('loadedmetadata', () => res(true));
    v.addEventListener('error', () => res(false));
    v.load();
  }));
  Promise.all(ready).then(states => {
    const imgs = Array.from(document.querySelectorAll('img'));
    const runs = Array.from(document.querySelectorAll('table')).pop();
    const first = () => Array.from(runs.tBodies[0].rows).map(r => r.cells[0].textContent);
    const before = first();
    const th = runs.querySelector('th');
    th.click();
    const asc = first();
    th.click();
    const desc = first();
    document.title = 'RESULT:' + JSON.stringify({
      errors: window.__errors,
      images: imgs.length,
      images_loaded: imgs.filter(i => i.complete && i.naturalWidth > 0).length,
      videos: videos.length,
      videos_loaded: states.filter(s => s).length,
      video_sizes: videos.map(v => [v.videoWidth, v.videoHeight]),
      tables: document.querySelectorAll('table').length,
      before: before, asc: asc, desc: desc,
    });
  });
});
</script>"""

SWEEP = """# report.html browser test: two short runs with videos
scenario: {scenario}
set: {{duration_s: 12, video.enabled: true, video.speedup: 4, video.fps: 5, video.height: 360}}
axes:
  - name: code
    variants:
      a: {{}}
      b: {{method.switches.vpb: false}}
seeds: [1]
"""


# Every user-controlled field of the injection report carries these.
PAYLOADS = ['<img id="injected" src=x onerror="document.title=\'PWNED\'">',
            "<script>document.title='PWNED'</script>",
            "</table><h1 id=\"injected\">x</h1>",
            "[click](javascript:document.title='PWNED')",
            "\u202egnp.exe\u202c \u200fmark",
            "<a href=\"javascript:document.title='PWNED'\" id=\"injected\">a</a>"]


# The injection page's probe: at load, what the page holds (the probe's own script and the page's:
# 2 script elements) and its title then (a payload that ran would have set it).
INJECTION_PROBE = r"""<script>
window.__errors = [];
window.addEventListener('error', e => window.__errors.push(String(e.message || e.type)), true);
window.addEventListener('load', () => {
  const all = Array.from(document.querySelectorAll('*'));
  const text = document.body.innerText;
  document.title = 'CHECK:' + JSON.stringify({
    title: document.title,
    errors: window.__errors,
    injected: document.querySelectorAll('#injected').length,
    handlers: all.filter(e => Array.from(e.attributes).some(a => a.name.startsWith('on'))).length,
    js_links: document.querySelectorAll('a[href^="javascript"], [src^="javascript"]').length,
    scripts: document.querySelectorAll('script').length,
    headings1: document.querySelectorAll('h1').length,
    hidden_chars: /[\u200b-\u200f\u202a-\u202e\u2066-\u2069]/.test(text),
  });
});
</script>"""


def with_probe(text, probe):
    """The page with `probe` first in <head>, its hash added to the page's script-src."""
    body = probe[len("<script>"):-len("</script>")]
    digest = "'sha256-" + base64.b64encode(hashlib.sha256(body.encode("utf-8")).digest()).decode("ascii") + "'"
    if "script-src " not in text:
        fail("the page has no Content-Security-Policy with a script-src")
    text = text.replace("script-src ", "script-src " + digest + " ", 1)
    return text.replace("<head>", "<head>\n" + probe, 1)


def dump_dom(chromium, page):
    return subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--mute-audio",
                           "--autoplay-policy=no-user-gesture-required", "--virtual-time-budget=30000", "--dump-dom",
                           "file://" + page], capture_output=True, text=True, timeout=180).stdout


def probed_result(chromium, page, probe, tag):
    """`page` opened with `probe` (a copy beside it, so its relative links are the page's): what
    the probe wrote into the title after `tag:`, as JSON."""
    with open(page, encoding="utf-8") as f:
        text = f.read()
    probed = os.path.join(os.path.dirname(page), "probe.html")
    with open(probed, "w", encoding="utf-8") as f:
        f.write(with_probe(text, probe))
    dom = dump_dom(chromium, probed)
    m = re.search(r"<title>%s:(.*?)</title>" % tag, dom, re.S)
    if not m:
        fail("the page's checks did not run (no %s in the title):\n%s" % (tag, dom[:2000]))
    return json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&"))


def injection_check(chromium, source, work):
    """A report whose names are payloads, made into a page and opened: nothing ran, nothing injected."""
    rep = os.path.join(work, "injected_report")
    os.makedirs(rep)
    name = " ".join(PAYLOADS)
    with open(os.path.join(rep, "report.md"), "w", encoding="utf-8") as f:
        f.write(f"# Sweep report: {name}\n\n| run | status |\n| --- | --- |\n| {name} | {name} |\n\n{name}\n")
    with open(os.path.join(rep, "report_runs.csv"), "w", encoding="utf-8", newline="") as f:
        w = csv.writer(f)
        w.writerow(["id", "world", "series", "status", "run_status", "dir", "area_m2", "verified_area_m2",
                    "score_earned_m3"])
        w.writerow([name, name, name, "complete", name, os.path.join(work, name.replace("/", "_")), "1", "1", "1"])
    subprocess.run([sys.executable, os.path.join(source, "tools/sweep/report_html.py"), rep], check=True)
    r = probed_result(chromium, os.path.join(rep, "report.html"), INJECTION_PROBE, "CHECK")
    print(json.dumps(r))
    if r["title"].strip() == "PWNED" or r["errors"]:
        fail("a payload ran: %s" % r)
    if r["injected"] or r["handlers"] or r["js_links"] or r["scripts"] != 2 or r["headings1"] != 1:
        fail("the page holds injected elements: %s" % r)
    if r["hidden_chars"]:
        fail("bidirectional or zero-width characters reached the page: %s" % r)
    print("ok: a report whose names are payloads renders inert")


def find_chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def main():
    msbench, source, work = sys.argv[1:4]
    chromium = find_chromium()
    if not chromium:
        print("SKIP: chromium is not installed (apt-get install chromium); report.html was not opened in a browser")
        sys.exit(77)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    sweep_file = os.path.join(work, "sweep.yaml")
    with open(sweep_file, "w") as f:
        f.write(SWEEP.format(scenario=os.path.join(source, "scenarios/missions/test_world_short.yaml")))
    sweep = os.path.join(work, "sweep")
    subprocess.run([msbench, "sweep", sweep_file, "--out", sweep, "--jobs", "2"], check=True)
    subprocess.run([msbench, "report", sweep], check=True)
    page = os.path.join(sweep, "report", "report.html")
    if not os.path.exists(page):
        fail("no report.html")
    r = probed_result(chromium, page, PROBE, "RESULT")
    print(json.dumps(r, indent=1))
    if r["errors"]:
        fail("errors: %s" % r["errors"])
    if r["images"] < 3 or r["images_loaded"] != r["images"]:
        fail("images: %d of %d loaded (expected the figures and both runs' top-downs)" % (r["images_loaded"], r["images"]))
    if r["videos"] != 2 or r["videos_loaded"] != 2:
        fail("videos: %d of %d loaded (expected 2)" % (r["videos_loaded"], r["videos"]))
    if any(h != 360 for _, h in r["video_sizes"]):
        fail("video sizes %s (expected height 360)" % r["video_sizes"])
    if r["asc"] != sorted(r["before"]) or r["desc"] != sorted(r["before"], reverse=True) or r["asc"] == r["desc"]:
        fail("sorting by the first column: before %s, ascending %s, descending %s" % (r["before"], r["asc"], r["desc"]))
    print("ok: report.html renders without errors, %d images and %d videos load, sorting reorders the rows"
          % (r["images"], r["videos"]))
    injection_check(chromium, source, work)


if __name__ == "__main__":
    main()
