"""The design report in Chromium and as a PDF: screenshots, the page count, tables that fit.

Starts ``beltstudy serve`` on a free loopback port with a temporary data directory, submits
``studies/report-failures.yaml`` (16 short runs of a loaded 3 % decline: runs that do not
stop, a drive rated far below the power it needs, a take-up too light to keep the drive from
slipping), waits for it, opens ``GET /studies/{id}/report`` in Debian's headless Chromium
(``/usr/bin/chromium`` with ``/usr/bin/chromedriver`` and selenium, the test extra) and

* saves ``docs/img/report-verdicts.png`` (section 1, the verdicts) and
  ``docs/img/report-failures.png`` (section 2, the runs that did not pass, by cause);
* checks, in print media at the width of an A4 page's content (210 mm less the report's
  2 x 12 mm margins = 186 mm = 703 CSS px), that no table is wider than the page, that the
  page scrolls nowhere sideways and that no table row is taller than 250 px;
* checks that section 2 lists each failure group the study has (did not stop, overloaded a
  drive, slipped on a drive pulley) with its count;
* prints the report with Chrome DevTools' ``Page.printToPDF`` (A4 from the page's
  ``@page`` rule) to ``test-artifacts/report.pdf`` (``--pdf``), counts its pages (pypdf when
  installed, else the ``/Type /Page`` objects) and checks there are at least two.

Usage::

    .venv/bin/python docs/report_pdf.py                 # its own service and study
    .venv/bin/python docs/report_pdf.py --html FILE     # a report saved with beltstudy report

With ``--html`` the report is any study's: the layout and PDF checks run, while the failure
groups (those of ``studies/report-failures.yaml``) are not asked for and the screenshots in
``docs/img`` (that study's) are left as they are.

Exit status 0 when every check passes, 1 otherwise (each failed check is printed).
"""

from __future__ import annotations

import argparse
import base64
import os
import re
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
IMG = ROOT / "docs" / "img"
STUDY = ROOT / "studies" / "report-failures.yaml"
#: A4 less the report's @page margins (12 mm each side), in CSS px (96 per inch).
PAGE_CONTENT_PX = round((210 - 2 * 12) / 25.4 * 96)
#: The tallest a table row may be in print [CSS px]: a quarter of the A4 content height
#: (about 1 020 px), so a page holds at least four rows, which are never split. A finding
#: prints whole with its fix (what would avoid it), which a fold would keep off the PDF.
ROW_MAX_PX = 250
#: The groups the study of ``studies/report-failures.yaml`` must show (title, fewest runs).
EXPECTED_GROUPS = ("did not stop", "overloaded a drive", "slipped on a drive pulley")


