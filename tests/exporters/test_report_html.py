"""The HTML report: structure, self-containment, determinism, content, and a real browser.

The last test renders ``report.html`` in headless Chromium (Debian package ``chromium``; skipped
with a reason when it is absent): it measures every section and chart in the laid-out page,
takes a screenshot and checks that each chart's area of the screenshot is drawn (decoded here
with the standard library: zlib and the PNG filters).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import struct
import subprocess
import sys
import textwrap
import time
import zlib
from pathlib import Path

import lxml.html
import pytest

import rosaadl.library
from rosaadl.analysis import run_analyses, simulate
from rosaadl.errors import ExportError
from rosaadl.exporters.report import build_view, render_report, write_report
from rosaadl.importers.aadl_text import read_files
from rosaadl.transforms.instantiate import instantiate

SYSTEMS = Path(rosaadl.library.__file__).resolve().parent / "systems"
SECTIONS = ["findings", "architecture", "cpu", "bus", "schedule", "latency", "executors", "tables"]
CHARTS = {
    "architecture": "chart-architecture",
    "cpu": "chart-cpu",
    "bus": "chart-bus",
    "schedule": "chart-gantt",
    "latency": "chart-latency",
}
ROOTS = {"tracking": "sys_tracking::tracking.impl", "rover": "sys_rover::rover.impl"}


@pytest.fixture(scope="module")
def systems_model():
    return read_files([SYSTEMS])


@pytest.fixture(scope="module")
def analysed(systems_model):
    """name → (instance, report, html, json text) for the library's two systems."""
    out = {}
    for name, root in ROOTS.items():
        instance = instantiate(systems_model, root)
        report = run_analyses(instance)
        html, data = render_report(instance, report)
        out[name] = (instance, report, html, data)
    return out


def _doc(html: str):
    return lxml.html.document_fromstring(html)


def _drawn(svg) -> list:
    return [e for e in svg.iter() if isinstance(e.tag, str) and e.tag in ("rect", "path", "line", "text")]


# =============================================================================== structure


@pytest.mark.parametrize("name", sorted(ROOTS))
def test_every_section_and_chart_is_there(analysed, name):
    html = analysed[name][2]
    doc = _doc(html)
    assert [s.get("id") for s in doc.iter("section")] == SECTIONS
    for section in doc.iter("section"):
        assert section.find(".//h2") is not None and section.find(".//h2").text_content().strip()
    for section_id, css in CHARTS.items():
        section = doc.get_element_by_id(section_id)
        svgs = section.findall(".//svg")
        assert len(svgs) == 1, section_id
        svg = svgs[0]
        assert css in svg.get("class").split()
        width, height = float(svg.get("width")), float(svg.get("height"))
        assert width >= 1000 and height >= 80
        assert svg.get("viewbox") == f"0 0 {svg.get('width')} {svg.get('height')}"
        assert len(_drawn(svg)) >= 15, f"{section_id} chart draws almost nothing"
        assert svg.find("title") is not None and svg.find("title").text
    # the executors: chain bars and the executors' Gantt chart
    classes = [svg.get("class").split() for svg in doc.get_element_by_id("executors").findall(".//svg")]
    assert [c for c in classes if "chart-chains" in c] and [c for c in classes if "chart-executors" in c]
    # the tables behind the charts
    tables = doc.get_element_by_id("tables").findall(".//table")
    assert len(tables) >= 8
    assert all(len(t.findall(".//tbody/tr")) >= 1 for t in tables)


@pytest.mark.parametrize("name", sorted(ROOTS))
def test_no_external_resource_and_no_script(analysed, name):
    html = analysed[name][2]
    assert not re.search(r"https?:", html, re.IGNORECASE)
    assert "@import" not in html
    doc = _doc(html)
    for tag in ("script", "link", "img", "iframe", "object", "embed", "base", "audio", "video", "source"):
        assert not list(doc.iter(tag)), f"<{tag}> in the page"
    for element in doc.iter():
        if not isinstance(element.tag, str):
            continue
        for attribute, value in element.attrib.items():
            assert not attribute.lower().startswith("on"), f"event handler {attribute}"
            assert attribute.lower() not in ("src", "srcset", "xlink:href", "action", "formaction")
            if attribute.lower() == "href":
                assert value.startswith("#"), value
            assert "//" not in value or attribute == "d", (attribute, value)
            assert "javascript:" not in value.lower()
    for target in re.findall(r"url\(([^)]*)\)", html):
        assert target.startswith("#"), target


