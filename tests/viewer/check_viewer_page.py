#!/usr/bin/env python3
"""The viewer page in a real browser: headless Chromium on the pages of the shipped drop and of a
short run of the 1000-sphere pile.

    check_viewer_page.py SUPERDEX SOURCE_DIR WORK_DIR

For each page: it loads with no error (the page's own error list, filled by window.onerror,
unhandled rejections and console.error, and no "Uncaught" line in Chromium's log) and says it is
ready. Drop: screenshots at two times with a camera given in the URL; at each, the pixel where the
ball's centre from the trajectory projects has the ball's colour, the ball moved between the two,
the energy plot's lines are drawn and its cursor stands at the shot's time; a third shot during
the first impact shows the contact samples under the ball (its view, cropped, is WORK_DIR/viewer.png:
docs/viewer.png). Pile: drawn in a few instanced draws,
the highest sphere where the trajectory puts it.

Standard library only. Exit status 0 when every check passes, 1 otherwise, 77 (skipped) when no
Chromium is installed (`.ci/install-deps` installs Debian's `chromium`).
"""
import colorsys
import html
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import time
import zlib

SKIPPED = 77
SIZE = (1000, 600)  # the page's fixed view (#size=...) [CSS px]; the window is taller
DROP_CAMERA = ((1.6, -2.4, 1.0), (0.0, 0.0, 0.55))
PILE_CAMERA = ((0.0, -0.4, 4.0), (0.0, 0.0, 0.3))  # from above: the highest sphere is visible
FOV = 40.0

failures = []


def check(condition, message):
    print(("ok    " if condition else "FAIL  ") + message)
    if not condition:
        failures.append(message)
    return condition


def find_chromium():
    for name in (os.environ.get("CHROMIUM"), "chromium", "chromium-browser", "google-chrome"):
        if name and shutil.which(name):
            return shutil.which(name)
    return None


def run(cmd, timeout):
    start = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if r.returncode != 0:
        sys.exit("command failed (exit %d): %s\n%s%s" % (r.returncode, " ".join(cmd), r.stdout,
                                                          r.stderr))
    return r, time.monotonic() - start


# --- PNG (8-bit RGB or RGBA, not interlaced: what Chromium writes).
def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path + ": not a PNG"
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
            assert depth == 8 and color in (2, 6) and interlace == 0, path + ": unsupported PNG"
            channels = 4 if color == 6 else 3
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        previous = line
    return rows


