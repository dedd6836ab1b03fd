#!/usr/bin/env python3
"""x_keys: presses keys in the X display's window under the pointer (XTEST,
through ctypes: no xdotool on the test machines), for the window tests.

    x_keys.py FILE_GLOB KEY QUIT_KEY [SECONDS]
moves the pointer to (100, 100), presses KEY every SECONDS (default half a
second) until a file matches the glob (10 s at most), then presses QUIT_KEY
once. A key that toggles wants SECONDS long enough for a slow window to
have answered the first press.
Keys are X keysym names ("p", "q", "space"), a modifier first if any
("shift+r", "ctrl+s"). Exits 77 when libX11 or libXtst is missing, 1 when
no file appeared.
"""
import ctypes
import glob
import sys
import time


class Keyboard:
    """The X display's fake keyboard and pointer (XTEST); exits 77 when
    libX11 or libXtst is missing. Also used by window_idle_test.py."""

    MODIFIERS = {"shift": "Shift_L", "ctrl": "Control_L", "alt": "Alt_L"}

    def __init__(self, who="x_keys"):
        try:
            self.x, self.t = ctypes.CDLL("libX11.so.6"), ctypes.CDLL("libXtst.so.6")
        except OSError as e:
            print("skip: %s" % e)
            sys.exit(77)
        x = self.x
        x.XOpenDisplay.restype = ctypes.c_void_p
        x.XStringToKeysym.restype = ctypes.c_ulong
        x.XStringToKeysym.argtypes = [ctypes.c_char_p]
        x.XKeysymToKeycode.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
        self.d = ctypes.c_void_p(x.XOpenDisplay(None))
        if not self.d.value:
            sys.exit("%s: no display" % who)

    def keycode(self, name):
        return self.x.XKeysymToKeycode(self.d, self.x.XStringToKeysym(name.encode()))

    def press(self, spec):
        """A key ("p", "space"), a modifier first if any ("shift+r")."""
        x, t, d = self.x, self.t, self.d
        *mods, key = spec.split("+")
        held = [self.keycode(self.MODIFIERS[m]) for m in mods]
        for kc in held:
            t.XTestFakeKeyEvent(d, kc, 1, 0)
        for down in (1, 0):
            t.XTestFakeKeyEvent(d, self.keycode(key), down, 0)
            x.XFlush(d)
            time.sleep(0.05)
        for kc in reversed(held):
            t.XTestFakeKeyEvent(d, kc, 0, 0)
        x.XFlush(d)

    def move(self, px, py):
        self.t.XTestFakeMotionEvent(self.d, -1, px, py, 0)
        self.x.XFlush(self.d)

    def button(self, n, down):
        """Mouse button n (1 left) pressed (down True) or released."""
        self.t.XTestFakeButtonEvent(self.d, n, 1 if down else 0, 0)
        self.x.XFlush(self.d)

    def pixel(self, px, py):
        """The screen's pixel at (px, py) as (r, g, b), 0-255 (what a
        window there shows: Xvfb has no compositor)."""
        x = self.x
        x.XDefaultRootWindow.restype = ctypes.c_ulong
        x.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
        x.XGetImage.restype = ctypes.c_void_p
        x.XGetImage.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int, ctypes.c_uint,
                                ctypes.c_uint, ctypes.c_ulong, ctypes.c_int]
        x.XGetPixel.restype = ctypes.c_ulong
        x.XGetPixel.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int]
        x.XDestroyImage.argtypes = [ctypes.c_void_p]
        img = x.XGetImage(self.d, x.XDefaultRootWindow(self.d), px, py, 1, 1, 0xFFFFFFFF, 2)   # ZPixmap
        if not img:
            return None
        v = x.XGetPixel(img, 0, 0)
        x.XDestroyImage(img)
        return (v >> 16) & 255, (v >> 8) & 255, v & 255


def main(argv):
    kb = Keyboard()
    press = kb.press
    kb.move(100, 100)   # the window is at the top left: keys go under the pointer
    deadline = time.time() + 10
    interval = float(argv[4]) if len(argv) > 4 else 0.5
    while not glob.glob(argv[1]) and time.time() < deadline:
        press(argv[2])
        until = time.time() + interval
        while not glob.glob(argv[1]) and time.time() < until:
            time.sleep(0.05)
    found = bool(glob.glob(argv[1]))
    press(argv[3])
    sys.exit(0 if found else 1)


if __name__ == "__main__":
    main(sys.argv)
