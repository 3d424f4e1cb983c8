#!/usr/bin/env python3
"""The report pages in headless Chromium (issue 20). Usage: browser_test.py path/to/kintsugi

Paper object 10's page loads without errors, shows the model and one list entry per
problem; the picture --png takes shows each problem type's colour near where the page
says that problem projects (and not in an empty corner); clicking an entry moves the
camera onto the problem; the page is the same bytes twice; the page after beautify
shows both models. Exit 77 (ctest: skipped) when no Chromium is installed."""
import html.parser
import json
import os
import shutil
import subprocess
import sys
import tempfile
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import png  # noqa: E402

K = sys.argv[1]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)
    return ok


def chromium():
    given = os.environ.get("KINTSUGI_CHROMIUM")
    if given:
        return shutil.which(given) or (given if os.access(given, os.X_OK) else None)
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        if shutil.which(name):
            return shutil.which(name)
    return None


BROWSER = chromium()
if not BROWSER:
    print("SKIP: no Chromium installed (apt-get install chromium); the report pages were not tested in a browser")
    sys.exit(77)

work = tempfile.mkdtemp(prefix="kintsugi-view-test-")


def run(*args):
    r = subprocess.run([K, *args], capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
    return r


def browser(page, query, width, height, extra):
    args = [BROWSER, "--headless", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--hide-scrollbars",
            "--force-device-scale-factor=1", "--no-first-run", "--user-data-dir=" + os.path.join(work, "profile"),
            "--window-size=%d,%d" % (width, height), "--virtual-time-budget=10000", *extra,
            "file://" + urllib.parse.quote(os.path.abspath(page)) + query]
    if os.geteuid() == 0:
        args.insert(1, "--no-sandbox")
    return subprocess.run(args, capture_output=True, timeout=300)


class Dom(html.parser.HTMLParser):
    """The attributes of <body> and of each problem entry, and the inlined scene."""

    def __init__(self, text):
        super().__init__()
        self.body, self.items, self.labels, self.scene, self._in_scene, self._label = {}, [], [], "", False, False
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "body":
            self.body = a
        elif tag == "li" and "data-index" in a:
            self.items.append(a)
        elif tag == "script" and a.get("id") == "scene":
            self._in_scene = True
        self._label = tag == "div" and a.get("class") == "label"

    def handle_endtag(self, tag):
        self._in_scene = False

    def handle_data(self, data):
        if self._in_scene:
            self.scene += data
        if self._label:
            self.labels.append(data)
            self._label = False


def dump(page, query="", width=1400, height=800):
    r = browser(page, query, width, height, ["--dump-dom"])
    return Dom(r.stdout.decode("utf-8", "replace"))


def screen(item):
    """{model: (x, y)} from data-screen="0:x,y 1:x,y"."""
    out = {}
    for part in item.get("data-screen", "").split():
        m, xy = part.split(":")
        x, y = xy.split(",")
        out[int(m)] = (float(x), float(y))
    return out


def hex_rgb(h):
    return tuple(int(h[i:i + 2], 16) for i in (1, 3, 5))


def colour_near(rows, x, y, rgb, radius=9, within=40):
    h, w = len(rows), len(rows[0])
    for yy in range(max(0, int(y) - radius), min(h, int(y) + radius + 1)):
        for xx in range(max(0, int(x) - radius), min(w, int(x) + radius + 1)):
            if sum(abs(a - b) for a, b in zip(rows[yy][xx], rgb)) <= within:
                return True
    return False


try:
    model = os.path.join(work, "paper10.json")
    page = os.path.join(work, "paper10.html")
    check(run("generate", "paper-10", "-o", model).returncode == 0, "generate paper-10")
    detected = json.loads(run("detect", model, "--json").stdout)
    problems = detected["problems"]
    types = sorted({p["type"] for p in problems})
    check(len(problems) > 0, "paper-10 has problems to show (%d of %d types)" % (len(problems), len(types)))

    check(run("view", model, "-o", page).returncode == 0, "view writes the page")
    again = os.path.join(work, "again.html")
    run("view", model, "-o", again)
    check(open(page, "rb").read() == open(again, "rb").read(), "the page is the same bytes for the same input")
    text = open(page, encoding="utf-8").read()
    check("http://" not in text.split("<script type=\"application/json\"")[0] and "<script src" not in text,
          "the page loads nothing from elsewhere")

    dom = dump(page)
    check(dom.body.get("data-ready") == "1", "the page finished loading (data-ready)")
    check(dom.body.get("data-errors") == "0", "no errors in the console (data-errors=%s)" % dom.body.get("data-errors"))
    check(len(dom.items) == len(problems), "one list entry per problem (%d entries, %d problems)" % (len(dom.items), len(problems)))
    check([i.get("data-type") for i in dom.items] == [p["type"] for p in problems], "entries in detect's order with its types")
    check(len(dom.labels) == 1 and "faces" in dom.labels[0], "one model shown: %s" % dom.labels)
    scene = json.loads(dom.scene)
    check(len(scene["models"]) == 1 and len(scene["models"][0]["mesh"]["chunks"]) > 0, "the model is tessellated")

    # The picture: each problem type's colour where its problems project, not in an empty corner.
    picture = os.path.join(work, "paper10.png")
    check(run("view", model, "--png", picture).returncode == 0, "view --png writes a picture")
    width, height, rows = png.decode(open(picture, "rb").read())
    check((width, height) == (1000, 800), "the picture is 1000 x 800 (got %d x %d)" % (width, height))
    grey = sum(1 for row in rows[::4] for p in row[::4] if abs(p[0] - p[2]) < 12 and 60 < p[0] < 235)
    check(grey > 2000, "the model is in the picture (%d shaded samples)" % grey)
    still = dump(page, "?still=1&size=1000x800", 1000, 800)  # as --png lays it out
    check(still.body.get("data-errors") == "0", "no errors in still mode")
    for t in types:
        rgb = hex_rgb(scene["colors"][t])
        at = [screen(i).get(0) for i in still.items if i.get("data-type") == t]
        hits = [xy for xy in at if xy and colour_near(rows, xy[0], xy[1], rgb)]
        check(len(hits) > 0, "%s's colour %s near its problems in the picture (%d of %d)" % (t, scene["colors"][t], len(hits), len(at)))
        check(not colour_near(rows, 4, height - 4, rgb, radius=3), "%s's colour not in an empty corner" % t)

    # Clicking entry 0 frames problem 0: the camera moves and looks at the problem.
    clicked = dump(page, "?click=0")
    before = [float(v) for v in clicked.body.get("data-camera-initial", "").split(",")]
    after = [float(v) for v in clicked.body.get("data-camera", "").split(",")]
    check(len(before) == 6 and len(after) == 6 and before != after, "clicking an entry changes the camera")
    anchor = scene["problems"][0]["anchor"]
    check(len(after) == 6 and all(abs(a - b) <= 1e-4 * scene["size"] for a, b in zip(after[3:], anchor)),
          "the camera now looks at problem 0's anchor %s (target %s)" % (anchor, after[3:]))
    check("selected" in (clicked.items[0].get("class") or ""), "the clicked entry is highlighted")

    # After beautify: both models side by side, entries with what was done.
    fixed, report, page2 = (os.path.join(work, n) for n in ("fixed.json", "report.json", "beautify.html"))
    check(run("beautify", model, "-o", fixed, "--report", report, "--html", page2).returncode == 0, "beautify --html")
    handled = json.load(open(report))["problems"]
    dom2 = dump(page2)
    check(dom2.body.get("data-errors") == "0", "beautify page: no errors")
    check(len(dom2.labels) == 2 and dom2.labels[0].startswith("before") and dom2.labels[1].startswith("after"),
          "beautify page: before and after side by side (%s)" % dom2.labels)
    check(len(dom2.items) == len(handled), "beautify page: one entry per problem handled (%d, %d)" % (len(dom2.items), len(handled)))
    scene2 = json.loads(dom2.scene)
    check([p["action"] for p in scene2["problems"]] == [p["action"] for p in handled] and
          [p["operators"] for p in scene2["problems"]] == [p["operators"] for p in handled],
          "beautify page: each entry's action and operators are the report's")
    shown = [screen(i) for i in dom2.items]
    check(any(0 in s for s in shown), "beautify page: problems marked in the model before")
finally:
    shutil.rmtree(work, ignore_errors=True)

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