def driver():
    """Headless Chromium through chromedriver (selenium)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for arg in ("--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                "--disable-background-networking", "--disable-component-update",
                f"--user-data-dir={tempfile.mkdtemp(prefix='beltstudy-report-')}",
                "--window-size=1100,1000"):
        options.add_argument(arg)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def _section_shot(drv, section_id: str, path: Path, max_height: int = 4000) -> None:
    """A screenshot of one ``<section>`` of the report, the window tall enough to hold it."""
    height = drv.execute_script(
        f"return document.getElementById('{section_id}').getBoundingClientRect().height")
    drv.set_window_size(1100, int(min(max(height + 200, 800), max_height)))
    time.sleep(0.3)
    element = drv.find_element("id", section_id)
    path.parent.mkdir(parents=True, exist_ok=True)
    element.screenshot(str(path))
    drv.set_window_size(1100, 1000)
    print(f"wrote {path.relative_to(ROOT)}")


#: Measured in print media at the A4 content width: each table's width against the page.
_MEASURE = """
const page = document.documentElement.clientWidth;
const tables = Array.from(document.querySelectorAll('table')).map((t, i) => {
  const r = t.getBoundingClientRect();
  const rows = Array.from(t.rows).map(tr => tr.getBoundingClientRect().height);
  return {i: i, cls: t.className, width: r.width, right: r.right, scroll: t.scrollWidth,
          tallest: Math.max(0, ...rows), rows: rows.length};
});
return {page: page, scroll: document.documentElement.scrollWidth, tables: tables};
"""


def check_print_layout(drv) -> list[str]:
    """Problems of the page in print media at :data:`PAGE_CONTENT_PX` wide (empty: none)."""
    drv.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": "print"})
    drv.execute_cdp_cmd("Emulation.setDeviceMetricsOverride", {
        "width": PAGE_CONTENT_PX, "height": 1000, "deviceScaleFactor": 1, "mobile": False})
    try:
        time.sleep(0.3)
        m = drv.execute_script(_MEASURE)
    finally:
        drv.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})
        drv.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": ""})
    problems = []
    if m["scroll"] > m["page"] + 1:
        problems.append(f"the page is {m['scroll']} px wide in print, the A4 content "
                        f"{m['page']} px")
    for t in m["tables"]:
        if t["scroll"] > m["page"] + 1 or t["right"] > m["page"] + 1:
            problems.append(f"table {t['i']} ({t['cls'] or 'plain'}) is {t['scroll']:.0f} px "
                            f"wide, the A4 content {m['page']} px")
        if t["tallest"] > ROW_MAX_PX:
            problems.append(f"table {t['i']} ({t['cls'] or 'plain'}) has a row "
                            f"{t['tallest']:.0f} px tall (at most {ROW_MAX_PX})")
    print(f"print layout at {m['page']} px (A4 content width): {len(m['tables'])} tables, "
          f"widest {max((t['scroll'] for t in m['tables']), default=0):.0f} px, tallest row "
          f"{max((t['tallest'] for t in m['tables']), default=0):.0f} px")
    return problems


def check_groups(drv) -> list[str]:
    """Section 2 names every expected failure group with a count."""
    text = drv.find_element("id", "s2").text
    problems = []
    for title in EXPECTED_GROUPS:
        m = re.search(rf"(\d+) of (\d+) runs {re.escape(title)}", text)
        if not m or int(m.group(1)) < 1:
            problems.append(f"section 2 does not list the group '{title}' with a count")
        else:
            print(f"group '{title}': {m.group(1)} of {m.group(2)} runs")
    return problems


def page_count(pdf: bytes) -> int:
    """Pages of a PDF: pypdf when installed, else the ``/Type /Page`` objects."""
    try:
        import io

        from pypdf import PdfReader

        return len(PdfReader(io.BytesIO(pdf)).pages)
    except ImportError:
        return len(re.findall(rb"/Type\s*/Page(?![a-zA-Z])", pdf))


def print_pdf(drv, path: Path | None) -> tuple[bytes, int]:
    """The page printed by Chrome DevTools' ``Page.printToPDF`` (the page's @page size and
    margins, backgrounds on) and its page count."""
    out = drv.execute_cdp_cmd("Page.printToPDF", {"preferCSSPageSize": True,
                                                   "printBackground": True})
    pdf = base64.b64decode(out["data"])
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(pdf)
        print(f"wrote {path.relative_to(ROOT) if path.is_relative_to(ROOT) else path}")
    return pdf, page_count(pdf)


def inspect(url: str, pdf_path: Path | None, shots: bool = True, drv=None,
            groups: bool = True) -> list[str]:
    """Every check of the report at ``url``; the problems found (empty: it passes).
    ``drv``: a selenium Chrome driver to use (default: a new one, closed at the end);
    ``groups``: ask for the shipped study's failure groups (:data:`EXPECTED_GROUPS`)."""
    own = drv is None
    drv = driver() if own else drv
    try:
        drv.get(url)
        t0 = time.monotonic()
        while not drv.execute_script(
                "return Array.from(document.images).every(i => i.complete && i.naturalWidth)"):
            if time.monotonic() - t0 > 60:
                return ["the report's figures did not load"]
            time.sleep(0.2)
        problems = []
        if shots:
            _section_shot(drv, "s1", IMG / "report-verdicts.png")
            _section_shot(drv, "s2", IMG / "report-failures.png")
        if groups:
            problems += check_groups(drv)
        problems += check_print_layout(drv)
        pdf, pages = print_pdf(drv, pdf_path)
        print(f"PDF: {pages} A4 pages, {len(pdf) / 1024:.0f} KiB")
        if not pdf.startswith(b"%PDF") or pages < 2:
            problems.append(f"the PDF has {pages} pages")
        return problems
    finally:
        if own:
            drv.quit()


def run_study() -> tuple[str, str, object, Path]:
    """``beltstudy serve`` on a temporary data directory with the study done: (base URL,
    study id, the server process, the temporary directory)."""
    from beltstudy.service.cli.client import ServiceClient
    from beltstudy.service.cli.demo import free_port, start_server, wait_ready
    from beltstudy.service.door.studyfile import study_body

    tmp = Path(tempfile.mkdtemp(prefix="beltstudy-report-pdf-"))
    port = free_port()
    env = {"BELTSTUDY_DATA_DIR": str(tmp / "data"), "BELTSTUDY_WORKERS": "1",
           "BELTSTUDY_STUDIES_DIR": str(ROOT / "studies"), "BELTSTUDY_TOKEN": "",
           "BELTSTUDY_SCHEDULER": "", "NUMBA_NUM_THREADS": os.environ.get(
               "NUMBA_NUM_THREADS", "1")}
    log = open(tmp / "server.log", "wb")
    proc = start_server(port, env=env, log=log)
    base = f"http://127.0.0.1:{port}"
    with ServiceClient(base) as client:
        wait_ready(client, proc, timeout_s=600)
        st, _ = client.submit(study_body(str(STUDY)))
        t0 = time.monotonic()
        while st["state"] in ("queued", "running"):
            if time.monotonic() - t0 > 1200:
                raise TimeoutError("the study did not finish in 20 min")
            time.sleep(1.0)
            st = client.status(st["id"])
        print(f"study {st['id']}: {st['state']}, {st['done']} runs, {st['failed']} failed")
    return base, st["id"], proc, tmp


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--html", type=Path, help="check this saved report instead")
    parser.add_argument("--pdf", type=Path, default=ROOT / "test-artifacts" / "report.pdf",
                        help="where the PDF goes (default test-artifacts/report.pdf)")
    parser.add_argument("--no-screenshots", action="store_true")
    args = parser.parse_args(argv)
    shots = not args.no_screenshots
    if args.html:
        # any study's report: not the shipped study's groups, nor its screenshots in docs/img
        problems = inspect(args.html.resolve().as_uri(), args.pdf, shots=False, groups=False)
    else:
        from beltstudy.service.cli.demo import stop_server

        base, sid, proc, tmp = run_study()
        try:
            problems = inspect(f"{base}/studies/{sid}/report", args.pdf, shots)
        finally:
            stop_server(proc)
            shutil.rmtree(tmp, ignore_errors=True)
    for p in problems:
        print("FAILED:", p)
    print("every check passed" if not problems else f"{len(problems)} checks failed")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
