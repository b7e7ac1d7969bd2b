"""The documentation site (``make docs``): it builds with warnings as errors, its tutorials
and gallery run during the build, and every page works in headless Chromium: it loads
without a console error, its images decode, its links and anchors resolve, and the search
page finds what the site says.

The build runs the executed tutorials and gallery afresh (``run_stale_examples``) on their
coarse grids: about 50 s on a quiet 2-core machine, 2 minutes under load; the Chromium pass
over every page takes about 10 s. In CI the browser pass reads the site `make test` built
(``FOILBEARING_DOCS_SITE``, :func:`_kept_site`): 30 s instead of about 130.
"""

from __future__ import annotations

import html
import json
import os
import re
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urlsplit

import pytest

from test_report import chromium

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"

#: The executed tutorials and gallery examples: each page must show its output and a figure.
EXECUTED = (
    "generated/tutorials/plot_01_bump_foil_bearing.html",
    "generated/tutorials/plot_02_cgfb_voltage.html",
    "generated/tutorials/plot_03_sweep_dask.html",
    "generated/tutorials/plot_04_uncertainty_dask.html",
    "generated/tutorials/plot_05_rotor_on_two_bearings.html",
    "generated/gallery/plot_static_map.html",
    "generated/gallery/plot_coefficients.html",
    "generated/gallery/plot_onset_map.html",
    "generated/gallery/plot_waterfall.html",
    "generated/gallery/plot_limit_cycles.html",
    "generated/gallery/plot_campbell.html",
)


# --- the site's HTML, parsed -------------------------------------------------------


class _Links(HTMLParser):
    """The ids of a page and every URL it refers to (href of a, link; src of img, script)."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.ids: set[str] = set()
        self.urls: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = {k: v or "" for k, v in attrs}
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "a" and "name" in a:
            self.ids.add(a["name"])
        key = {"a": "href", "link": "href", "img": "src", "script": "src"}.get(tag)
        if key and a.get(key):
            self.urls.append(a[key])


def site_pages(site: Path) -> list[Path]:
    """The pages of the site: its HTML files but the theme's templates in ``_static``."""
    return [p for p in sorted(site.rglob("*.html")) if "_static" not in p.relative_to(site).parts]


def parse_site(site: Path) -> dict[Path, _Links]:
    """Every HTML page of ``site``, parsed."""
    pages = {}
    for page in site_pages(site):
        parser = _Links()
        parser.feed(page.read_text(encoding="utf-8"))
        pages[page] = parser
    return pages


def broken_links(site: Path) -> list[str]:
    """Each URL of the site that leaves it or does not resolve: a missing file, or an anchor
    that its page does not have. One line each, naming the page and the URL."""
    pages = parse_site(site)
    bad = []
    for page, links in pages.items():
        where = page.relative_to(site)
        for url in links.urls:
            parts = urlsplit(url)
            if parts.scheme in ("http", "https") or url.startswith("//"):
                bad.append(f"{where}: {url} leaves the site")
                continue
            if parts.scheme or not (parts.path or parts.fragment):
                continue  # mailto:, javascript:, data: and a bare "#"
            target = (page.parent / unquote(parts.path)).resolve() if parts.path else page
            if target.is_dir():
                target = target / "index.html"
            if not target.is_file():
                bad.append(f"{where}: {url} has no file")
            elif parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else set()
                if unquote(parts.fragment) not in ids:
                    bad.append(f"{where}: {url} has no anchor #{parts.fragment}")
    return bad


# --- the site in Chromium --------------------------------------------------------

#: Put first in each page's <head>: records what goes wrong as the page loads (a resource
#: that fails, in the capture phase; an uncaught error; console.error and console.warn) in
#: ``window.fbErrors``. The theme's console.log/info/debug notes are not errors.
PROBE = """<script>(function(){var e=window.fbErrors=[];
window.addEventListener('error',function(v){var t=v.target;
e.push(t&&t!==window&&t.tagName?'failed to load <'+t.tagName+'> '+String(t.src||t.href)
:'uncaught: '+v.message);},true);
window.addEventListener('unhandledrejection',function(v){e.push('unhandled: '+v.reason);});
['error','warn'].forEach(function(k){var o=console[k];console[k]=function(){
e.push('console.'+k+': '+Array.prototype.join.call(arguments,' '));o.apply(console,arguments);};});
})();</script>"""

