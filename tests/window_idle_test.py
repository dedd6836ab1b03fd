#!/usr/bin/env python3
"""window_idle_test: a still window sleeps and quits at once (issue #30).

    window_idle_test.py TARN SOURCE_DIR     (run under an X server: Xvfb)

Opens `tarn view` on the lake (basic pack, a small window), pauses time with
Space, waits for the full-resolution frame, then measures the process's CPU
time over a few seconds from /proc: a still window must use at most 5% of a
core (it drew the same frame over and over: 75%). Then R (reload) must
still be answered, and Q must end the process within a second.
Exits 77 when libX11 or libXtst is missing.
"""
import os
import subprocess
import sys
import time

sys.dont_write_bytecode = True   # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from x_keys import Keyboard  # noqa: E402

MAX_IDLE_SHARE = 0.05   # of one core, while nothing changes
MAX_QUIT_S = 1.0


def cpu_s(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main(argv):
    kb = Keyboard("window_idle_test")
    press = kb.press

    tarn, src = argv[1], argv[2]
    log = open("window-idle.log", "w")
    p = subprocess.Popen([tarn, "view", os.path.join(src, "scenes/lake.glib"), "--pack", "basic",
                          "--size", "320x180", "--verbose"], stdout=log, stderr=log)
    time.sleep(6)                       # start-up: the programs compile
    # and the compile job loads the scene off the frame once the window is
    # up (a one-off at start-up, not the still window's cost): wait for it
    for _ in range(600):
        if "compile job has the scene loaded" in open("window-idle.log").read() or p.poll() is not None:
            break
        time.sleep(0.1)
    if p.poll() is not None:
        sys.exit("FAIL: tarn view exited early (%s); see window-idle.log" % p.returncode)
    kb.move(600, 100)   # over the scene, right of the panel
    press("space")                      # pause: the picture stops changing
    time.sleep(2.0)                     # the budget's settle, the full frame
    c0, w0 = cpu_s(p.pid), time.time()
    time.sleep(4.0)
    share = (cpu_s(p.pid) - c0) / (time.time() - w0)
    print("still window: %.1f%% of a core" % (100 * share))
    ok = share <= MAX_IDLE_SHARE
    if not ok:
        print("FAIL: a still window should sleep (at most %.0f%% of a core)" % (100 * MAX_IDLE_SHARE))
    c0 = cpu_s(p.pid)
    press("r")                          # a key wakes it: the reload runs
    time.sleep(2.0)
    woke = cpu_s(p.pid) - c0
    print("after R: %.2f s of CPU" % woke)
    if woke < 0.02:
        print("FAIL: R did not wake the window")
        ok = False
    q0 = time.time()
    press("q")
    try:
        p.wait(timeout=10)
    except subprocess.TimeoutExpired:
        p.kill()
        sys.exit("FAIL: Q did not end tarn view in 10 s")
    quit_s = time.time() - q0
    print("quit took %.2f s" % quit_s)
    if quit_s > MAX_QUIT_S:
        print("FAIL: quitting should be immediate (at most %.1f s)" % MAX_QUIT_S)
        ok = False
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main(sys.argv)
