"""A Python method's run with --video (docs/video.md): the video is written into the output with
the documented frames, the run's hash is the one without a video, and no temporary is left."""
import glob
import json
import os
import shutil
import subprocess

import pytest

from conftest import MSBENCH_BIN, SOURCE_DIR

SCENARIO = os.path.join(SOURCE_DIR, "examples/hover_turn_python.yaml")


def probe(video):
    """(frames, width, height) as ffprobe decodes them."""
    out = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                          "stream=nb_read_frames,width,height", "-of", "csv=p=0", video],
                         capture_output=True, text=True, check=True).stdout.strip().rstrip(",")
    w, h, n = out.split(",")
    return int(n), int(w), int(h)


@pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="ffmpeg is not installed (apt-get install ffmpeg)")
def test_a_python_methods_run_has_its_video_and_keeps_its_hash(tmp_path):
    temporaries = set(glob.glob("/tmp/msbench_video.*"))
    runs = {}
    for name, extra in (("video", ["--video", "--set", "video.height=360"]), ("plain", [])):
        r = subprocess.run([MSBENCH_BIN, "run", SCENARIO, "--duration", "10", "--quiet", "--out",
                            str(tmp_path / name)] + extra, capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        with open(tmp_path / name / "metrics.json") as f:
            runs[name] = json.load(f)
    assert runs["video"]["determinism_hash"] == runs["plain"]["determinism_hash"]
    assert "video" not in runs["plain"]
    video = runs["video"]["video"]
    # One frame a simulated second for 10 s, then the end held 2 s at 10 fps.
    assert video["file"] == "video.mp4" and video["frames"] == 30 and video["height"] == 360
    assert probe(str(tmp_path / "video" / "video.mp4")) == (30, video["width"], 360)
    assert set(glob.glob("/tmp/msbench_video.*")) == temporaries