#: Loads each page in turn in an iframe (same origin: --allow-file-access-from-files),
#: makes its lazy images load and waits for every image to decode, reads the probe's
#: errors, then opens the search page with a query and waits for its results.
DRIVER = """<!DOCTYPE html><html><head><meta charset="utf-8"><title>check</title></head>
<body><iframe id="f" style="width:1280px;height:900px"></iframe><pre id="fb-out"></pre>
<script>
var pages = %(pages)s, query = %(query)s, results = [];
var f = document.getElementById('f');
function out(r) { document.getElementById('fb-out').textContent = JSON.stringify(r); }
function check(i) {
  if (i >= pages.length) { return search(); }
  f.onload = function () {
    var imgs = Array.prototype.slice.call(f.contentDocument.images);
    imgs.forEach(function (im) { im.loading = 'eager'; });
    Promise.all(imgs.map(function (im) {
      // decode() can stay pending in headless Chromium for an image of a frame it does not
      // paint (2 runs of 4 stalled on one tutorial page): after 10 s of virtual time an
      // image that has loaded with a size counts as decoded, any other as broken.
      var late = new Promise(function (done) { setTimeout(function () {
        done(im.complete && im.naturalWidth > 0 ? null : im.getAttribute('src'));
      }, 10000); });
      return Promise.race([late, im.decode().then(
        function () { return im.naturalWidth > 0 ? null : im.src; },
        function () { return im.getAttribute('src'); })]);
    })).then(function (broken) {
      results.push({page: pages[i], images: imgs.length,
                    broken: broken.filter(function (b) { return b !== null; }),
                    errors: f.contentWindow.fbErrors || ['no probe']});
      out({stalled: true, pages: results});
      check(i + 1);
    });
  };
  out({stalled: pages[i], pages: results});
  f.src = pages[i];
}
function search() {
  f.onload = function () {
    var tries = 0;
    (function poll() {
      var d = f.contentDocument, items = d.querySelectorAll('#search-results li');
      var status = d.querySelector('#search-results .search-summary, #search-progress');
      var done = status && /finished|found/i.test(status.textContent);
      if (done || tries++ > 6000) {  // 300 s of virtual time
        out({pages: results, search: Array.prototype.map.call(items, function (li) {
          var a = li.querySelector('a'); return a ? a.getAttribute('href') : '';
        })});
      } else { setTimeout(poll, 50); }
    })();
  };
  f.src = 'search.html?q=' + encodeURIComponent(query);
}
check(0);
</script></body></html>"""


def run_site_in_chromium(
    site: Path, pages: list[str], query: str, tmp: Path
) -> tuple[dict[str, Any], list[str]]:
    """Each of ``pages`` (relative to ``site``) in Chromium, then the search for ``query``:
    the driver's result and chromium's console lines. Runs on a copy of ``site`` in
    ``tmp`` whose pages carry the probe."""
    site = Path(shutil.copytree(site, tmp / "probed"))
    for page in pages:
        path = site / page
        text = path.read_text(encoding="utf-8")
        head = re.search(r"<head[^>]*>", text)
        assert head, f"{page}: no <head>"
        path.write_text(text[: head.end()] + PROBE + text[head.end() :], encoding="utf-8")
    driver = site / "_browser_check.html"
    driver.write_text(
        DRIVER % {"pages": json.dumps(pages), "query": json.dumps(query)}, encoding="utf-8"
    )
    cmd = [
        chromium(),
        "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync",
        "--disable-extensions", "--host-resolver-rules=MAP * ~NOTFOUND",
        "--allow-file-access-from-files",
        f"--user-data-dir={tmp / 'chromium-profile'}", "--enable-logging=stderr", "--v=0",
        "--virtual-time-budget=600000", "--dump-dom", driver.as_uri(),
    ]  # fmt: skip
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300, check=False)
    m = re.search(r'<pre id="fb-out">(.*?)</pre>', proc.stdout, re.S)
    assert proc.returncode == 0 and m and m.group(1), (
        f"chromium failed (rc {proc.returncode}):\n{proc.stderr[-3000:]}"
    )
    console = [line for line in proc.stderr.splitlines() if ":CONSOLE" in line]
    result = json.loads(html.unescape(m.group(1)))
    assert "stalled" not in result, f"the check stalled at {result['stalled']}"
    return result, console