def test_json_holds_what_the_page_shows(analysed):
    instance, report, html, data = analysed["tracking"]
    view = json.loads(data)
    assert view["instance"] == "tracking_impl_Instance"
    assert view["ok"] is False and view["ok"] == report.ok
    assert view["analyses"] == json.loads(report.to_json())["analyses"]
    assert len(view["findings"]["errors"]) == len(report.errors)
    assert len(view["cpu"]) == len(report.cpu.processors)
    assert view["schedule"]["available"] and view["schedule"]["intervals"]
    assert {n["name"] for n in view["architecture"]["nodes"]} >= {"usbcam", "tracker", "poscmd"}
    doc = _doc(html)
    cpu_svg = doc.get_element_by_id("cpu").find(".//svg")
    labels = [t.text for t in cpu_svg.iter("text")]
    for row in view["cpu"]:
        assert row["label"].rpartition(".")[2] in labels


# =============================================================================== content


def test_overloaded_core_is_the_first_finding(analysed):
    _instance, _report, html, data = analysed["tracking"]
    doc = _doc(html)
    findings = doc.get_element_by_id("findings")
    verdict = findings.find_class("verdict")[0]
    assert "error" in verdict.get("class") and "problems found" in verdict.text_content()
    cards = {c.find_class("title")[0].text_content(): c for c in findings.find_class("card")}
    core = cards["Highest core load"]
    assert core.find_class("value")[0].text_content() == "111.0 %"
    assert "big_proc2" in core.text_content() and "1 overloaded" in core.text_content()
    assert "error" in core.get("class")
    assert any("exceeds MIPS capacity" in li.text_content() for li in findings.iter("li"))
    # the CPU chart hatches the part of big_proc2 beyond its capacity, and only that
    cpu_svg = doc.get_element_by_id("cpu").find(".//svg")
    hatched = [
        r for r in cpu_svg.iter("rect") if r.get("fill") == "url(#cpu-over)" and r.find("title") is not None
    ]
    assert len(hatched) == 1 and hatched[0].find("title").text == "11.00 % over capacity"
    assert any("overloaded" in t.text_content() for t in cpu_svg.iter("text"))
    # the Gantt chart marks every missed deadline of its window
    view = json.loads(data)
    misses = view["schedule"]["misses"]
    assert len(misses) == 3 and all(m["task"].endswith("image_tracker") for m in misses)
    gantt = doc.get_element_by_id("schedule").find(".//svg")
    markers = [
        p
        for p in gantt.iter("path")
        if p.get("fill") == "#c62828" and "missed its deadline" in p.text_content()
    ]
    assert len(markers) == 3
    # the overloaded core is outlined in red in the architecture diagram
    arch = doc.get_element_by_id("architecture").find(".//svg")
    assert any(r.get("stroke") == "#c62828" and "big_proc2" in r.text_content() for r in arch.iter("rect"))


def test_a_deployment_that_fits_passes(analysed):
    _instance, report, html, data = analysed["rover"]
    assert report.ok
    doc = _doc(html)
    verdict = doc.get_element_by_id("findings").find_class("verdict")[0]
    assert "ok" in verdict.get("class").split() and "All analyses pass" in verdict.text_content()
    cpu_svg = doc.get_element_by_id("cpu").find(".//svg")
    assert not [
        r for r in cpu_svg.iter("rect") if r.get("fill") == "url(#cpu-over)" and r.find("title") is not None
    ]
    assert json.loads(data)["schedule"]["deadline_misses"] == 0