def write_png(path, rows):
    """An 8-bit RGB PNG of rows of (r, g, b)."""
    raw = b"".join(b"\x00" + bytes(c for pixel in row for c in pixel) for row in rows)

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" +
                chunk(b"IHDR", struct.pack(">IIBBBBB", len(rows[0]), len(rows), 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def hex_rgb(text):
    return tuple(int(text[k:k + 2], 16) for k in (1, 3, 5))


def hue_sat(rgb):
    h, _, s = colorsys.rgb_to_hls(*(c / 255.0 for c in rgb))
    return 360.0 * h, s


def same_hue(rgb, reference, tolerance=20.0):
    h, s = hue_sat(rgb)
    href, _ = hue_sat(reference)
    return s > 0.3 and min(abs(h - href), 360 - abs(h - href)) < tolerance


# --- The page's camera: three.js's PerspectiveCamera looking from eye at target, up +z.
def project(eye, target, point, width, height, fov=FOV):
    def sub(a, b):
        return [a[k] - b[k] for k in range(3)]

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def unit(a):
        n = math.sqrt(sum(c * c for c in a))
        return [c / n for c in a]

    def dot(a, b):
        return sum(a[k] * b[k] for k in range(3))

    z = unit(sub(eye, target))
    x = unit(cross([0, 0, 1], z))
    y = cross(z, x)
    d = sub(point, eye)
    depth = -dot(d, z)
    f = 1.0 / math.tan(math.radians(fov) / 2)
    ndc_x = f * dot(d, x) / depth / (width / height)
    ndc_y = f * dot(d, y) / depth
    return (ndc_x + 1) / 2 * width, (1 - ndc_y) / 2 * height


def read_trajectory(path):
    with open(path) as f:
        lines = [json.loads(line) for line in f if line.strip()]
    return lines[0], lines[1:]


def shoot(chromium, page, fragment, png, work):
    """Loads page#fragment: the page's status and errors, and a screenshot."""
    cmd = [chromium, "--headless", "--no-sandbox", "--use-angle=swiftshader",
           "--enable-unsafe-swiftshader", "--hide-scrollbars", "--force-device-scale-factor=1",
           "--window-size=%d,%d" % (SIZE[0], SIZE[1] + 150), "--virtual-time-budget=15000",
           "--enable-logging=stderr", "--v=0", "--user-data-dir=" + os.path.join(work, "profile"),
           "--screenshot=" + png, "--dump-dom", "file://" + os.path.abspath(page) + "#" + fragment]
    r, seconds = run(cmd, timeout=120)
    found = {}
    for name in ("status", "errors"):
        m = re.search(r'<pre id="viewer-%s"[^>]*>(.*?)</pre>' % name, r.stdout, re.S)
        found[name] = json.loads(html.unescape(m.group(1))) if m else None
    uncaught = [line for line in r.stderr.splitlines() if "Uncaught" in line]
    print("      %s#%s: %.1f s" % (os.path.basename(page), fragment, seconds))
    return found["status"], (found["errors"] or []) + uncaught, read_png(png)


def check_loaded(name, status, errors):
    check(status is not None and status.get("ready") is True,
          "%s: the page is ready (status %s)" % (name, json.dumps(status)[:300]))
    check(not errors, "%s: no errors (%s)" % (name, errors))
    return bool(status and status.get("ready"))


def check_plot(name, status, image, t, t_end):
    """The energy lines in the plot area, and the cursor's column at time t."""
    p = status["plot"]
    left, top, w, h = (int(round(p[k])) for k in ("left", "top", "width", "height"))
    area = [image[y][x] for y in range(top + 2, top + h - 2) for x in range(left + 2, left + w - 2)]
    total = sum(1 for c in area if max(c) < 70)
    kinetic = sum(1 for c in area if same_hue(c, hex_rgb(p["colors"]["kinetic"]), 12))
    check(total > w // 2, "%s: the total energy's line is drawn (%d dark pixels)" % (name, total))
    check(kinetic > w // 4, "%s: the kinetic energy's line is drawn (%d pixels)" % (name, kinetic))
    cursor = hex_rgb(p["cursor"])
    columns = [sum(1 for y in range(top, top + h)
                   if sum(abs(a - b) for a, b in zip(image[y][x], cursor)) < 60)
               for x in range(left, left + w + 1)]
    expected = left + t / t_end * w
    at = max(range(len(columns)), key=lambda k: columns[k]) + left
    check(columns[at - left] > h // 2 and abs(at - expected) <= 2,
          "%s: the plot's cursor stands at t = %g s (column %d, expected %.1f)" % (name, t, at,
                                                                                 expected))


def ball_at(header, frames, name, t):
    index = [a["name"] for a in header["actors"]].index(name)
    frame = min(frames, key=lambda f: abs(f["t"] - t))
    return frame["actors"][index]["p"], frame


def drop_checks(chromium, superdex, source, work):
    traj = os.path.join(work, "drop.jsonl")
    r, seconds = run([superdex, "run", os.path.join(source, "scenes/data/drop.json"), "--quiet",
                      "--view", "--out", traj], timeout=300)
    page = os.path.join(work, "drop.html")
    check(re.search(r"viewer page +%s\b" % re.escape(page), r.stdout) is not None,
          "drop: `superdex run --view` names the page (%s)" % page)
    check(os.path.exists(page), "drop: the page exists (%.1f s run)" % seconds)
    again = os.path.join(work, "drop_view.html")
    run([superdex, "view", traj, "--out", again], timeout=60)
    check(open(page, "rb").read() == open(again, "rb").read(),
          "drop: `superdex view` writes the same page as `run --view`")
    header, frames = read_trajectory(traj)
    eye, target = DROP_CAMERA
    camera = "camera=%g,%g,%g,%g,%g,%g&fov=%g&size=%dx%d" % (*eye, *target, FOV, *SIZE)
    centres = []
    for t in (0.2, 0.4):
        p, frame = ball_at(header, frames, "ball", t)
        status, errors, image = shoot(chromium, page, "t=%r&%s" % (frame["t"], camera),
                                      os.path.join(work, "drop_t%g.png" % t), work)
        if not check_loaded("drop t=%g" % t, status, errors):
            return
        x, y = project(eye, target, p, *SIZE)
        pixel = image[int(y)][int(x)]
        check(same_hue(pixel, hex_rgb(status["colors"]["ball"])),
              "drop t=%g: the ball (z = %.3f m) is at pixel (%d, %d): %s" % (t, p[2], x, y, pixel))
        centres.append((x, y, image))
        check_plot("drop t=%g" % t, status, image, frame["t"], frames[-1]["t"])
    (xa, ya, _), (xb, yb, image_b) = centres
    check(math.hypot(xb - xa, yb - ya) > 30 and
          not same_hue(image_b[int(ya)][int(xa)], hex_rgb(status["colors"]["ball"])),
          "drop: the ball moved on screen (%.0f px) and left its first place" % math.hypot(
              xb - xa, yb - ya))
    contact_checks(chromium, page, header, frames, work)


def contact_checks(chromium, page, header, frames, work):
    """During the first impact: the contact samples' traction colours under the ball."""
    touching = [f for f in frames if f.get("contacts", {}).get("count", 0) > 0]
    if not check(bool(touching), "drop: the trajectory has contact samples"):
        return
    frame = touching[len(touching) // 2] if len(touching) < 3 else touching[1]
    n = frame["contacts"]["count"]
    centre = [sum(frame["contacts"]["p"][3 * s + k] for s in range(n)) / n for k in range(3)]
    eye, target = (0.45, -0.8, 0.35), (0.0, 0.0, 0.1)
    fragment = "t=%r&camera=%g,%g,%g,%g,%g,%g&fov=%g&size=%dx%d&contacts=1&forces=1" % (
        frame["t"], *eye, *target, FOV, *SIZE)
    png = os.path.join(work, "drop_contact.png")
    status, errors, image = shoot(chromium, page, fragment, png, work)
    if not check_loaded("drop contact", status, errors):
        return
    x, y = project(eye, target, centre, *SIZE)
    box = [image[j][i] for j in range(int(y) - 15, int(y) + 16) for i in range(int(x) - 30, int(x) + 31)]
    coloured = sum(1 for c in box if hue_sat(c)[1] > 0.5 and 60 < hue_sat(c)[0] < 250)
    check(coloured > 20, "drop t=%g: %d contact samples drawn in traction colours around pixel "
                         "(%d, %d): %d pixels" % (frame["t"], n, x, y, coloured))
    # The page's view alone (the window is taller): docs/viewer.png is this file.
    write_png(os.path.join(work, "viewer.png"), [row[:SIZE[0]] for row in image[:SIZE[1]]])


def pile_checks(chromium, superdex, source, work):
    traj = os.path.join(work, "pile.jsonl")
    r, seconds = run([superdex, "run", os.path.join(source, "scenes/data/pile.json"), "--quiet",
                      "--view", "--contacts", "--duration", "0.2", "--out", traj], timeout=600)
    page = os.path.join(work, "pile.html")
    print("      pile: 0.2 s run %.1f s; page %.2f MB" % (seconds, os.path.getsize(page) / 1e6))
    header, frames = read_trajectory(traj)
    status, errors, _ = shoot(chromium, page, "t=0.2&size=%dx%d&contacts=1&forces=1" % SIZE,
                              os.path.join(work, "pile_contacts.png"), work)
    if not check_loaded("pile (contacts shown)", status, errors):
        return
    print("      pile: first frame after %.0f ms (virtual time)" % status["timings"]["firstFrame"])
    check(status["instancedGroups"] == 4 and status["drawCalls"] <= 12,
          "pile: 1005 actors in %d instanced meshes, %d draw calls" % (status["instancedGroups"],
                                                                       status["drawCalls"]))
    eye, target = PILE_CAMERA
    fragment = "t=%r&camera=%g,%g,%g,%g,%g,%g&fov=%g&size=%dx%d" % (frames[-1]["t"], *eye, *target,
                                                                   FOV, *SIZE)
    status, errors, image = shoot(chromium, page, fragment, os.path.join(work, "pile_top.png"), work)
    if not check_loaded("pile (from above)", status, errors):
        return
    balls = [(a["p"], h["name"]) for a, h in zip(frames[-1]["actors"], header["actors"])
             if h["dynamic"]]
    p, name = max(balls, key=lambda b: b[0][2])
    x, y = project(eye, target, p, *SIZE)
    pixel = image[int(y)][int(x)]
    check(same_hue(pixel, hex_rgb(status["colors"][name])),
          "pile: the highest sphere %s (z = %.3f m) is at pixel (%d, %d): %s" % (name, p[2], x, y,
                                                                                 pixel))
    check_plot("pile", status, image, frames[-1]["t"], frames[-1]["t"])


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    superdex, source, work = sys.argv[1:]
    chromium = find_chromium()
    if not chromium:
        print("SKIPPED: no Chromium found (install Debian's `chromium`, as .ci/install-deps does, "
              "or set CHROMIUM to the browser's path)")
        return SKIPPED
    os.makedirs(work, exist_ok=True)
    drop_checks(chromium, superdex, source, work)
    pile_checks(chromium, superdex, source, work)
    print("%d failed" % len(failures) if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