# --- the build -----------------------------------------------------------------------


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """``make docs``'s build, into a temporary folder, the tutorials and gallery run afresh.
    Longer than a test's 120 s budget under load (about 50 s quiet, 2 minutes with the
    2 cores shared): it runs eleven scripts and reads 110 pages, once for this module."""
    try:
        import sphinx_gallery  # noqa: F401  (the docs extra)
    except ImportError:
        message = "the docs extra is not installed: pip install -c constraints.txt '.[docs]'"
        if os.environ.get("CI"):
            pytest.fail(message)
        pytest.skip(message)
    kept = _kept_site()
    if kept is not None and kept[1].is_file():
        return kept[0] / "html"  # this CI run's `make test` built the same sources
    out = tmp_path_factory.mktemp("docs") if kept is None else kept[0]
    if kept is not None:
        shutil.rmtree(out, ignore_errors=True)
        out.mkdir(parents=True)
    env = {**os.environ, "MPLBACKEND": "Agg", "FOILBEARING_COMPILE_NOTICE": "0"}
    cmd = [
        sys.executable, "-m", "sphinx", "-b", "html", "-W", "--keep-going", "-q",
        "-d", str(out / "doctrees"), "-D", "sphinx_gallery_conf.run_stale_examples=1",
        str(DOCS), str(out / "html"),
    ]  # fmt: skip
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900, check=False)
    assert proc.returncode == 0, f"sphinx-build failed:\n{proc.stdout[-3000:]}{proc.stderr[-5000:]}"
    assert "WARNING" not in proc.stderr, proc.stderr[-5000:]
    if kept is not None:
        kept[1].write_text("built\n", encoding="utf-8")  # after the checks: a whole build
    return out / "html"


def _kept_site() -> tuple[Path, Path] | None:
    """Where CI keeps the site between its two phases, and the stamp of a finished build.

    ``.ci/run`` sets ``FOILBEARING_DOCS_SITE`` to a folder: `make test` builds the site
    there and `make docs-check` (the browser pass, run alone after it) reads the same build
    instead of building it a second time, about a minute of CI. The build is named by the
    SHA-256 of every tracked file of the docs, the package, the examples and the project's
    metadata (``git ls-files``), so a stamp is only ever read for the same sources. Unset, or
    outside a git checkout: None, and each run builds its own site.
    """
    import hashlib

    folder = os.environ.get("FOILBEARING_DOCS_SITE")
    if not folder:
        return None
    try:
        listed = subprocess.run(
            ["git", "ls-files", "-z", "docs", "src", "examples", "README.md", "pyproject.toml",
             "constraints.txt"],
            cwd=ROOT, capture_output=True, check=True,
        ).stdout  # fmt: skip
    except (OSError, subprocess.CalledProcessError):
        return None
    digest = hashlib.sha256()
    for name in sorted(filter(None, listed.split(b"\0"))):
        path = ROOT / name.decode()
        digest.update(name + b"\0" + (path.read_bytes() if path.is_file() else b"") + b"\0")
    where = Path(folder) / digest.hexdigest()[:16]
    return where, where / "BUILT"