def test_architecture_shows_nodes_topics_cores_and_bindings(analysed):
    html = analysed["tracking"][2]
    arch = _doc(html).get_element_by_id("architecture").find(".//svg")
    texts = {t.text for t in arch.iter("text")}
    assert {"usbcam", "tracker", "poscmd", "camera", "base"} <= texts
    assert {f"big_proc{i}" for i in range(1, 5)} | {f"little_proc{i}" for i in range(1, 5)} <= texts
    assert "/usb_cam/image_raw" in texts
    assert any("27.6 MB/s" in (t or "") for t in texts)
    bindings = [p for p in arch.iter("path") if p.get("stroke-dasharray") == "6 4"]
    assert len(bindings) == 3
    assert {"on big_proc1", "on big_proc2", "on little_proc1"} <= texts


def test_a_given_simulation_is_drawn_with_its_own_windows(analysed):
    instance, report, _html, _data = analysed["tracking"]
    simulation = simulate(instance)
    view = build_view(instance, report, simulation=simulation)
    assert view["schedule"]["note"] == "as simulated by the analyses"
    assert view["schedule"]["horizon"] == 100000
    html, _ = render_report(instance, report, simulation=simulation)
    gantt = _doc(html).get_element_by_id("schedule").find(".//svg")
    idle = [r for r in gantt.iter("rect") if r.get("fill") == "url(#gantt-idle)"]
    assert len(idle) == 2  # the two A15 cores were simulated over 33.3 ms only


def test_text_from_the_model_is_escaped(analysed):
    instance, report, _html, _data = analysed["rover"]
    title = "<script>alert('x')</script> & <b>co</b>"
    html, data = render_report(instance, report, title=title)
    assert "<script>" not in html and "<b>co</b>" not in html
    assert "&lt;script&gt;" in html
    doc = _doc(html)
    assert not list(doc.iter("script"))
    assert doc.find(".//h1").text_content() == title
    assert json.loads(data)["title"] == title


# =============================================================================== determinism


def test_same_input_same_bytes(analysed, tmp_path):
    instance, report, html, data = analysed["tracking"]
    again = render_report(instance, report)
    assert again == (html, data)
    first = write_report(instance, report, tmp_path / "a")
    second = write_report(instance, report, tmp_path / "b")
    assert [p.name for p in first] == ["report.html", "report.json"]
    for a, b in zip(first, second, strict=True):
        assert a.read_bytes() == b.read_bytes()
    assert first[0].read_text(encoding="utf-8") == html


