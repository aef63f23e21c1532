"""The output folder's gallery (``index.html``): cards grouped by kind, each kind's
signature figure as the thumbnail, a headline in words, slugs that stay in their card."""

from __future__ import annotations

import html
import json
import math
import re
import shutil
import subprocess
from pathlib import Path

import h5py
import pytest
from scipy.special import ellipk

from conftest import pendulum_text
from reportgen.archive.store import ArchiveData, gallery_entry
from reportgen.kinds import KINDS
from reportgen.pipeline.stages import GALLERY_CACHE, run_batch, write_index
from reportgen.scene.gallery import check_headline, chosen_figure, family_headline, plain
from reportgen.scene.results import Check
from reportgen.scene.typeset import visible_text

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-quic"]
#: a config path as a check or a config may spell it ("initial.theta", "run.t_end")
CONFIG_KEY = re.compile(r"\b(?:initial|params|run|report|band|sweep|system)\.[a-z_]+\b")
LONG = "a_scene_whose_file_name_is_far_longer_than_any_card_is_wide_" * 2 + "end"


@pytest.fixture(scope="module")
def gallery(tmp_path_factory):
    """A folder with two pendulums, the oscillator and the heavy top of Fig. 4.3, and a
    copy of one pendulum under a very long name."""
    root = tmp_path_factory.mktemp("gallery")
    configs = root / "configs"
    configs.mkdir()
    (configs / "swing_b.toml").write_text(pendulum_text(theta=1.0, t_end=4.0, samples=401,
                                                        title="B swing"))
    (configs / "swing_a.toml").write_text(pendulum_text(theta=0.5, t_end=4.0, samples=401,
                                                        title="A swing"))
    shutil.copy(ROOT / "configs" / "oscillator.toml", configs / "oscillator.toml")
    shutil.copy(ROOT / "configs" / "heavy_top_fig4.3.toml", configs / "top_fig.toml")
    out = root / "out"
    outcomes = run_batch([str(configs)], out_root=str(out), jobs=1, formats=("html",))
    assert all(o.ok for o in outcomes), [(o.name, o.message) for o in outcomes]
    shutil.copytree(out / "swing_a", out / LONG)
    write_index(str(out))
    return out


def _cards(index: str) -> list[tuple[str, str]]:
    """(heading or "", card name) in page order: a heading as ("h", name)."""
    found = re.findall(r'<h2 class="group">([^<]*?) <span|<div class="card[^"]*" id="scene-([^"]*)"',
                       index)
    return [("h", html.unescape(h)) if h else ("card", html.unescape(c)) for h, c in found]


def _card(index: str, name: str) -> str:
    start = index.index(f'id="scene-{name}"')
    return index[start:index.index("</div>\n</div>", start)]


def test_cards_are_grouped_by_kind_in_the_kinds_order_and_by_title(gallery):
    index = (gallery / "index.html").read_text(encoding="utf-8")
    order = _cards(index)
    headings = [name for what, name in order if what == "h"]
    assert headings == ["Plane pendulum", "Harmonic oscillator", "Heavy symmetric top"]
    assert list(KINDS).index("pendulum") < list(KINDS).index("oscillator") \
        < list(KINDS).index("heavy_top")
    pendulums = [name for what, name in order[1:order.index(("h", "Harmonic oscillator"))]]
    # by title: "A swing" (its long-named copy, then swing_a: by name), "B swing"
    assert pendulums == [LONG, "swing_a", "swing_b"]
    assert order[-2:] == [("h", "Heavy symmetric top"), ("card", "top_fig")]
    assert 'href="#kind-heavy_top"' in index and 'id="kind-heavy_top"' in index


def test_heavy_top_thumbnail_is_fig_4_3(gallery):
    """The kind's signature figure, not the report's first one."""
    index = (gallery / "index.html").read_text(encoding="utf-8")
    card = _card(index, "top_fig")
    assert 'src="top_fig/figures/fig4_3-fig4_3.svg"' in card
    assert "card wide" in index[index.index('id="scene-top_fig"') - 40:
                                index.index('id="scene-top_fig"')]  # a strip: two columns
    # the pendulum's is its phase portrait, though the report opens on θ(t)
    manifest = json.loads((gallery / "swing_a" / "figures" / "sections.json").read_text())
    assert manifest["sections"][0]["figures"][0]["id"] != "phase_portrait-phase"
    assert 'src="swing_a/figures/phase_portrait-phase.svg"' in _card(index, "swing_a")