def test_every_section_is_built(site: Path) -> None:
    """The sections of the site, each with its pages; the API reference from the docstrings."""
    for page in (
        "index.html",
        "getting-started.html",
        "generated/tutorials/index.html",
        "generated/gallery/index.html",
        "guide/index.html",
        "guide/commands.html",
        "case-format.html",
        "rotor-format.html",
        "theory.html",
        "lift-off.html",
        "api/index.html",
        "api/generated/foilbearing.static.html",
        "development/index.html",
        "development/orbit-performance.html",
        "search.html",
    ):
        assert (site / page).is_file(), page
    static = (site / "api/generated/foilbearing.static.html").read_text(encoding="utf-8")
    assert "solve_equilibrium" in static and "Parameters" in static


def script_output(page: str) -> str:
    """What a gallery page's scripts printed, its output blocks' text joined."""
    blocks = re.findall(r'class="sphx-glr-script-out[^"]*".*?<pre>(.*?)</pre>', page, re.S)
    return html.unescape(re.sub(r"<[^>]+>", "", "".join(blocks))).strip()


def test_the_tutorials_and_gallery_ran(site: Path) -> None:
    """Each executed script's page shows its printed output and at least one figure of its
    own; the numbers they print say what the pages claim."""
    for name in EXECUTED:
        text = (site / name).read_text(encoding="utf-8")
        assert "sphx-glr-script-out" in text, f"{name}: no output"
        assert re.search(r'<img[^>]+src="[^"]*sphx_glr_plot_\w+_\d{3}\.png"', text), name
    voltage = (site / "generated/tutorials/plot_02_cgfb_voltage.html").read_text(encoding="utf-8")
    # What a voltage buys: 150 V lifts the C-GFB's onset (43.9 to 55.2 krpm on the default grid)
    gain = re.search(r"150 V raises the onset by (-?\d+) %", voltage)
    assert gain and 15 <= int(gain.group(1)) <= 40, gain
    assert "8 of 8 points, 0 failed" in page_output(
        site, "generated/tutorials/plot_03_sweep_dask.html"
    )
    # The paper's bounded whip at 150 V: a supercritical Hopf bifurcation, every cycle stable
    cycles = page_output(site, "generated/gallery/plot_limit_cycles.html")
    assert cycles.startswith("supercritical Hopf bifurcation"), cycles
    assert cycles.count(", stable") >= 3 and "unstable" not in cycles, cycles


def page_output(site: Path, name: str) -> str:
    """What the executed page ``name`` (one of EXECUTED) printed."""
    assert name in EXECUTED, name
    return script_output((site / name).read_text(encoding="utf-8"))


def test_the_uncertainty_envelope_holds_the_nominal_bearing(site: Path) -> None:
    """The uncertainty tutorial's study ran every point, and the nominal bearing, computed
    beside the study, lies inside the 5-95 % band of the minimum film and of the onset:
    the inputs' distributions are centred on the nominal values and both outputs are
    monotone in the input that dominates them (the clearance)."""
    out = page_output(site, "generated/tutorials/plot_04_uncertainty_dask.html")
    assert "64 of 64 points computed" in out, out
    for what, unit in (("minimum film at 40 krpm", "µm"), ("onset of whirl", "krpm")):
        m = re.search(
            rf"{what}: ([\d.]+) to ([\d.]+) {unit} \(median ([\d.]+)\); nominal ([\d.]+) {unit}",
            out,
        )
        assert m, out
        low, high, median, nominal = (float(g) for g in m.groups())
        assert low < median < high and low <= nominal <= high, m.group(0)
    # The onset is set by the clearance first: it ranks first among the four inputs
    onset = re.search(r"onset_speed_krpm\[[^\]]*\]: ([\w.]+) ", out)
    assert onset and onset.group(1) == "bearing.clearance", out


def test_the_rotor_whirls_below_half_its_speed_at_onset(site: Path) -> None:
    """The rotor tutorial ran ROSS: the onset lies inside its scan (30-60 krpm), and the
    rotor whirls there sub-synchronously, below half its running speed, as a rotor on
    gas films does (the film's mean circumferential flow moves at half the surface)."""
    out = page_output(site, "generated/tutorials/plot_05_rotor_on_two_bearings.html")
    m = re.search(r"onset (\d+) rpm, whirl ([\d.]+) Hz", out)
    assert m, out
    onset_rpm, whirl_hz = float(m.group(1)), float(m.group(2))
    assert 30000 < onset_rpm < 60000, out
    assert 0.0 < whirl_hz < 0.5 * onset_rpm / 60.0, out


