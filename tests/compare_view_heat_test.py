#!/usr/bin/env python3
"""compare_view_heat_test: a still compare-view window shows its heat maps
when the worker has them, with no input to wake it.

    compare_view_heat_test.py TARN SOURCE_DIR     (run under an X server: Xvfb)

Opens `tarn compare-view` on the lake (basic twice, a small window and a
coarse reference), presses H once, then touches nothing: the window must
pick up the reference and then the maps (the log's "heat map ... RMSE"
line for each pack) within the time the work takes. A window that slept
through the job's end showed them only at the next key or mouse move.
Exits 77 when libX11 or libXtst is missing.
"""
import os
import re
import subprocess
import sys
import time

sys.dont_write_bytecode = True   # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from x_keys import Keyboard  # noqa: E402

MAX_WAIT_S = 90     # a 320x180 reference at 32 cells, 4 photons: a few seconds on 2 cores


def log_text():
    with open("compare-view-heat.log") as f:
        return f.read()


def maps_reported():
    return len(re.findall(r"heat map .*: water RMSE", log_text()))


def main(argv):
    kb = Keyboard("compare_view_heat_test")
    tarn, src = argv[1], argv[2]
    log = open("compare-view-heat.log", "w")
    p = subprocess.Popen([tarn, "compare-view", os.path.join(src, "scenes/lake.glib"), "--packs", "basic,basic",
                          "--size", "320x180", "--time", "1", "--ref-caustic-res", "32", "--ref-photons", "4"],
                         stdout=log, stderr=log)
    for _ in range(1200):              # both packs loaded (the second off the first frame)
        if "(2 packs)" in log_text() or p.poll() is not None:
            break
        time.sleep(0.1)
    if p.poll() is not None:
        sys.exit("FAIL: tarn compare-view exited early (%s); see compare-view-heat.log" % p.returncode)
    kb.move(700, 100)   # over the views, right of the panel
    time.sleep(2.0)     # the picture settles: the window sleeps
    kb.press("h")
    t0 = time.time()
    while time.time() - t0 < MAX_WAIT_S and maps_reported() < 2:
        time.sleep(0.2)
    n = maps_reported()
    print("heat maps reported after %.1f s with no input: %d of 2" % (time.time() - t0, n))
    kb.press("q")
    try:
        p.wait(timeout=10)
    except subprocess.TimeoutExpired:
        p.kill()
    if n < 2:
        sys.exit("FAIL: the still window did not show the heat maps until input woke it")
    sys.exit(0)


if __name__ == "__main__":
    main(sys.argv)
