#!/usr/bin/env python3
"""window_idle_test: a still window sleeps and quits at once (issue #30).

    window_idle_test.py TARN SOURCE_DIR     (run under an X server: Xvfb)

Opens `tarn view` on the lake (basic pack, a small window), pauses time with
Space, waits for the full-resolution frame, then measures the process's CPU
time over a few seconds from /proc: a still window must use at most 5% of a
core (it drew the same frame over and over: 75%), and so while a toast
shows (P's "saved" toast: it drew the toast's frame for 4 s). Then R (reload) must
still be answered (its "reloaded" line in the log), and Q must end the
process within a second. Then two
glman scenes with the clock left running: one that reads it (Timer) must
keep moving, one that does not must sleep the same way. And a still window
whose shaders' folder is renamed away must sleep too, and reload once it
is back.
Exits 77 when libX11 or libXtst is missing.
"""
import os
import shutil
import subprocess
import sys
import tempfile
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
    wait_for_job(p, "window-idle.log")
    if p.poll() is not None:
        sys.exit("FAIL: tarn view exited early (%s); see window-idle.log" % p.returncode)
    kb.move(600, 100)   # over the scene, right of the panel
    press("space")                      # pause: the picture stops changing
    time.sleep(2.0)                     # the budget's settle, the full frame
    share = share_over(p.pid, 4.0)
    print("still window: %.1f%% of a core" % (100 * share))
    ok = share <= MAX_IDLE_SHARE
    if not ok:
        print("FAIL: a still window should sleep (at most %.0f%% of a core)" % (100 * MAX_IDLE_SHARE))
    ok = still_under_toast(p, press) and ok
    c0 = cpu_s(p.pid)
    reloads = reload_count("window-idle.log")
    press("r")                          # a key wakes it: the reload runs
    answered = wait_for_reload("window-idle.log", reloads, 10.0)
    print("after R: %.2f s of CPU, %s" % (cpu_s(p.pid) - c0, "reloaded" if answered else "no reload"))
    if not answered:
        # the reload's own line, not a CPU figure: a reload of unchanged
        # files at 320x180 takes one or two of /proc's 10 ms ticks
        print("FAIL: R did not wake the window (no 'reloaded' line in window-idle.log in 10 s)")
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
    ok = clock_running_scenes(tarn, kb) and ok
    ok = missing_folder(tarn) and ok
    sys.exit(0 if ok else 1)


def still_under_toast(p, press):
    """A toast stands still: P (a screenshot, then its "saved" toast for
    APP_TOAST_S = 4 s) must leave the window asleep while the toast shows
    (it drew the same frame for the toast's 4 s: a core). The screenshot
    goes to the current folder; it is removed."""
    before = set(f for f in os.listdir(".") if f.startswith("tarn-") and f.endswith(".png"))
    press("p")
    time.sleep(0.8)                     # the shot's full frame, the toast's first frame
    share = share_over(p.pid, 2.5)      # still within the toast's 4 s
    print("still window under a toast: %.1f%% of a core" % (100 * share))
    for f in os.listdir("."):
        if f.startswith("tarn-") and f.endswith(".png") and f not in before:
            os.remove(f)
    if share > MAX_IDLE_SHARE:
        print("FAIL: a still window showing a toast should sleep (at most %.0f%% of a core)" % (100 * MAX_IDLE_SHARE))
        return False
    return True


def wait_for_job(p, log_path):
    """The compile job loads the scene off the frame once the window is up
    (start-up's one-off work, seconds under a sanitizer on a busy machine,
    not the window's steady state): waits for its log line, a minute at
    most, or for the process's end."""
    for _ in range(600):
        if "compile job has the scene loaded" in open(log_path).read() or p.poll() is not None:
            return
        time.sleep(0.1)


def reload_count(log_path):
    """How many reloads the window has logged."""
    return open(log_path).read().count(": reloaded ")


def wait_for_reload(log_path, before, seconds):
    """True once the log holds more reloads than before, within seconds."""
    end = time.time() + seconds
    while time.time() < end:
        if reload_count(log_path) > before:
            return True
        time.sleep(0.05)
    return False


def share_over(pid, seconds):
    """The share of a core process pid uses over the next seconds."""
    c0, w0 = cpu_s(pid), time.time()
    time.sleep(seconds)
    return (cpu_s(pid) - c0) / (time.time() - w0)


def open_scene(tarn, d, name, frag):
    """tarn view of a one-quad glman scene in d whose fragment shader is
    frag, in a 960x540 scene area, once its start-up is over; the process."""
    with open(os.path.join(d, "quad.vert"), "w") as f:
        f.write("#version 330 compatibility\n"
                "void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; }\n")
    with open(os.path.join(d, name + ".frag"), "w") as f:
        f.write("#version 330 compatibility\nuniform float Timer;\nout vec4 c;\n"
                "void main() { c = %s; }\n" % frag)
    with open(os.path.join(d, name + ".glib"), "w") as f:
        f.write("##OpenGL GLIB\nOrtho -1 1 -1 1\nVertex quad.vert\nFragment %s.frag\n"
                "Program Quad\nQuadXY 0 1 1 1\n" % name)
    path = "window-idle-%s.log" % name
    log = open(path, "w")
    p = subprocess.Popen([tarn, "view", os.path.join(d, name + ".glib"), "--size", "960x540", "--verbose"],
                         stdout=log, stderr=log)
    wait_for_job(p, path)
    time.sleep(2.0)                     # the budget's settle and the full-size frame
    return p