def test_signature_figure_falls_back_in_order():
    """A scene without the first preference (a Hénon–Heiles run without a section) shows
    the next one drawn, else the report's first figure."""
    ids = ["trajectory-coordinates", "trajectory-configuration", "invariants-invariants"]
    assert chosen_figure(ids, ("poincare", "poincare_family", "configuration")) == 1
    assert chosen_figure(ids + ["poincare-poincare"], ("poincare", "configuration")) == 3
    assert chosen_figure(ids, ("fig4_3",)) == 0
    assert chosen_figure(ids, ()) == 0
    assert chosen_figure([], ("fig4_3",)) is None
    assert chosen_figure(ids, ("trajectory-configuration",)) == 1  # a full id works too
    for cls in KINDS.values():  # every kind names its signature figure and heading
        assert cls.gallery_figures and (cls.gallery_name or cls.name_in_words), cls.kind


def test_headlines_are_in_words(gallery):
    index = (gallery / "index.html").read_text(encoding="utf-8")
    lines = {name: visible_text(re.search(r'class="meta headline">(.*?)</p>',
                                          _card(index, name)).group(1))
             for name in ("swing_a", "oscillator", "top_fig")}
    for line in lines.values():
        assert "rel. error" not in line and "t_end" not in line
        assert not CONFIG_KEY.search(line), line
    # θ0 = 0.5 rad, g = 9.81, l = 1: T = 4K(k)√(l/g), k = sin(θ0/2) (DLMF 22.19.4)
    period = 4 * ellipk(math.sin(0.25) ** 2) * math.sqrt(1 / 9.81)
    found = re.fullmatch(r"libration, period ([\d.]+) s: measured (?:(?:\d × )?10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+) "
                         r"from|equal to) the exact 4K\(k\)√\(l/g\)", lines["swing_a"])
    assert found, lines["swing_a"]
    assert float(found.group(1)) == pytest.approx(period, rel=1e-4)
    power = found.group(2) and int(found.group(2).translate(str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹",
                                                                          "-0123456789")))
    assert power is None or power <= -8  # the measured period within 10⁻⁸ of the exact
    assert lines["oscillator"].startswith("q(t), p(t) ") and "closed form" in lines["oscillator"]
    assert "nutation period" in lines["top_fig"] and "4K(k²)/√(β(u₃−u₁))" in lines["top_fig"]


def _light(checks, analysis=None) -> ArchiveData:
    return ArchiveData(path=None, attrs={"kind": "pendulum"}, config_text="", provenance={},
                       analysis=analysis or {}, checks=checks)


def test_default_headline_drops_config_keys_and_jargon():
    worst = Check("period of the worst member (initial.theta = 3.0969085)", 6.62584,
                  6.62584 * (1 + 1.3e-10), "s", "4K(k)·√(l/g), DLMF 22.19.4")
    line = family_headline(_light([worst], {"sweep_members": 2000, "sweep_ok": 2000}),
                           "amplitudes", "period")
    assert line == "2000 amplitudes, all ok; every period within 1e-10 of 4K(k)·√(l/g)"
    assert plain("H(0) of the member furthest (initial.y = 0.28)") == "H(0) of the member furthest"
    single = Check("cos θ(t_end)", 0.58, 0.58 * (1 + 1.1e-11), "",
                   "u1 + (u2−u1) sn²(λt + τ0 | k²) (Jacobi form of Goldstein 5.72; FIELD-NOTES)")
    assert check_headline(_light([single])) == \
        "cos θ(t_end) 0.58, 1e-11 from u1 + (u2−u1) sn²(λt + τ0 | k²)"
    exact = Check("nutation period", 2.3, 2.3, "s", "4K(k²)/√(β(u3−u1)) (notes §10.1)")
    assert check_headline(_light([exact])) == "nutation period 2.3 s, equal to 4K(k²)/√(β(u3−u1))"
    assert check_headline(_light([])) == ""


def test_a_failing_kind_headline_costs_the_line_only(gallery, tmp_path):
    def broken(data):
        raise KeyError("period")

    entry = gallery_entry(gallery / "swing_a" / "run.h5", headline=broken)
    assert entry is not None and entry["title"] == "A swing"
    assert "rel. error" not in entry["headline"] and entry["headline"]  # the worst check


