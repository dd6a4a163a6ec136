"""The HTML report: self-contained, every section, and it renders in a real headless Chromium
(loads without errors, images decode)."""

import base64
import re
import shutil
import struct
import subprocess
from pathlib import Path

import pytest

from webfem.cli import main
from webfem.io.report import SECTIONS

ROOT = Path(__file__).resolve().parents[1]
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--hide-scrollbars"]

# appended to a copy of the page: reports errors and whether every image decoded
PROBE = """<script>
var errors = [];
window.addEventListener("error", function (e) { errors.push(String(e.message || e.type)); },
                        true);
window.addEventListener("load", function () {
  var imgs = Array.prototype.slice.call(document.images);
  var bad = imgs.filter(function (i) { return !(i.complete && i.naturalWidth > 100); });
  var missing = %s.filter(function (id) { var s = document.getElementById(id);
    return !s || s.getBoundingClientRect().height < 10; });
  document.body.setAttribute("data-probe", "images=" + imgs.length + ";bad=" + bad.length +
    ";missing=" + missing.join(",") + ";errors=" + errors.length);
});
</script>"""


def chromium() -> str:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name) or (f"/usr/bin/{name}" if Path(f"/usr/bin/{name}").exists()
                                      else None)
        if path:
            return path
    pytest.skip("no chromium on this machine (.ci/run installs it with apt-get)")


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    assert main(["report", str(ROOT / "cases" / "base.toml"), "--model", "closed-form",
                 "--out", str(out)]) == 0
    return out / "base_closed-form.html"


def test_page_is_self_contained(page):
    html = page.read_text()
    for key in SECTIONS:
        assert f'<section id="{key}">' in html
    # nothing fetched from elsewhere: no scripts, links or remote sources
    assert "<script" not in html and "<link" not in html
    assert not re.search(r'src="(?!data:image/png;base64,)', html)
    images = re.findall(r'src="data:image/png;base64,([^"]+)"', html)
    assert images
    for data in images:   # real PNGs of a sensible size
        png = base64.b64decode(data)
        assert png[:8] == b"\x89PNG\r\n\x1a\n"
        width, height = struct.unpack(">II", png[16:24])
        assert width > 400 and height > 300
    assert "roller.speed" in html and "m/s" in html and "closed-form" in html
    assert "How it was computed" in html and "webfem" in html
    # a key not set says what is used instead (not "left out": read as "not modelled")
    assert "not set, so: D = E_m t^3 / 12" in html and "left out" not in html


def run_chromium(args, tmp_path):
    profile = tmp_path / "profile"
    profile.mkdir()
    return subprocess.run([chromium(), *FLAGS, f"--user-data-dir={profile}", *args],
                          capture_output=True, text=True, timeout=120)


def test_page_renders_in_chromium(page, tmp_path):
    probe = tmp_path / "probe.html"
    ids = "[" + ",".join(f'"{k}"' for k in SECTIONS) + "]"
    probe.write_text(page.read_text().replace("</body>", PROBE % ids + "</body>"))
    done = run_chromium(["--virtual-time-budget=10000", "--enable-logging=stderr", "--v=0",
                         "--dump-dom", probe.as_uri()], tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    found = re.search(r'data-probe="([^"]*)"', done.stdout)
    assert found, done.stdout[:2000]
    assert found.group(1) == f"images={done.stdout.count('<img')};bad=0;missing=;errors=0"
    assert "<img" in done.stdout
    assert not re.search(r"CONSOLE.*(Uncaught|Error)|ERR_FILE_NOT_FOUND", done.stderr)
    for heading in SECTIONS.values():
        assert f"<h2>{heading}</h2>" in done.stdout


def test_screenshot_is_not_blank(page, tmp_path):
    shot = tmp_path / "shot.png"
    done = run_chromium(["--window-size=1000,1400", f"--screenshot={shot}", page.as_uri()],
                        tmp_path)
    assert done.returncode == 0 and shot.stat().st_size > 20000, done.stderr[-2000:]
    from PIL import Image   # matplotlib depends on Pillow
    with Image.open(shot) as im:
        colours = im.convert("L").getextrema()
    assert colours[0] < 80 and colours[1] > 200   # text on a light page


def test_default_report_says_which_model_answered_and_why(tmp_path):
    """No --model: the page is base_auto.html, shows the model auto chose and its reason,
    and never claims the model was asked for by name (issue 20)."""
    import webfem
    assert main(["report", "base", "--out", str(tmp_path), "--quiet"]) == 0
    page = tmp_path / "base_auto.html"
    html = page.read_text()
    solved = webfem.solve(webfem.load_case(ROOT / "cases" / "base.toml"), model="auto")
    used, why = solved.summary.model_used, solved.summary.why
    from html import escape
    assert "asked for by name" not in html
    assert f"answered by <b>{used}</b>" in html and escape(why) in html
    assert "the default of webfem report (--model auto)" in html
    assert f"webfem report: base (auto: {used})" in html or used == "auto"
    assert main(["report", "base", "--out", str(tmp_path), "--model", "closed-form"]) == 0
    named = (tmp_path / "base_closed-form.html").read_text()
    assert "asked for by name (--model closed-form)" in named
