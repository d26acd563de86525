#!/bin/sh
# Publishes a sweep directory as committed results (docs/sweeps.md, "Publishing a sweep"):
#   tools/publish-sweep.sh SWEEP_DIR DEST        e.g. tools/publish-sweep.sh /tmp/table1 results/table1
#   tools/publish-sweep.sh --report-only DEST    the report of published results written anew from
#                                                their committed runs (no run re-done; the gallery,
#                                                which needs the runs' pictures, is kept)
# DEST receives the report (report.md with the findings, report.html, table.csv, findings.csv, the Table I and
# coverage figures, the ablation-across-levels table and figures of a level sweep, and the gallery), the sweep's index (sweep.json, runs.csv) and each run's
# metrics.json, coverage.csv and config.yaml — no maps, trajectories or logs, so that it stays small;
# paths of the machine it ran on are rewritten (the sweep directory to DEST, scenario files
# repository-relative). DEST is replaced as a whole (written next to it, then renamed). Needs msbench
# on PATH or in build/bin.
set -eu
here=$(dirname "$(readlink -f "$0")")
msbench=$(command -v msbench || echo "$here/../build/bin/msbench")
[ -x "$msbench" ] || { echo "$0: msbench not found (build it first)" >&2; exit 2; }
if [ $# -eq 2 ] && [ "$1" = "--report-only" ]; then
  dest=$2
  [ -f "$dest/sweep.json" ] && [ -d "$dest/runs" ] || { echo "$0: $dest is not published results (no sweep.json, runs/)" >&2; exit 2; }
  tmp=$(mktemp -d "${TMPDIR:-/tmp}/msb_report.XXXXXX")
  "$msbench" report "$dest" --out "$tmp/report"
  for f in report.md table.csv findings.csv table1.png ablation_levels.csv; do [ -f "$tmp/report/$f" ] && cp "$tmp/report/$f" "$dest/"; done
  for f in "$tmp"/report/coverage_*.png "$tmp"/report/ablation_levels_*.png; do [ -f "$f" ] && cp "$f" "$dest/"; done
  # report.html over the kept gallery, its links relative to DEST.
  [ -f "$dest/gallery.png" ] && cp "$dest/gallery.png" "$tmp/report/"
  if /usr/bin/python3 -c 'import markdown' 2>/dev/null; then
    /usr/bin/python3 "$tmp/report/make_html.py" "$tmp/report" "$dest" >/dev/null && cp "$tmp/report/report.html" "$dest/"
  fi
  rm -rf "$tmp"
  echo "report of $dest written anew from its $(ls "$dest/runs" | wc -l) committed runs"
  exit 0
fi
[ $# -eq 2 ] || { echo "usage: $0 SWEEP_DIR DEST | $0 --report-only DEST" >&2; exit 2; }
src=$1 dest=$2
[ -f "$src/sweep.json" ] || { echo "$0: $src is not a sweep directory (no sweep.json)" >&2; exit 2; }
tmp="$dest.publishing"
rm -rf "$tmp"
mkdir -p "$tmp/runs"
"$msbench" report "$src" --out "$tmp/report"
for f in report.md table.csv findings.csv table1.png gallery.png ablation_levels.csv; do [ -f "$tmp/report/$f" ] && mv "$tmp/report/$f" "$tmp/"; done
for f in "$tmp"/report/coverage_*.png "$tmp"/report/ablation_levels_*.png; do [ -f "$f" ] && mv "$f" "$tmp/"; done
# The gallery (every run's top-down picture) as a 256-colour PNG: a third of the size, same look
# (Pillow comes with python3-matplotlib; without it the gallery stays as written).
if [ -f "$tmp/gallery.png" ] && /usr/bin/python3 -c 'import PIL' 2>/dev/null; then
  /usr/bin/python3 -c 'import sys; from PIL import Image; Image.open(sys.argv[1]).convert("RGB").quantize(256).save(sys.argv[1], optimize=True)' "$tmp/gallery.png"
fi
mv "$tmp/report/make_html.py" "$tmp/report/report_runs.csv" "$tmp/"
rm -rf "$tmp/report"
cp "$src/sweep.json" "$src/runs.csv" "$tmp/"
for run in "$src"/runs/*/; do
  case "$run" in *.partial/) continue ;; esac
  id=$(basename "$run")
  mkdir -p "$tmp/runs/$id"
  for f in metrics.json coverage.csv config.yaml; do [ -f "$run/$f" ] && cp "$run/$f" "$tmp/runs/$id/"; done
done
# Paths of the machine it ran on: the sweep directory becomes DEST, scenario files repository-relative.
find "$tmp" \( -name report.md -o -name sweep.json -o -name config.yaml \) -exec \
  sed -i -e "s|$src|$dest|g" -e 's|/[^ "]*/scenarios/|scenarios/|g' {} +
# report.html from the published files (the runs' records under DEST; links relative to DEST).
sed -i "s|,$src/runs/|,$tmp/runs/|" "$tmp/report_runs.csv"
if /usr/bin/python3 -c 'import markdown' 2>/dev/null; then
  /usr/bin/python3 "$tmp/make_html.py" "$tmp" "$dest" >/dev/null
else
  echo "$0: python3-markdown not found: no report.html (apt-get install python3-markdown)" >&2
fi
rm -f "$tmp/make_html.py" "$tmp/report_runs.csv"
rm -rf "$dest"
mv "$tmp" "$dest"
echo "published $(ls "$dest/runs" | wc -l) runs of $src -> $dest ($(du -sh "$dest" | cut -f1))"