def test_same_bytes_across_processes(tmp_path):
    script = textwrap.dedent(
        f"""
        import hashlib, sys
        from rosaadl.importers.aadl_text import read_files
        from rosaadl.transforms.instantiate import instantiate
        from rosaadl.analysis import run_analyses
        from rosaadl.exporters.report import render_report
        instance = instantiate(read_files([{str(SYSTEMS)!r}]), "sys_tracking::tracking.impl")
        html, data = render_report(instance, run_analyses(instance))
        print(hashlib.sha256((html + data).encode()).hexdigest())
        """
    )
    digests = set()
    for seed in ("0", "4242"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        done = subprocess.run(
            [sys.executable, "-c", script], capture_output=True, text=True, env=env, timeout=120, check=True
        )
        digests.add(done.stdout.strip())
    assert len(digests) == 1


# =============================================================================== writing


def test_write_report_refuses_a_file_and_leaves_nothing(analysed, tmp_path):
    instance, report, _html, _data = analysed["rover"]
    target = tmp_path / "taken"
    target.write_text("not a folder", encoding="utf-8")
    with pytest.raises(ExportError, match="not a folder"):
        write_report(instance, report, target)
    assert target.read_text(encoding="utf-8") == "not a folder"
    nested = tmp_path / "deep" / "er"
    written = write_report(instance, report, nested)
    assert sorted(p.name for p in nested.iterdir()) == ["report.html", "report.json"]
    assert all(p.parent == nested for p in written)


def test_write_report_keeps_the_old_files_when_rendering_fails(analysed, tmp_path):
    instance, _report, _html, _data = analysed["rover"]
    write_report(instance, analysed["rover"][1], tmp_path)
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    with pytest.raises(Exception):  # noqa: B017 - whatever a broken report raises
        write_report(instance, object(), tmp_path)
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


# =============================================================================== other models


def test_a_model_without_threads_still_gives_a_page(tmp_path):
    source = tmp_path / "bare.aadl"
    source.write_text(
        textwrap.dedent(
            """\
            package bare
            public
              processor cpu
              end cpu;
              system top
              end top;
              system implementation top.impl
                subcomponents
                  cpu1: processor cpu;
              end top.impl;
            end bare;
            """
        ),
        encoding="utf-8",
    )
    instance = instantiate(read_files([source]), "bare::top.impl")
    report = run_analyses(instance)
    html, data = render_report(instance, report)
    doc = _doc(html)
    assert [s.get("id") for s in doc.iter("section")] == SECTIONS
    assert "No schedule" in doc.get_element_by_id("schedule").text_content()
    assert "No bus in the model" in doc.get_element_by_id("bus").text_content()
    assert json.loads(data)["schedule"]["available"] is False


def _big_model(nodes: int, cores: int) -> str:
    lines = [
        "package big_demo",
        "public",
        "  data msg",
        "    properties",
        "      Data_Size => 64 Bytes;",
        "  end msg;",
        "  thread worker",
        "    features",
        "      i: in event data port msg;",
        "      o: out event data port msg;",
        "  end worker;",
        "  thread implementation worker.impl",
        "  end worker.impl;",
        "  process node",
        "    features",
        "      i: in event data port msg;",
        "      o: out event data port msg;",
        "  end node;",
        "  process implementation node.impl",
        "    subcomponents",
        "      w: thread worker.impl;",
        "    connections",
        "      c1: port i -> w.i;",
        "      c2: port w.o -> o;",
        "  end node.impl;",
        "  processor cpu",
        "  end cpu;",
        "  processor implementation cpu.impl",
        "    properties",
        "      SEI::MIPSCapacity => 1000.0 MIPS;",
        "  end cpu.impl;",
        "  system top",
        "  end top;",
        "  system implementation top.impl",
        "    subcomponents",
    ]
    lines += [f"      cpu{c}: processor cpu.impl;" for c in range(cores)]
    lines += [f"      n{i}: process node.impl;" for i in range(nodes)]
    lines += ["    connections"]
    lines += [f"      t{i}: port n{i}.o -> n{i + 1}.i;" for i in range(nodes - 1)]
    lines += ["    properties"]
    for i in range(nodes):
        lines += [
            f"      Period => {(10, 20, 40, 50)[i % 4]} ms applies to n{i}.w;",
            f"      Dispatch_Protocol => Periodic applies to n{i}.w;",
            f"      Compute_Execution_Time => {1 + i % 3} ms .. {1 + i % 3} ms applies to n{i}.w;",
            f"      Actual_Processor_Binding => (reference (cpu{i % cores})) applies to n{i};",
        ]
    lines += ["  end top.impl;", "end big_demo;", ""]
    return "\n".join(lines)


def test_a_large_model_wraps_and_stays_fast(tmp_path):
    source = tmp_path / "big.aadl"
    source.write_text(_big_model(60, 8), encoding="utf-8")
    instance = instantiate(read_files([source]), "big_demo::top.impl")
    report = run_analyses(instance)
    start = time.process_time()
    html, data = render_report(instance, report)
    elapsed = time.process_time() - start
    assert elapsed < 10, f"rendering took {elapsed:.1f} s"
    view = json.loads(data)
    assert len(view["architecture"]["nodes"]) == 60 and len(view["architecture"]["topics"]) == 59
    doc = _doc(html)
    arch = doc.get_element_by_id("architecture").find(".//svg")
    assert float(arch.get("width")) <= 1200  # the chain of 60 nodes wraps into bands
    assert float(arch.get("height")) > 1000
    names = {t.text for t in arch.iter("text")}
    assert {f"n{i}" for i in range(60)} <= names
    # with 60 threads, the legends name nodes, not threads, and say how many are left out
    cpu_texts = [t.text or "" for t in doc.get_element_by_id("cpu").find(".//svg").iter("text")]
    assert any(t.startswith("… and 30 more nodes") for t in cpu_texts)


def _corpus_models(corpus):
    files = sorted((corpus / "osate").rglob("*.aaxl2")) + sorted((corpus / "cheddar").glob("*.xml"))
    return [f for f in files if f.suffix == ".xml" or "/instances/" in f.as_posix()]


@pytest.mark.corpus
def test_every_corpus_instance_gives_a_complete_page(corpus):
    from rosaadl.importers.aaxl2 import read_aaxl2
    from rosaadl.importers.cheddar import load_cheddar

    files = _corpus_models(corpus)
    assert len(files) >= 20
    for path in files:
        model = read_aaxl2(path).model if path.suffix == ".aaxl2" else load_cheddar(path)
        report = run_analyses(model)
        html, data = render_report(model, report)
        doc = _doc(html)
        assert [s.get("id") for s in doc.iter("section")] == SECTIONS, path
        executor_charts = 2 if report.result("executor") is not None else 0  # chains, executors
        assert len(list(doc.iter("svg"))) == len(CHARTS) + executor_charts, path
        assert not re.search(r"https?:", html, re.IGNORECASE), path
        view = json.loads(data)
        assert view["ok"] == report.ok, path
        assert len(view["findings"]["errors"]) == len(report.errors), path


# =============================================================================== the browser


def _png_pixels(path: Path) -> tuple[int, int, list[bytes]]:
    """Width, height and RGB rows of an 8-bit RGB/RGBA PNG (non-interlaced), with the standard
    library only."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, chunks = 8, []
    width = height = channels = 0
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour, _c, _f, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and interlace == 0 and colour in (2, 6), (depth, colour, interlace)
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            chunks.append(body)
    raw = zlib.decompress(b"".join(chunks))
    stride = width * channels
    size = stride
    mask_low = int.from_bytes(b"\x7f" * size, "big")
    mask_high = int.from_bytes(b"\x80" * size, "big")

    def add(a: int, b: int) -> int:  # bytewise addition modulo 256 of two rows held as integers
        return ((a & mask_low) + (b & mask_low)) ^ ((a ^ b) & mask_high)

    rows: list[bytes] = []
    previous = bytes(stride)
    offset = 0
    for _ in range(height):
        kind = raw[offset]
        line = raw[offset + 1 : offset + 1 + stride]
        offset += 1 + stride
        if kind == 0:
            out = line
        elif kind == 2:
            out = add(int.from_bytes(line, "big"), int.from_bytes(previous, "big")).to_bytes(size, "big")
        elif kind == 1:  # prefix sums by doubling: log2(width) row additions
            value = int.from_bytes(line, "big")
            shift = channels
            while shift < stride:
                value = add(value, value >> (8 * shift))
                shift *= 2
            out = value.to_bytes(size, "big")
        else:
            cur = bytearray(line)
            for x in range(stride):
                a = cur[x - channels] if x >= channels else 0
                b = previous[x]
                if kind == 3:
                    cur[x] = (cur[x] + ((a + b) >> 1)) & 255
                else:
                    c = previous[x - channels] if x >= channels else 0
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    cur[x] = (cur[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
            out = bytes(cur)
        rows.append(out)
        previous = out
    if channels == 4:
        rows = [bytes(b for i, b in enumerate(r) if i % 4 != 3) for r in rows]
    return width, height, rows


def _region_stats(rows: list[bytes], x: int, y: int, w: int, h: int) -> tuple[int, float]:
    """(distinct colours, variance of the grey level) of a rectangle, sampled every 2 pixels."""
    colours = set()
    total = total_sq = count = 0
    for row in rows[y : y + h : 2]:
        for px in range(x, x + w, 2):
            r, g, b = row[3 * px], row[3 * px + 1], row[3 * px + 2]
            colours.add((r, g, b))
            grey = (r * 299 + g * 587 + b * 114) // 1000
            total += grey
            total_sq += grey * grey
            count += 1
    mean = total / max(count, 1)
    return len(colours), total_sq / max(count, 1) - mean * mean


_MEASURE = """
<script>
(function () {
  function box(e) {
    var r = e.getBoundingClientRect();
    return {x: r.left + window.scrollX, y: r.top + window.scrollY, w: r.width, h: r.height};
  }
  var out = {width: document.documentElement.scrollWidth, height: document.documentElement.scrollHeight,
             sections: [], svgs: []};
  document.querySelectorAll('section').forEach(function (s) {
    var b = box(s); b.id = s.id; out.sections.push(b);
  });
  document.querySelectorAll('svg').forEach(function (s) {
    var b = box(s), bb = s.getBBox();
    b.section = s.closest('section').id; b.bw = bb.width; b.bh = bb.height;
    b.drawn = s.querySelectorAll('rect,path,line,text').length;
    out.svgs.push(b);
  });
  var pre = document.createElement('pre');
  pre.id = 'rosaadl-measure';
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
})();
</script>
"""


def _chromium() -> str | None:
    for name in ("chromium", "chromium-browser"):
        found = shutil.which(name)
        if found:
            return found
    return None


def _run_chromium(binary: str, profile: Path, *args: str) -> subprocess.CompletedProcess:
    command = [
        binary,
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--no-first-run",
        "--hide-scrollbars",
        "--force-device-scale-factor=1",
        f"--user-data-dir={profile}",
        *args,
    ]
    return subprocess.run(command, capture_output=True, timeout=180, check=False)


@pytest.mark.slow
def test_report_renders_in_headless_chromium(analysed, tmp_path):
    binary = _chromium()
    if binary is None:
        pytest.skip("headless Chromium not installed (Debian: apt-get install -y chromium)")
    instance, report, _html, _data = analysed["tracking"]
    html_path, _json_path = write_report(instance, report, tmp_path / "out")
    profile = tmp_path / "profile"
    # 1. the page as Chromium parses it: every section and chart
    dom = _run_chromium(binary, profile, "--dump-dom", "--window-size=1280,2000", html_path.as_uri())
    assert dom.returncode == 0, dom.stderr.decode(errors="replace")[-2000:]
    parsed = _doc(dom.stdout.decode("utf-8"))
    assert [s.get("id") for s in parsed.iter("section")] == SECTIONS
    assert len(list(parsed.iter("svg"))) == len(CHARTS) + 2  # and the executors' two charts
    # 2. the laid-out page, measured by a script in a copy of it (the report itself has none)
    measured = html_path.with_name("measured.html")
    measured.write_text(
        html_path.read_text(encoding="utf-8").replace("</body>", _MEASURE + "</body>"), "utf-8"
    )
    run = _run_chromium(binary, profile, "--dump-dom", "--window-size=1280,2000", measured.as_uri())
    assert run.returncode == 0, run.stderr.decode(errors="replace")[-2000:]
    pre = _doc(run.stdout.decode("utf-8")).get_element_by_id("rosaadl-measure")
    layout = json.loads(pre.text_content())
    assert [s["id"] for s in layout["sections"]] == SECTIONS
    for section in layout["sections"]:
        assert section["w"] > 900 and section["h"] > 100, section
    assert layout["width"] <= 1280, "the page scrolls sideways"
    assert sorted(s["section"] for s in layout["svgs"]) == sorted([*CHARTS, "executors", "executors"])
    for svg in layout["svgs"]:
        assert svg["w"] > 900 and svg["h"] > 80, svg
        assert svg["bw"] > 500 and svg["bh"] > 50, svg  # what is drawn, not just the canvas
    # 3. the screenshot of the whole page: every chart's area is drawn, not blank
    height = int(layout["height"]) + 20
    shot = tmp_path / "report.png"
    run = _run_chromium(
        binary, profile, f"--screenshot={shot}", f"--window-size=1280,{height}", html_path.as_uri()
    )
    assert run.returncode == 0 and shot.is_file(), run.stderr.decode(errors="replace")[-2000:]
    width, shot_height, rows = _png_pixels(shot)
    assert (width, shot_height) == (1280, height)
    colours, variance = _region_stats(rows, 0, 0, width, shot_height)
    assert colours > 50 and variance > 100, "the screenshot is blank"
    for svg in layout["svgs"]:
        x, y = int(svg["x"]), int(svg["y"])
        w, h = int(svg["w"]), int(svg["h"])
        assert y + h <= shot_height
        colours, variance = _region_stats(rows, x, y, w, h)
        assert colours >= 8 and variance > 50, f"the {svg['section']} chart looks empty on screen"
    for section in layout["sections"]:
        colours, variance = _region_stats(rows, int(section["x"]), int(section["y"]), int(section["w"]), 60)
        assert variance > 50, f"the heading of {section['id']} is not drawn"