def clock_running_scenes(tarn, kb):
    """The clock left running (the window's default) on two glman scenes.
    One reads it (red = Timer, a 10 s sawtooth): the window must go on
    drawing it; it froze once the picture was drawn at full size, as the
    window slept and the clock advances with the frames. One never reads
    it (Timer declared, unused): its picture does not change, so the window
    draws it once at full size and sleeps as a paused one does."""
    d = tempfile.mkdtemp(prefix="tarn-clock-")
    ok = True
    p = open_scene(tarn, d, "moving", "vec4(Timer, 0.5, 0.8, 1.0)")
    # the window is at the screen's corner (no window manager): its scene
    # area ends at x = 960, right of the panel
    r0 = kb.pixel(900, 100)
    time.sleep(1.5)
    r1 = kb.pixel(900, 100)
    p.terminate()
    p.wait(timeout=10)
    print("animated scene, clock running: red %s -> %s in 1.5 s" % (r0 and r0[0], r1 and r1[0]))
    # 1.5 s of a 10 s sawtooth is 38 levels (less where it wraps: then more than 200)
    if not r0 or not r1 or abs(r1[0] - r0[0]) < 10 or r0[1:] != (128, 204):
        print("FAIL: a scene that reads the clock must keep moving while it runs (window-idle-moving.log)")
        ok = False
    p = open_scene(tarn, d, "still", "vec4(0.2, 0.5, 0.8, 1.0)")
    if p.poll() is not None:
        print("FAIL: tarn view of a still scene exited early (%s); see window-idle-still.log" % p.returncode)
        return False
    # the compile job goes on drawing the scene for the shader cache after
    # it has loaded it (seconds under a sanitizer): the window must fall
    # asleep within half a minute of that, then stay asleep
    settle_s = share_over(p.pid, 2.0)
    for _ in range(15):
        if settle_s <= MAX_IDLE_SHARE:
            break
        settle_s = share_over(p.pid, 2.0)
    share = share_over(p.pid, 4.0)
    p.terminate()
    p.wait(timeout=10)
    shutil.rmtree(d, ignore_errors=True)
    print("still scene, clock running: %.1f%% of a core" % (100 * share))
    if share > MAX_IDLE_SHARE:
        print("FAIL: a scene that reads no clock should sleep while the clock runs (at most %.0f%% of a core)"
              % (100 * MAX_IDLE_SHARE))
        ok = False
    return ok


def missing_folder(tarn):
    """A still window whose shaders' folder is renamed away keeps the last
    good picture and looks for the folder again every APP_RETRY_S: it must
    sleep meanwhile (it spun 121% of a core), and reload once the folder
    is back."""
    d = tempfile.mkdtemp(prefix="tarn-missing-")
    sh = os.path.join(d, "sh")
    os.mkdir(sh)
    with open(os.path.join(sh, "quad.vert"), "w") as f:
        f.write("#version 330 compatibility\nvoid main() { gl_Position = gl_Vertex; }\n")
    with open(os.path.join(sh, "quad.frag"), "w") as f:
        f.write("#version 330 compatibility\nout vec4 c;\nvoid main() { c = vec4(0.2, 0.5, 0.8, 1.0); }\n")
    with open(os.path.join(d, "scene.glib"), "w") as f:
        f.write("##OpenGL GLIB\nVertex sh/quad.vert\nFragment sh/quad.frag\nProgram Quad\nQuadXY\n")
    path = "window-idle-missing.log"
    log = open(path, "w")
    p = subprocess.Popen([tarn, "view", os.path.join(d, "scene.glib"), "--size", "320x180", "--verbose"],
                         stdout=log, stderr=log)
    wait_for_job(p, path)
    time.sleep(2.0)
    ok = True
    os.rename(sh, sh + "_moved")
    time.sleep(1.5)                     # the reload's errors, the last good picture kept
    share = share_over(p.pid, 3.0)
    print("still window, its shaders' folder missing: %.1f%% of a core" % (100 * share))
    if share > MAX_IDLE_SHARE:
        print("FAIL: a still window should sleep while a folder is missing (at most %.0f%% of a core)"
              % (100 * MAX_IDLE_SHARE))
        ok = False
    os.rename(sh + "_moved", sh)
    end = time.time() + 10
    while time.time() < end and "a missing folder appeared" not in open(path).read():
        time.sleep(0.1)
    if "a missing folder appeared" not in open(path).read():
        print("FAIL: the folder came back and the window did not reload (%s)" % path)
        ok = False
    p.terminate()
    p.wait(timeout=10)
    shutil.rmtree(d, ignore_errors=True)
    return ok


if __name__ == "__main__":
    main(sys.argv)