def test_the_campbell_diagram_splits_its_bending_pair_and_crosses_1x(site: Path) -> None:
    """The Campbell gallery example: the shaft's bending pair splits with speed, the
    backward whirl falling and the forward rising (the disks' gyroscopic moments); where
    a mode meets the 1X line, the diagram's interpolated crossing and ROSS's modal solve
    at that speed agree on the frequency to 2 %."""
    out = page_output(site, "generated/gallery/plot_campbell.html")
    pair = dict(
        (whirl, (float(f0), float(f1)))
        for whirl, f0, f1 in re.findall(r"mode \d+ \((\w+)\): (\d+) Hz at \d+ krpm, (\d+) Hz", out)
    )
    assert set(pair) == {"backward", "forward"}, out
    assert pair["backward"][1] < pair["backward"][0] and pair["forward"][1] > pair["forward"][0]
    crossings = re.findall(
        r"meets 1X at (\d+) rpm \([\d.]+ Hz\); ROSS at that speed: ([\d.]+) Hz", out
    )
    assert crossings, out
    for rpm, hz in crossings:
        assert float(hz) == pytest.approx(float(rpm) / 60.0, rel=0.02), (rpm, hz)


def test_every_link_and_anchor_resolves_inside_the_site(site: Path) -> None:
    assert broken_links(site) == []


# Run alone (`make docs-check`, a phase of .ci/run): a Chromium run over ~100 pages is the
# suite's one browser session of this size. Its stalls (an image's decode() left pending on
# one tutorial page, 2 runs of 4) are bounded in the driver above; a stall left is named.
@pytest.mark.browser
def test_every_page_loads_cleanly_in_headless_chromium(site: Path, tmp_path: Path) -> None:
    """Every page without a console message, every image decoded; the search page finds the
    case format for a word of it."""
    pages = [str(p.relative_to(site)) for p in site_pages(site)]
    result, console = run_site_in_chromium(site, pages, "eccentricity", tmp_path)
    assert [r["page"] for r in result["pages"]] == pages
    assert [r for r in result["pages"] if r["broken"] or r["errors"]] == []
    assert [line for line in console if "Uncaught" in line] == []
    assert sum(r["images"] for r in result["pages"]) >= 2 * len(EXECUTED)
    assert any(href.startswith("case-format.html") for href in result["search"]), result["search"]


def test_the_checks_catch_a_broken_site(tmp_path: Path) -> None:
    """A negative control: a missing page, a missing anchor, a link off the site, an image
    that does not decode and a script error are each seen."""
    site = tmp_path / "site"
    site.mkdir()
    (site / "search.html").write_text("<html><body><ul id='search-results'></ul></body></html>")
    (site / "bad.png").write_bytes(b"not a png")
    (site / "index.html").write_text(
        "<!DOCTYPE html><html><head><title>x</title></head><body id='top'>"
        '<a href="#top">ok</a><a href="missing.html">gone</a><a href="search.html#nowhere">x</a>'
        '<a href="https://example.invalid/">out</a><img alt="bad" src="bad.png">'
        "<script>console.log('a note is fine'); undefinedFunction();</script></body></html>",
        encoding="utf-8",
    )
    assert broken_links(site) == [
        "index.html: missing.html has no file",
        "index.html: search.html#nowhere has no anchor #nowhere",
        "index.html: https://example.invalid/ leaves the site",
    ]
    result, console = run_site_in_chromium(site, ["index.html"], "x", tmp_path)
    [page] = result["pages"]
    assert page["page"] == "index.html" and page["images"] == 1 and page["broken"] == ["bad.png"]
    assert any("undefinedFunction" in e for e in page["errors"])
    assert any("failed to load <IMG>" in e for e in page["errors"])
    assert any("undefinedFunction" in line for line in console)
    assert result["search"] == []
