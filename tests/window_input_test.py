#!/usr/bin/env python3
"""window_input_test: at 2 fps a press that starts over the panel never
reaches the camera (issue #30: moving onto a slider and pressing within a
frame dragged the slider and orbited the camera too, and the recorded
session kept the camera move).

    window_input_test.py TARN SOURCE_DIR     (run under an X server: Xvfb)

Runs `tarn view` on the lake with a script that makes every frame last
500 ms (`slow 500`: what a slow GPU gives) and records a session. Between
two frames the pointer arrives over the panel and presses; it drags across
into the scene over the next frames and lets go: the session must hold no
camera event. The same
drag pressed in the scene must orbit (a camera event), so the check can
fail. Exits 77 when libX11 or libXtst is missing.
"""
import os
import subprocess
import sys
import time

sys.dont_write_bytecode = True   # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from x_keys import Keyboard  # noqa: E402

# a window under 590 px wide: the panel floats over the scene's left (wider,
# it stands beside the scene and a press left of its edge is its own)
SIZE = "560x315"


def wait_for(path, text, seconds):
    deadline = time.time() + seconds
    while time.time() < deadline:
        with open(path) as f:
            if text in f.read():
                return True
        time.sleep(0.1)
    return False


PANEL = (150, 115)    # the panel's "Frame budget" slider
SCENE = (470, 250)    # the lake, right of the panel


def drag(kb, x0, x1, y):
    """Arrive at x0 and press within one 500 ms frame (20 ms apart), then
    cross to x1 over three frames and let go."""
    kb.move(x0, y)
    time.sleep(0.02)
    kb.button(1, True)
    for k in range(1, 16):
        kb.move(x0 + (x1 - x0) * k // 15, y)
        time.sleep(0.1)
    kb.button(1, False)


def run(kb, tarn, src, name, start):
    """The session's camera events after a drag from start, 80 px right."""
    with open(name + ".script", "w") as f:
        f.write("frames 2\nslow 500\nclock\nwait 4\nquit\n")
    log = open(name + ".log", "w")
    p = subprocess.Popen([tarn, "view", os.path.join(src, "scenes/lake.glib"), "--pack", "basic",
                          "--size", SIZE, "--script", name + ".script", "--record", name + ".session"],
                         stdout=log, stderr=log)
    if not wait_for(name + ".log", " clock ", 60):
        p.kill()
        sys.exit("FAIL: %s: the window did not start; see %s.log" % (name, name))
    time.sleep(0.7)      # into the slow frames
    drag(kb, start[0], start[0] + 80, start[1])
    try:
        p.wait(timeout=30)
    except subprocess.TimeoutExpired:
        p.kill()
        sys.exit("FAIL: %s: tarn view did not quit" % name)
    if p.returncode != 0:
        sys.exit("FAIL: %s: tarn view exited %d; see %s.log" % (name, p.returncode, name))
    with open(name + ".session") as f:   # "t=1.250 camera ...", the first the start's
        events = [line.split()[1] for line in f if line.startswith("t=")]
    cams = sum(1 for e in events if e == "camera") - 1
    print("%s: drag from (%d, %d): %d camera event(s) after the start's" % (name, start[0], start[1], cams))
    return cams


def main(argv):
    kb = Keyboard("window_input_test")
    tarn, src = argv[1], argv[2]
    on_panel = run(kb, tarn, src, "panel", PANEL)
    on_scene = run(kb, tarn, src, "scene", SCENE)
    ok = True
    if on_panel:
        print("FAIL: a press that started over the panel moved the camera")
        ok = False
    if not on_scene:
        print("FAIL: a drag in the scene did not orbit: the test cannot see a camera move")
        ok = False
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main(sys.argv)