def test_inaccurate_status_has_its_badge(gallery, tmp_path):
    out = tmp_path / "out"
    shutil.copytree(gallery / "swing_b", out / "swing_b")
    with h5py.File(out / "swing_b" / "run.h5", "r+") as f:
        f.attrs["status"] = "inaccurate"
    write_index(str(out))
    index = (out / "index.html").read_text(encoding="utf-8")
    assert '<span class="badge inaccurate">inaccurate</span>' in index
    rule = re.search(r"([^}]*\.badge\.inaccurate[^{]*)\{([^}]*)\}", index)
    unstable = re.search(r"\.badge\.unstable[^{]*\{([^}]*)\}", index)
    assert rule and unstable and rule.group(2) == unstable.group(1)  # amber, like unstable
    assert (out / GALLERY_CACHE).exists()


def test_long_slug_wraps_inside_its_card(gallery, tmp_path):
    index = (gallery / "index.html").read_text(encoding="utf-8")
    assert re.search(r"\.card \.slug \{[^}]*overflow-wrap: anywhere", index)
    assert re.search(r"\.card \{[^}]*min-width: 0", index)  # a grid item may shrink
    if CHROMIUM is None:
        pytest.skip("chromium not installed (make test installs it)")
    probe = """<script>
    var bad = [], n = 0, widths = [];
    document.querySelectorAll(".card").forEach(function (card) {
      var c = card.getBoundingClientRect(), s = card.querySelector(".slug");
      if (!s) return; n++;
      var r = s.getBoundingClientRect();
      if (r.right > c.right + 0.5 || r.left < c.left - 0.5) bad.push(card.id);
      if (!card.classList.contains("wide")) widths.push(c.width);
    });
    /* no column grew to hold a long name: every one-column card is as wide as the others */
    if (Math.max.apply(null, widths) - Math.min.apply(null, widths) > 1) bad.push("widths");
    var d = document.createElement("div"); d.id = "probe";
    d.textContent = "cards=" + n + " bad=" + bad.join(",");
    document.body.appendChild(d);
    </script>"""
    page = gallery / "probe.html"
    page.write_text(index.replace("</body>", probe + "</body>"), encoding="utf-8")
    dom = subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={tmp_path / 'profile'}",
                          "--window-size=1200,900", "--virtual-time-budget=3000",
                          "--dump-dom", page.as_uri()],
                         capture_output=True, text=True, timeout=120).stdout
    found = re.search(r'id="probe">cards=(\d+) bad=([^<]*)<', dom)
    assert found, dom[-500:]
    assert int(found.group(1)) == 5 and found.group(2) == ""


def test_thumbnail_verdicts_are_kept_while_the_file_is_unchanged(gallery, tmp_path):
    """Each write of index.html sanitized every thumbnail again (0.3 s for 58 scenes in
    every edit-loop turn): the verdict is kept by the file's identity, so a figure changed
    after it passed is checked again, and a forged cache entry for another file is not
    taken."""
    from reportgen.pipeline.stages import THUMB_CACHE

    out = tmp_path / "out"
    shutil.copytree(gallery / "swing_a", out / "swing_a")
    write_index(str(out))
    thumbs = json.loads((out / THUMB_CACHE).read_text(encoding="utf-8"))
    assert thumbs["swing_a"]["safe"] is True
    assert 'src="swing_a/figures/phase_portrait-phase.svg"' in (out / "index.html").read_text()

    svg = out / "swing_a" / "figures" / "phase_portrait-phase.svg"
    svg.write_text(svg.read_text().replace("<svg ", "<svg onload=\"alert(1)\" ", 1))
    write_index(str(out))  # the file changed: checked again, refused
    assert json.loads((out / THUMB_CACHE).read_text())["swing_a"]["safe"] is False
    assert "no figure" in _card((out / "index.html").read_text(), "swing_a")

    forged = json.loads((out / THUMB_CACHE).read_text())
    forged["swing_a"]["safe"], forged["swing_a"]["key"][1] = True, 0  # another mtime
    (out / THUMB_CACHE).write_text(json.dumps(forged))
    write_index(str(out))
    assert "no figure" in _card((out / "index.html").read_text(), "swing_a")
